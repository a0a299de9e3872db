// SPDX-License-Identifier: Apache-2.0
#pragma once
// Physical and GPS constants. Sources: IS-GPS-200 Table 20-IV, WGS-84
// (NIMA TR8350.2). See shared/reference/gps-orbits.md §1.

namespace gnssemu {

inline constexpr double kSpeedOfLight_m_s = 299792458.0;
/// WGS-84 gravitational constant used by GPS (IS-GPS-200 Table 20-IV), m^3/s^2.
inline constexpr double kMuGps_m3_s2 = 3.986005e14;
/// WGS-84 Earth rotation rate, rad/s.
inline constexpr double kOmegaEarth_rad_s = 7.2921151467e-5;
/// Pi as the GPS curve fit uses it (IS-GPS-200 §20.3.3.4.3); for semicircles.
inline constexpr double kPiGps = 3.1415926535898;
/// Relativistic clock constant F = -2 sqrt(mu) / c^2, s/m^0.5 (IS-GPS-200 §20.3.3.3.3.1).
inline constexpr double kRelativityF_s_sqrtm = -4.442807633e-10;
/// GPS L1 carrier, Hz, and wavelength, m.
inline constexpr double kL1Freq_hz = 1575.42e6;
inline constexpr double kL1Wavelength_m = kSpeedOfLight_m_s / kL1Freq_hz;
/// L1 C/A code chipping rate, chip/s (IS-GPS-200: 1.023 Mbps), and chip length, m.
inline constexpr double kCaChipRate_hz = 1.023e6;
inline constexpr double kCaChip_m = kSpeedOfLight_m_s / kCaChipRate_hz;
/// WGS-84 ellipsoid.
inline constexpr double kWgs84A_m = 6378137.0;
inline constexpr double kWgs84F = 1.0 / 298.257223563;

inline constexpr double kSecondsPerWeek = 604800.0;
inline constexpr double kHalfWeek_s = 302400.0;
inline constexpr double kSecondsPerDay = 86400.0;

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegToRad = kPi / 180.0;
inline constexpr double kRadToDeg = 180.0 / kPi;

}  // namespace gnssemu

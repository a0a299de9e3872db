// SPDX-License-Identifier: Apache-2.0
#pragma once
// The system table: one row of facts per satellite system, in the style of
// RTKLIB's per-system tables, so that a system is a row and not a hunt.
// Sources per column: shared/reference/multi-gnss.md §1 (frequencies, ranges),
// §1.1 (orbit constants), §1.2 (time scales), §6 (ephemeris age: RTKLIB
// 2.4.3 MAXDTOE*), §7-8 (NMEA talkers and system ids, UBX gnssId).
#include <array>
#include <cstddef>
#include <cstdint>

#include "core/common/sat_id.hpp"

namespace gnssemu {

/// Time scale a system's broadcast times are given in.
enum class TimeScale : uint8_t {
  kGpst,      ///< GPS time (GPS, QZSS, SBAS)
  kGst,       ///< Galileo system time: GPST, weeks counted from GPS week 1024
  kBdt,       ///< BeiDou time: GPST - 14 s, weeks from GPS week 1356
  kGlonasst,  ///< UTC(SU) + 3 h: has leap seconds
};

/// How the broadcast orbit is given.
enum class OrbitKind : uint8_t {
  kKepler,       ///< Keplerian elements with harmonic corrections (GPS, Galileo, BeiDou, QZSS)
  kStateVector,  ///< position, velocity, acceleration at tb, integrated (GLONASS)
  kSbasPoly,     ///< position, velocity, acceleration polynomial (SBAS)
};

struct SystemInfo {
  GnssSystem system;
  TimeScale time_scale;
  OrbitKind orbit;
  /// L1-band civil carrier the single-frequency user tracks, Hz; GLONASS:
  /// the channel-0 carrier, channel k adds k * l1_step_hz (FDMA).
  double l1_freq_hz;
  double l1_step_hz;
  /// Gravitational constant and Earth rotation rate in the system's own
  /// broadcast-orbit formulas, m^3/s^2 and rad/s.
  double mu_m3_s2;
  double omega_e_rad_s;
  /// Largest |t - toe| an ephemeris is used for, s (RTKLIB 2.4.3 MAXDTOE*).
  double max_ephemeris_age_s;
  uint8_t ubx_gnss_id;     ///< UBX gnssId (0 GPS, 1 SBAS, 2 Galileo, 3 BeiDou, 5 QZSS, 6 GLONASS)
  uint8_t nmea_system_id;  ///< NMEA 4.10 GSA system id (1 GPS, 2 GLONASS, 3 Galileo, 4 BeiDou, 5 QZSS; SBAS reports as GPS)
  char nmea_talker[3];     ///< talker of a single-system sentence ("GP", "GL", "GA", "GB", "GQ")
};

/// GLONASS FDMA channels k: -7..+6 (ICD GLONASS Ed. 5.1).
inline constexpr int kGlonassMinChannel = -7;
inline constexpr int kGlonassMaxChannel = 6;

inline constexpr std::array<SystemInfo, kNumSystems> kSystems{{
    {GnssSystem::kGps, TimeScale::kGpst, OrbitKind::kKepler, 1575.42e6, 0.0, 3.986005e14, 7.2921151467e-5, 7200.0, 0, 1,
     "GP"},
    {GnssSystem::kGlonass, TimeScale::kGlonasst, OrbitKind::kStateVector, 1602.0e6, 0.5625e6, 3.986004418e14, 7.292115e-5,
     1800.0, 6, 2, "GL"},
    {GnssSystem::kGalileo, TimeScale::kGst, OrbitKind::kKepler, 1575.42e6, 0.0, 3.986004418e14, 7.2921151467e-5, 14400.0,
     2, 3, "GA"},
    {GnssSystem::kBeiDou, TimeScale::kBdt, OrbitKind::kKepler, 1561.098e6, 0.0, 3.986004418e14, 7.292115e-5, 21600.0, 3,
     4, "GB"},
    {GnssSystem::kQzss, TimeScale::kGpst, OrbitKind::kKepler, 1575.42e6, 0.0, 3.986005e14, 7.2921151467e-5, 7200.0, 5, 5,
     "GQ"},
    {GnssSystem::kSbas, TimeScale::kGpst, OrbitKind::kSbasPoly, 1575.42e6, 0.0, 3.986005e14, 7.2921151467e-5, 360.0, 1, 1,
     "GP"},
}};

constexpr const SystemInfo& system_info(GnssSystem s) noexcept { return kSystems[static_cast<std::size_t>(s)]; }

/// L1-band carrier of a satellite, Hz; glonass_channel is used for GLONASS only.
constexpr double l1_carrier_hz(GnssSystem s, int glonass_channel = 0) noexcept {
  return system_info(s).l1_freq_hz + glonass_channel * system_info(s).l1_step_hz;
}

/// BeiDou GEO satellites (C01-C05, C59-C63): their broadcast orbit needs the
/// GEO transformation (BDS-SIS-ICD-B1I 3.0; multi-gnss.md §4).
constexpr bool is_beidou_geo(SatId id) noexcept {
  return id.system == GnssSystem::kBeiDou && (id.number <= 5 || id.number >= 59);
}

static_assert(kSystems[0].system == GnssSystem::kGps && kSystems[5].system == GnssSystem::kSbas);

}  // namespace gnssemu

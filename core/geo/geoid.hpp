// SPDX-License-Identifier: Apache-2.0
#pragma once
// Geoid height N (EGM2008) from an embedded 5 deg x 5 deg grid, so that the
// receiver can report MSL height H = h - N as a real receiver does (NMEA GGA
// fields 9 and 11, UBX hMSL). No data files are needed at run time.
//
// Accuracy: bilinear interpolation on a 5 deg grid misses the geoid's
// shorter wavelengths. Against independently known values (u-blox, Trimble
// and B&G receivers' own GGA / NAV-PVT separations, RTKLIB's 1 deg EGM96,
// GeographicLib's EGM96 at Timbuktu; 12 places, see docs/models.md "Geoid")
// the difference is 1.9 m RMS, 3.3 m at most. Expect several metres more in
// steep regions (trenches, high mountains, e.g. Indonesia, Andes).

namespace gnssemu::geo {

/// Geoid height above the WGS-84 ellipsoid, m (MSL height = ellipsoidal
/// height - N), at geodetic latitude lat_rad (rad; values beyond +-pi/2 are
/// clamped to the pole) and longitude lon_rad (rad; any value, wrapped).
/// Bilinear in latitude and longitude degrees between the grid nodes, which
/// it reproduces exactly. NaN or infinite input gives 0. Never allocates.
double geoid_separation_m(double lat_rad, double lon_rad) noexcept;

}  // namespace gnssemu::geo

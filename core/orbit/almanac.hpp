// SPDX-License-Identifier: Apache-2.0
#pragma once
// GPS almanacs: YUMA (radians) and SEM (semicircles) readers and almanac
// propagation (IS-GPS-200 §20.3.3.5.2.1). Km-level: for visibility only.
#include <string>
#include <vector>

#include "core/orbit/ephemeris.hpp"

namespace gnssemu::orbit {

struct AlmanacEntry {
  SatId sat;  ///< GPS satellite
  int health = 0;
  double e = 0.0;
  time::GpsTime toa;            ///< full week resolved against the reader's reference week
  double i0_rad = 0.0;          ///< full inclination (SEM offset already added)
  double omega_dot_rad_s = 0.0;
  double sqrt_a_sqrtm = 0.0;
  double omega0_rad = 0.0;
  double omega_rad = 0.0;
  double m0_rad = 0.0;
  double af0_s = 0.0;
  double af1_s_s = 0.0;
};

/// reference_week: full GPS week near the almanac's date, used to resolve the
/// truncated (mod 1024) week. Throws gnssemu::Error with file:line on bad input.
std::vector<AlmanacEntry> read_yuma(const std::string& path, int reference_week);
std::vector<AlmanacEntry> read_sem(const std::string& path, int reference_week);
/// YUMA or SEM, told apart by the content (a YUMA file starts with a
/// "****" block header, a SEM file with its record count).
std::vector<AlmanacEntry> read_almanac(const std::string& path, int reference_week);

/// The almanac as an Ephemeris (zero harmonic terms) for sat_state().
Ephemeris to_ephemeris(const AlmanacEntry& alm) noexcept;
/// Position/velocity/clock from an almanac at time t (no relativistic term).
SatState almanac_state(const AlmanacEntry& alm, const time::GpsTime& t) noexcept;

}  // namespace gnssemu::orbit

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Contents of a navigation message file: the ephemerides of every system
// plus the header's broadcast ionosphere, UTC, GLONASS time correction and
// leap-second parameters.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/common/sat_id.hpp"
#include "core/orbit/ephemeris.hpp"

namespace gnssemu::orbit {

/// Broadcast Klobuchar coefficients (IS-GPS-200 §20.3.3.5.2.5).
struct KlobucharParams {
  std::array<double, 4> alpha{};  ///< s, s/semicircle, s/semicircle^2, s/semicircle^3
  std::array<double, 4> beta{};   ///< s, s/semicircle, s/semicircle^2, s/semicircle^3
  bool valid = false;             ///< false when the file had none
};

/// GPS -> UTC polynomial (RINEX 2 DELTA-UTC, RINEX 3 GPUT).
struct UtcParams {
  double a0_s = 0.0;
  double a1_s_s = 0.0;
  double tot_s = 0.0;   ///< reference time, s of week
  int wnt = 0;          ///< reference week (continuous)
  bool valid = false;
};

/// Galileo NeQuick G broadcast coefficients (RINEX 3 IONOSPHERIC CORR GAL).
struct NequickParams {
  std::array<double, 3> ai{};  ///< ai0 sfu, ai1 sfu/deg, ai2 sfu/deg^2
  bool valid = false;
};

struct NavData {
  std::string source;                ///< file name it was read from
  double rinex_version = 0.0;
  std::vector<Ephemeris> ephemerides;  ///< every system, in file order
  KlobucharParams klobuchar;         ///< GPS (GPSA/GPSB, RINEX 2 ION ALPHA/BETA)
  KlobucharParams beidou_klobuchar;  ///< BeiDou (BDSA/BDSB; the first of a merged file's per-satellite lines)
  NequickParams galileo_nequick;     ///< Galileo (GAL)
  UtcParams utc;                     ///< GPS - UTC
  /// GLONASS time scale correction tau_c as a0 (RINEX 3 GLUT; RINEX 2 CORR
  /// TO SYSTEM TIME, whose sign is -tau_c), s; UTC(SU) - GLONASST + 3 h.
  UtcParams glonass_utc;
  std::optional<int> leap_seconds;   ///< GPS - UTC from the header, if present
  int skipped_records = 0;           ///< records of systems not handled (I/NavIC, ...), skipped
};

/// Several files as one: every file's ephemerides (the store sorts them and
/// resolves duplicates); each header parameter from the first file that has
/// it; the leap-second count if every file that gives one agrees (else
/// none: the built-in table decides); source names joined with " + ".
NavData merge(const std::vector<NavData>& files);

/// The systems nav holds at least one ephemeris of.
SystemSet systems_of(const NavData& nav) noexcept;

}  // namespace gnssemu::orbit

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Differential corrections as a rover holds them: the reference station's
// latest observation epoch and its antenna position, decoded from RTCM 3
// (MSM4/MSM7, 1005/1006, 1230, 4072; RTCM 10403.3 §3.5;
// shared/reference/rtk-raw.md §2). Plain data: the RTCM decoder fills it from
// a host's bytes, or a test or a fleet's moving base fills it directly; the
// receiver's RTK stage only reads it.
#include <array>
#include <cstdint>

#include "core/common/vec3.hpp"
#include "core/receiver/raw_measurements.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::receiver {

/// The reference station (1005/1006, or the moving base's 4072.0).
struct ReferenceStation {
  int station_id = 0;                 ///< DF003, 0..4095
  bool position_valid = false;        ///< a 1005/1006 (or 4072.0) arrived
  Ecef arp_ecef_m;                    ///< antenna reference point, ECEF m (DF025-DF027)
  double antenna_height_m = 0.0;      ///< 1006 DF028, m (0 for 1005)
  /// The reference moves (a moving-baseline base: 4072.0 received): the rover
  /// solves the baseline only, not an absolute RTK position.
  bool moving = false;
  time::GpsTime position_time;        ///< rover time the position arrived (GPS)
};

/// Everything a rover has from its correction link.
struct Corrections {
  ReferenceStation station;
  /// The base's latest complete observation epoch (the MSMs of every system
  /// with the same epoch time, merged; obs.t_rx is the base's epoch, GPS).
  RawEpoch obs;
  bool obs_valid = false;
  int obs_station_id = 0;             ///< DF003 of obs's MSMs (a rover pairs it with station.station_id)
  time::GpsTime obs_received;         ///< rover time the epoch became complete (GPS)
  /// 1230 GLONASS code-phase biases, m: L1 C/A, L1 P, L2 C/A, L2 P (DF423-DF426);
  /// 0 when not sent.
  std::array<double, 4> glonass_cpb_m{};
  /// DF421: the base's GLONASS phase ranges are code-phase aligned already
  /// (u-blox F9 bases: aligned, no bias fields; docs/base-station.md).
  bool glonass_cpb_aligned = false;
  /// 1230 received and usable: aligned, or its biases align it.
  bool glonass_cpb_valid = false;
  /// Incremented whenever obs or station changes: the RTK stage processes a
  /// base epoch once.
  std::uint32_t revision = 0;
};

}  // namespace gnssemu::receiver

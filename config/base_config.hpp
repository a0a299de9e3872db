// SPDX-License-Identifier: Apache-2.0
#pragma once
// [base]: a static reference receiver whose observations leave as RTCM 3
// (docs/base-station.md): where it stands, its receiver settings (the top
// level's, overridden like a [[vehicle.receiver]]), the messages and their
// intervals, and where they go (an NTRIP caster endpoint).
#include <string>
#include <vector>

#include "core/common/vec3.hpp"

namespace gnssemu::config {

/// One RTCM message the base sends and how often.
struct BaseMessage {
  int number = 0;           ///< 1005, 1006, 1230, 107x..112x MSM4/7, 1019, 1020, 1042, 1046
  double interval_s = 1.0;  ///< > 0; MSMs every epoch of the base's rate at most
  int line = 0;             ///< config line (for messages)
};

/// Message numbers [base] messages accepts, in the order of the docs.
inline constexpr int kBaseMessageNumbers[] = {1005, 1006, 1230, 1074, 1077, 1084, 1087, 1094, 1097,
                                              1114, 1117, 1124, 1127, 1019, 1020, 1042, 1046};

/// The NTRIP caster endpoint of a base (NTRIP v1 and v2 on loopback).
struct NtripCasterConfig {
  bool enabled = false;
  int port = 2101;              ///< TCP port on 127.0.0.1 (0: any free port)
  std::string mountpoint = "GNSSEMU";
  std::string user;             ///< "" = no credentials asked
  std::string password;
};

/// Farther than this from the rover's origin the loader warns: the ZED-F9P
/// rover reports INF-WARNING "DGNSS baseline big" beyond 50 km (ZED-F9P
/// Integration Manual R08 §3.1.5.4; shared/reference/rtk-raw.md §2.6).
inline constexpr double kBaseWarnDistance_m = 50e3;

}  // namespace gnssemu::config

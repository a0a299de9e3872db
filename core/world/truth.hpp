// SPDX-License-Identifier: Apache-2.0
#pragma once
// Vehicle truth at the antenna: what the world is computed for. The receiver
// never sees it; it sees only the observables the world makes of it.
#include "core/common/vec3.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::world {

/// Truth at time t.
struct Truth {
  time::GpsTime t;
  Ecef pos_m;       ///< antenna position, ECEF m
  Ecef vel_m_s;     ///< antenna velocity, ECEF m/s
  bool valid = false;  ///< false: no truth (antenna lost) -> no signals
};

}  // namespace gnssemu::world

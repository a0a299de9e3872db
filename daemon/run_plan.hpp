// SPDX-License-Identifier: Apache-2.0
#pragma once
// What gnssemud runs on, decided before any port opens (and by
// --check-config): the epoch clock's start and the satellites for it.
#include "config/config.hpp"
#include "core/orbit/constellation.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::daemon {

/// GPS time of the system clock now (today's leap seconds, utc.hpp table).
time::GpsTime system_clock_gps();

struct RunPlan {
  time::GpsTime start;                 ///< GPS time of the first epoch
  orbit::Constellation constellation;  ///< the satellites, dated for the run
};

/// start: time.start; today with use_wall_clock_date (now rounded up to a
/// whole GPS second); else the nav data's first toe + 1 h. The constellation
/// is nav dated by [nav] mode for that start. Throws gnssemu::Error naming
/// the nav data's coverage when the start cannot be served.
RunPlan plan_run(const config::Config& cfg, const orbit::NavData& nav, const time::GpsTime& now);

}  // namespace gnssemu::daemon

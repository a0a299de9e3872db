// SPDX-License-Identifier: Apache-2.0
#include "daemon/run_plan.hpp"

#include <chrono>

#include "config/setup/nav_setup.hpp"
#include "core/time/unix_time.hpp"
#include "daemon/truth/time_mapping.hpp"

namespace gnssemu::daemon {

time::GpsTime system_clock_gps() {
  const auto now = std::chrono::system_clock::now();
  return time::gps_from_unix(std::chrono::duration<double>(now.time_since_epoch()).count());
}

RunPlan plan_run(const config::Config& cfg, const orbit::NavData& nav, const time::GpsTime& now) {
  RunPlan p;
  p.start = run_start(cfg.time.start, cfg.time.use_wall_clock_date, nav.ephemerides, now);
  p.constellation = config::make_constellation(cfg, nav, p.start);
  return p;
}

}  // namespace gnssemu::daemon

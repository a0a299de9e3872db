// SPDX-License-Identifier: Apache-2.0
#include "daemon/truth/time_mapping.hpp"

#include <cmath>

namespace gnssemu::daemon {
namespace {

constexpr double kSettle_s = 3600.0;

}  // namespace

time::GpsTime first_toe_plus_hour(const std::vector<orbit::Ephemeris>& ephemerides) {
  if (ephemerides.empty()) return {};
  time::GpsTime first = ephemerides.front().toe;
  for (const auto& e : ephemerides)
    if (e.toe < first) first = e.toe;
  return first + kSettle_s;
}

time::GpsTime run_start(const std::optional<time::GpsTime>& start, bool wall_clock,
                        const std::vector<orbit::Ephemeris>& ephemerides, const time::GpsTime& now) {
  if (start) return *start;
  if (wall_clock) return whole_second_start(now).start;
  return first_toe_plus_hour(ephemerides);
}

WholeSecondStart whole_second_start(const time::GpsTime& now) noexcept {
  const double tow = now.tow_s();
  double wait = std::ceil(tow) - tow;
  if (!(wait >= 0.0 && wait < 1.0)) wait = 0.0;  // non-finite input: leave it
  WholeSecondStart w;
  w.start = time::GpsTime::make(now.week(), std::ceil(tow)).value_or(now);  // 604800 carries into the next week
  w.wait_s = wait;
  return w;
}

SimClockMap::Mapped SimClockMap::map(double sim_time_s, const time::GpsTime& arrival) noexcept {
  if (anchored_) {
    const time::GpsTime t = to_gps(sim_time_s);
    if (std::abs(t - arrival) <= threshold_s_) return {t, false};
  }
  anchor(sim_time_s, arrival);
  return {arrival, true};
}

void SimClockMap::anchor(double sim_time_s, const time::GpsTime& gps) noexcept {
  anchored_ = true;
  anchor_sim_s_ = sim_time_s;
  anchor_gps_ = gps;
}

}  // namespace gnssemu::daemon

#include "daemon/time_mapping.hpp"

#include <algorithm>
#include <cmath>

namespace gnssemu::daemon {
namespace {

constexpr double kSettle_s = 3600.0;

bool toe_range(const std::vector<orbit::Ephemeris>& ephs, time::GpsTime& first, time::GpsTime& last) {
  if (ephs.empty()) return false;
  first = last = ephs.front().toe;
  for (const auto& e : ephs) {
    if (e.toe < first) first = e.toe;
    if (e.toe > last) last = e.toe;
  }
  return true;
}

}  // namespace

Coverage default_coverage(const std::vector<orbit::Ephemeris>& ephemerides) {
  time::GpsTime first, last;
  if (!toe_range(ephemerides, first, last)) return {};
  Coverage c;
  c.start = first + kSettle_s;
  c.span_s = std::max(0.0, last - c.start);
  return c;
}

Coverage coverage_from(const time::GpsTime& start, const std::vector<orbit::Ephemeris>& ephemerides) {
  Coverage c;
  c.start = start;
  time::GpsTime first, last;
  if (toe_range(ephemerides, first, last) && last - start > kSettle_s) c.span_s = last - start;
  return c;
}

WholeSecondStart whole_second_start(const time::GpsTime& now) noexcept {
  const double tow = now.tow_s();
  double wait = std::ceil(tow) - tow;
  if (!(wait >= 0.0 && wait < 1.0)) wait = 0.0;  // non-finite input: leave it
  WholeSecondStart w;
  w.start = time::GpsTime(now.week(), std::ceil(tow));  // 604800 carries into the next week
  w.wait_s = wait;
  return w;
}

EpochTime realtime_gps_time(const Coverage& coverage, double elapsed_s) noexcept {
  EpochTime out;
  if (coverage.span_s <= 0.0 || elapsed_s < coverage.span_s) {
    out.t = coverage.start + elapsed_s;
    return out;
  }
  const double wraps = std::floor(elapsed_s / coverage.span_s);
  out.wraps = static_cast<int64_t>(wraps);
  out.t = coverage.start + (elapsed_s - wraps * coverage.span_s);
  return out;
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

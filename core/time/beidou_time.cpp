// SPDX-License-Identifier: Apache-2.0
#include "core/time/beidou_time.hpp"

namespace gnssemu::time {

WeekTime bdt_from_gps(const GpsTime& t) noexcept {
  // BDT expressed on the GPS week grid: its weeks start 14 s after GPS's.
  const GpsTime b = t - kGpsMinusBdt_s;
  return {b.week() - kBdtWeekOrigin, b.tow_s()};
}

GpsTime gps_from_bdt(const WeekTime& bdt) { return GpsTime(bdt.week + kBdtWeekOrigin, bdt.tow_s) + kGpsMinusBdt_s; }

}  // namespace gnssemu::time

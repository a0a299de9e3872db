// SPDX-License-Identifier: Apache-2.0
#include "core/time/glonass_time.hpp"

#include <algorithm>
#include <cmath>

#include "core/common/error.hpp"
#include "core/time/utc.hpp"

namespace gnssemu::time {

namespace {
constexpr int kDaysPerCycle = 3 * 365 + 366;

/// Days since 1970-01-01 of day 1 of interval n4.
int64_t cycle_start_days(int n4) noexcept { return days_from_civil(kGlonassFirstCycleYear + 4 * (n4 - 1), 1, 1); }
}  // namespace

CalendarTime glonass_calendar(const GpsTime& t, std::optional<int> leap_s) {
  const bool inserting = leap_s ? false : in_inserted_leap_second(t);
  CalendarTime c = gps_to_utc(t, leap_s, inserting);
  // +3 h on the calendar keeps a leap second's 60.x: 23:59:60 UTC is 02:59:60.
  int64_t days = days_from_civil(c.year, c.month, c.day);
  c.hour += 3;
  if (c.hour >= 24) {
    c.hour -= 24;
    ++days;
  }
  civil_from_days(days, c.year, c.month, c.day);
  return c;
}

GlonassTime glonass_from_gps(const GpsTime& t, std::optional<int> leap_s) {
  const CalendarTime c = glonass_calendar(t, leap_s);
  const int64_t days = days_from_civil(c.year, c.month, c.day);
  const int cycle = static_cast<int>(std::floor(static_cast<double>(c.year - kGlonassFirstCycleYear) / 4.0));
  GlonassTime g;
  g.n4 = cycle + 1;
  g.nt = static_cast<int>(days - cycle_start_days(g.n4)) + 1;
  g.tod_s = c.hour * 3600.0 + c.minute * 60.0 + c.second;
  return g;
}

GpsTime gps_from_glonass(const GlonassTime& g, std::optional<int> leap_s) {
  if (g.n4 < 1 || g.nt < 1 || g.nt > kDaysPerCycle || !(g.tod_s >= 0.0 && g.tod_s < 86401.0)) {
    throw Error("GLONASS time N4 " + std::to_string(g.n4) + " NT " + std::to_string(g.nt) + " tod " +
                std::to_string(g.tod_s) + " s out of range");
  }
  const int64_t days = cycle_start_days(g.n4) + g.nt - 1;
  CalendarTime c;
  civil_from_days(days, c.year, c.month, c.day);
  // Back to UTC: 3 h earlier, possibly the day before.
  double utc_tod = g.tod_s - kGlonasstMinusUtc_s;
  int64_t utc_days = days;
  if (utc_tod < 0.0) {
    utc_tod += 86400.0;
    --utc_days;
  }
  civil_from_days(utc_days, c.year, c.month, c.day);
  const double whole = std::floor(std::min(utc_tod, 86399.0));
  c.hour = static_cast<int>(whole / 3600.0);
  c.minute = static_cast<int>((whole - c.hour * 3600.0) / 60.0);
  c.second = utc_tod - c.hour * 3600.0 - c.minute * 60.0;  // 60.x in a leap second
  return utc_to_gps(c, leap_s);
}

}  // namespace gnssemu::time

// SPDX-License-Identifier: Apache-2.0
#include "core/time/utc.hpp"

#include <array>

namespace gnssemu::time {

namespace {
struct LeapStep {
  int year, month;  // UTC date (day 1, 00:00) from which count applies
  int count;        // GPS - UTC, s
};
// IERS Bulletin C history; the same table as RTKLIB rtkcmn.c leaps[].
constexpr std::array<LeapStep, 18> kLeapTable{{
    {1981, 7, 1}, {1982, 7, 2}, {1983, 7, 3}, {1985, 7, 4}, {1988, 1, 5}, {1990, 1, 6},
    {1991, 1, 7}, {1992, 7, 8}, {1993, 7, 9}, {1994, 7, 10}, {1996, 1, 11}, {1997, 7, 12},
    {1999, 1, 13}, {2006, 1, 14}, {2009, 1, 15}, {2012, 7, 16}, {2015, 7, 17}, {2017, 1, 18},
}};

GpsTime step_instant(const LeapStep& s) {
  // The step happens at UTC midnight, which is GPS midnight + new count.
  return GpsTime::from_calendar({s.year, s.month, 1, 0, 0, 0.0}) + static_cast<double>(s.count);
}
}  // namespace

int leap_seconds_at(const GpsTime& t) noexcept {
  int n = 0;
  for (const auto& s : kLeapTable) {
    if (t >= step_instant(s)) n = s.count;
  }
  return n;
}

bool in_inserted_leap_second(const GpsTime& t) noexcept {
  int before = 0;
  for (const auto& s : kLeapTable) {
    const GpsTime step = step_instant(s);
    if (s.count > before && t < step && t >= step - 1.0) return true;
    before = s.count;
  }
  return false;
}

CalendarTime gps_to_utc(const GpsTime& t, std::optional<int> leap_s, bool in_leap_second) {
  const bool inserting = leap_s ? in_leap_second : in_inserted_leap_second(t);
  const int leap = leap_s ? *leap_s : leap_seconds_at(t);
  if (!inserting) return (t - static_cast<double>(leap)).to_calendar();
  // The inserted second is 23:59:60 of the last day before the step (ITU-R
  // TF.460-6 §2.2): count it from 23:59:59 with the new count, then add 1.
  CalendarTime c = (t - static_cast<double>(leap + 1)).to_calendar();
  c.second += 1.0;
  return c;
}

GpsTime utc_to_gps(const CalendarTime& utc, std::optional<int> leap_s) {
  // Second 60 is normalised into the next day by from_calendar; count it
  // with the old count, i.e. as 23:59:59.x + 1 s.
  const bool leap_second = utc.second >= 60.0;
  const GpsTime as_gps = GpsTime::from_calendar(utc);
  if (leap_s) return as_gps + static_cast<double>(*leap_s);
  // The table steps at UTC midnight (UTC + new count in GPS time).
  const GpsTime key = leap_second ? as_gps - 1.0 : as_gps;
  int n = 0;
  for (const auto& s : kLeapTable) {
    if (key >= GpsTime::from_calendar({s.year, s.month, 1, 0, 0, 0.0})) n = s.count;
  }
  return as_gps + static_cast<double>(n);
}

}  // namespace gnssemu::time

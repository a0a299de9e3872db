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

CalendarTime gps_to_utc(const GpsTime& t, std::optional<int> leap_s) {
  const int leap = leap_s ? *leap_s : leap_seconds_at(t);
  return (t - static_cast<double>(leap)).to_calendar();
}

GpsTime utc_to_gps(const CalendarTime& utc, std::optional<int> leap_s) {
  const GpsTime as_gps = GpsTime::from_calendar(utc);
  if (leap_s) return as_gps + static_cast<double>(*leap_s);
  // The table is indexed by GPS time; UTC + n is within one step of it.
  const int n0 = leap_seconds_at(as_gps);
  const int n1 = leap_seconds_at(as_gps + static_cast<double>(n0));
  return as_gps + static_cast<double>(n1);
}

}  // namespace gnssemu::time

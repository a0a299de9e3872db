#include <gtest/gtest.h>

#include <cmath>

#include "core/time/gps_time.hpp"
#include "core/time/utc.hpp"

using gnssemu::time::CalendarTime;
using gnssemu::time::GpsTime;

TEST(GpsTime, EpochIsWeekZero) {
  const GpsTime t = GpsTime::from_calendar({1980, 1, 6, 0, 0, 0.0});
  EXPECT_EQ(t.week(), 0);
  EXPECT_DOUBLE_EQ(t.tow_s(), 0.0);
}

TEST(GpsTime, KnownDates) {
  // 2022-01-01 00:00:00 GPST is week 2190, day 6 (Saturday).
  const GpsTime t = GpsTime::from_calendar({2022, 1, 1, 0, 0, 0.0});
  EXPECT_EQ(t.week(), 2190);
  EXPECT_DOUBLE_EQ(t.tow_s(), 6 * 86400.0);
  // Rollovers: week 1024 = 1999-08-22, 2048 = 2019-04-07, 3072 = 2038-11-21.
  EXPECT_EQ(GpsTime::from_calendar({1999, 8, 22, 0, 0, 0.0}).week(), 1024);
  EXPECT_EQ(GpsTime::from_calendar({2019, 4, 7, 0, 0, 0.0}).week(), 2048);
  EXPECT_EQ(GpsTime::from_calendar({2038, 11, 21, 0, 0, 0.0}).week(), 3072);
}

TEST(GpsTime, ArithmeticAcrossWeekBoundary) {
  const GpsTime t(2190, 604799.5);
  const GpsTime u = t + 1.0;
  EXPECT_EQ(u.week(), 2191);
  EXPECT_NEAR(u.tow_s(), 0.5, 1e-9);
  EXPECT_NEAR(u - t, 1.0, 1e-9);
  const GpsTime v = u - 2.0;
  EXPECT_EQ(v.week(), 2190);
  EXPECT_NEAR(v.tow_s(), 604798.5, 1e-9);
  EXPECT_LT(v, u);
  EXPECT_NEAR(GpsTime(2000, 0.0) - GpsTime(1999, 604800.0 - 1e-3), 1e-3, 1e-9);  // tow is a double: ~1e-10 s resolution
  // Large negative tow normalises.
  const GpsTime w(2190, -3 * 604800.0 - 10.0);
  EXPECT_EQ(w.week(), 2186);
  EXPECT_NEAR(w.tow_s(), 604790.0, 1e-9);
}

TEST(GpsTime, CalendarRoundTrip) {
  const CalendarTime c{2024, 5, 3, 23, 59, 59.75};
  const CalendarTime r = GpsTime::from_calendar(c).to_calendar();
  EXPECT_EQ(r.year, 2024);
  EXPECT_EQ(r.month, 5);
  EXPECT_EQ(r.day, 3);
  EXPECT_EQ(r.hour, 23);
  EXPECT_EQ(r.minute, 59);
  EXPECT_NEAR(r.second, 59.75, 1e-9);
  EXPECT_EQ(GpsTime::from_calendar({2024, 12, 31, 12, 0, 0}).day_of_year(), 366);
  EXPECT_EQ(GpsTime::from_calendar({2022, 1, 1, 0, 0, 0}).day_of_year(), 1);
}

TEST(GpsTime, FractionalDayOfYear) {
  EXPECT_EQ(GpsTime::from_calendar({2022, 1, 1, 0, 0, 0}).fractional_day_of_year(), 1.0);
  EXPECT_EQ(GpsTime::from_calendar({2024, 12, 31, 12, 0, 0}).fractional_day_of_year(), 366.5);
  EXPECT_EQ(GpsTime::from_calendar({2022, 5, 3, 6, 0, 0}).fractional_day_of_year(), 123.25);
  // The day's fraction comes from the time of week: day_of_year() + (tow mod 1 day) / 1 day.
  const GpsTime t(2190, 521233.25);
  EXPECT_EQ(t.fractional_day_of_year(), t.day_of_year() + std::fmod(521233.25, 86400.0) / 86400.0);
  EXPECT_NEAR(t.fractional_day_of_year(), 1.0 + 2833.25 / 86400.0, 1e-12);  // 2022-01-01 00:47:13.25
}

TEST(GpsTime, WeekRollover) {
  using gnssemu::time::resolve_week_at_or_after;
  using gnssemu::time::resolve_week_nearest;
  EXPECT_EQ(resolve_week_nearest(862, 1900), 1886);
  EXPECT_EQ(resolve_week_nearest(182, 2200), 2230);
  EXPECT_EQ(resolve_week_nearest(1023, 2048), 2047);
  EXPECT_EQ(resolve_week_at_or_after(0, 2047), 2048);
  EXPECT_EQ(resolve_week_at_or_after(1000, 2048), 3048);
  EXPECT_EQ(gnssemu::time::year_from_two_digits(99), 1999);
  EXPECT_EQ(gnssemu::time::year_from_two_digits(22), 2022);
}

TEST(Utc, LeapSeconds) {
  using gnssemu::time::gps_to_utc;
  using gnssemu::time::leap_seconds_at;
  using gnssemu::time::utc_to_gps;
  EXPECT_EQ(leap_seconds_at(GpsTime::from_calendar({1980, 6, 1, 0, 0, 0})), 0);
  EXPECT_EQ(leap_seconds_at(GpsTime::from_calendar({2016, 12, 31, 23, 59, 59})), 17);
  // The 2017 step happens at UTC midnight = GPS 00:00:18.
  EXPECT_EQ(leap_seconds_at(GpsTime::from_calendar({2017, 1, 1, 0, 0, 17.5})), 17);
  EXPECT_EQ(leap_seconds_at(GpsTime::from_calendar({2017, 1, 1, 0, 0, 18.0})), 18);
  const GpsTime t = GpsTime::from_calendar({2022, 1, 1, 0, 0, 18.0});
  const CalendarTime u = gps_to_utc(t);
  EXPECT_EQ(u.year, 2022);
  EXPECT_EQ(u.hour, 0);
  EXPECT_NEAR(u.second, 0.0, 1e-9);
  EXPECT_NEAR(utc_to_gps(u) - t, 0.0, 1e-9);
  // A header value overrides the table.
  EXPECT_NEAR(gps_to_utc(t, 17).second, 1.0, 1e-9);
}

// 2016-12-31 23:59:60 UTC (17 -> 18 s) is GPS 2017-01-01 00:00:17-18 GPST.
// UTC must step through 23:59:60.x, strictly increasing, never repeating.
TEST(Utc, InsertedLeapSecondIs60) {
  using gnssemu::time::gps_to_utc;
  using gnssemu::time::in_inserted_leap_second;
  using gnssemu::time::utc_to_gps;
  const GpsTime t0 = GpsTime::from_calendar({2017, 1, 1, 0, 0, 16.5});
  double prev_s = -1.0;  // UTC label as a number: day * 1e5 + seconds of day (60.x < next day)
  for (int k = 0; k <= 25; ++k) {
    const GpsTime t = t0 + 0.1 * k;  // 00:00:16.5 .. 00:00:19.0 GPST
    const CalendarTime u = gps_to_utc(t);
    const double day = u.year == 2016 ? 0.0 : 1e5;
    ASSERT_TRUE((u.year == 2016 && u.month == 12 && u.day == 31) || (u.year == 2017 && u.day == 1)) << k;
    const double s = day + u.hour * 3600.0 + u.minute * 60.0 + u.second;
    EXPECT_GT(s, prev_s) << "k=" << k << " " << u.hour << ":" << u.minute << ":" << u.second;
    prev_s = s;
    EXPECT_NEAR(utc_to_gps(u) - t, 0.0, 1e-6) << k;  // round trip, 60.x included
  }
  const CalendarTime mid = gps_to_utc(GpsTime::from_calendar({2017, 1, 1, 0, 0, 17.5}));
  EXPECT_EQ(mid.year, 2016);
  EXPECT_EQ(mid.day, 31);
  EXPECT_EQ(mid.hour, 23);
  EXPECT_EQ(mid.minute, 59);
  EXPECT_NEAR(mid.second, 60.5, 1e-6);
  const CalendarTime after = gps_to_utc(GpsTime::from_calendar({2017, 1, 1, 0, 0, 18.0}));
  EXPECT_EQ(after.year, 2017);
  EXPECT_EQ(after.hour, 0);
  EXPECT_NEAR(after.second, 0.0, 1e-6);
  EXPECT_TRUE(in_inserted_leap_second(GpsTime::from_calendar({2017, 1, 1, 0, 0, 17.0})));
  EXPECT_FALSE(in_inserted_leap_second(GpsTime::from_calendar({2017, 1, 1, 0, 0, 16.999})));
  EXPECT_FALSE(in_inserted_leap_second(GpsTime::from_calendar({2017, 1, 1, 0, 0, 18.0})));
  // With an explicit count the caller says whether t is inserted.
  EXPECT_NEAR(gps_to_utc(GpsTime::from_calendar({2017, 1, 1, 0, 0, 17.5}), 17, true).second, 60.5, 1e-6);
  // UTC just after the step on the step day.
  EXPECT_NEAR(utc_to_gps({2017, 1, 1, 0, 0, 0.5}) - GpsTime::from_calendar({2017, 1, 1, 0, 0, 18.5}), 0.0, 1e-6);
}

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "core/time/gps_time.hpp"
#include "core/time/utc.hpp"

using gnssemu::time::CalendarTime;
using gnssemu::time::GpsTime;

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

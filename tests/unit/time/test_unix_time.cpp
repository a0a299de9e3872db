// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/time/gps_time.hpp"
#include "core/time/unix_time.hpp"
#include "core/time/utc.hpp"

using gnssemu::time::CalendarTime;
using gnssemu::time::GpsTime;
using gnssemu::time::gps_from_unix;
using gnssemu::time::unix_from_gps;

namespace {
// 2017-01-01 00:00:00 UTC: GPS - UTC steps from 17 to 18 s (IERS Bulletin C 52).
constexpr double kStep2017_unix_s = 1483228800.0;
}  // namespace

TEST(UnixTime, GpsEpochAndKnownDates) {
  // 1980-01-06 00:00:00 UTC, GPS - UTC = 0.
  const GpsTime epoch = gps_from_unix(315964800.0);
  EXPECT_EQ(epoch.week(), 0);
  EXPECT_DOUBLE_EQ(epoch.tow_s(), 0.0);
  // 2022-01-01 00:00:00 UTC is 00:00:18 GPST, week 2190 day 6.
  const GpsTime t = gps_from_unix(1640995200.0);
  EXPECT_EQ(t.week(), 2190);
  EXPECT_DOUBLE_EQ(t.tow_s(), 6 * 86400.0 + 18.0);
  EXPECT_DOUBLE_EQ(unix_from_gps(t), 1640995200.0);
}

TEST(UnixTime, LeapSecondBoundaries) {
  // The last POSIX second before the 2017 step counts 17 s, the first after it 18 s:
  // one Unix second apart, two GPS seconds apart (23:59:60 lies between).
  const GpsTime before = gps_from_unix(kStep2017_unix_s - 1.0);
  const GpsTime after = gps_from_unix(kStep2017_unix_s);
  EXPECT_EQ(before, GpsTime::from_calendar({2017, 1, 1, 0, 0, 16.0}));
  EXPECT_EQ(after, GpsTime::from_calendar({2017, 1, 1, 0, 0, 18.0}));
  EXPECT_DOUBLE_EQ(after - before, 2.0);
  // 1981-07-01, the first step (0 -> 1 s).
  EXPECT_DOUBLE_EQ(gps_from_unix(362793600.0) - gps_from_unix(362793599.0), 2.0);
  // Inside the inserted second (GPS 00:00:17.x) a Linux clock repeats 23:59:59.x.
  const GpsTime inserted = GpsTime::from_calendar({2017, 1, 1, 0, 0, 17.25});
  ASSERT_TRUE(gnssemu::time::in_inserted_leap_second(inserted));
  EXPECT_NEAR(unix_from_gps(inserted), kStep2017_unix_s - 0.75, 1e-6);
  EXPECT_NEAR(gps_from_unix(unix_from_gps(inserted)) - inserted, -1.0, 1e-6);
}

TEST(UnixTime, SubSecond) {
  const GpsTime t = gps_from_unix(kStep2017_unix_s + 0.25);
  EXPECT_EQ(t.week(), 1930);
  EXPECT_NEAR(t.tow_s(), 18.25, 1e-6);
  EXPECT_NEAR(gps_from_unix(kStep2017_unix_s - 0.001) - gps_from_unix(kStep2017_unix_s - 1.0), 0.999, 1e-6);
  // Negative Unix time (before 1970): the day still starts at midnight.
  const CalendarTime c = gnssemu::time::gps_to_utc(gps_from_unix(-0.5));
  EXPECT_EQ(c.year, 1969);
  EXPECT_EQ(c.hour, 23);
  EXPECT_NEAR(c.second, 59.5, 1e-9);
}

TEST(UnixTime, RoundTrip) {
  // Every ~3.7 days from 1980 to 2040, at odd fractions of a second.
  for (double u = 315964800.123; u < 2208988800.0; u += 319999.877) {
    const GpsTime t = gps_from_unix(u);
    EXPECT_NEAR(unix_from_gps(t), u, 1e-6) << std::fixed << u;
    EXPECT_NEAR(gps_from_unix(unix_from_gps(t)) - t, 0.0, 1e-6) << std::fixed << u;
  }
}

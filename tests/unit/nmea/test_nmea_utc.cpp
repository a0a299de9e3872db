// SPDX-License-Identifier: Apache-2.0
// core/protocol/nmea/nmea_utc: GPS time to the UTC an NMEA sentence carries.
#include <gtest/gtest.h>

#include <cmath>

#include "core/protocol/nmea/nmea_utc.hpp"
#include "core/time/utc.hpp"

namespace gnssemu::protocol::nmea {
namespace {

time::GpsTime gps_of_utc(int y, int mo, int d, int h, int mi, double s) {
  return time::utc_to_gps({y, mo, d, h, mi, s}, 18);
}

TEST(NmeaUtc, RoundsToCentisecondsWithCarryThroughTheDate) {
  // 2021-12-31 23:59:59.996 UTC -> 2022-01-01 00:00:00.00.
  UtcStamp u = utc_stamp(gps_of_utc(2021, 12, 31, 23, 59, 59.996), 18);
  EXPECT_EQ(u.year, 2022);
  EXPECT_EQ(u.month, 1);
  EXPECT_EQ(u.day, 1);
  EXPECT_EQ(u.hour, 0);
  EXPECT_EQ(u.minute, 0);
  EXPECT_EQ(u.second, 0);
  EXPECT_EQ(u.centisecond, 0);
  // Leap day and month end.
  u = utc_stamp(gps_of_utc(2024, 2, 29, 23, 59, 59.999), 18);
  EXPECT_EQ(u.month, 3);
  EXPECT_EQ(u.day, 1);
  u = utc_stamp(gps_of_utc(2024, 2, 28, 23, 59, 59.9951), 18);
  EXPECT_EQ(u.month, 2);
  EXPECT_EQ(u.day, 29);
  EXPECT_EQ(u.hour, 0);
  // Below the half: stays.
  u = utc_stamp(gps_of_utc(2024, 2, 28, 23, 59, 59.994), 18);
  EXPECT_EQ(u.day, 28);
  EXPECT_EQ(u.second, 59);
  EXPECT_EQ(u.centisecond, 99);
  // Minute and hour carry.
  u = utc_stamp(gps_of_utc(2024, 5, 3, 12, 59, 59.997), 18);
  EXPECT_EQ(u.hour, 13);
  EXPECT_EQ(u.minute, 0);
  EXPECT_EQ(u.second, 0);
  // 10 Hz epochs keep their tenths exactly.
  const time::GpsTime t0 = gps_of_utc(2024, 5, 3, 8, 15, 20.0);
  for (int k = 0; k < 10; ++k) {
    u = utc_stamp(t0 + 0.1 * k, 18);
    EXPECT_EQ(u.second, 20);
    EXPECT_EQ(u.centisecond, 10 * k);
  }
}

TEST(NmeaUtc, UsesTheGivenLeapSeconds) {
  const time::GpsTime t = gps_of_utc(2024, 5, 3, 0, 0, 30.0);
  EXPECT_EQ(utc_stamp(t, 18).second, 30);
  EXPECT_EQ(utc_stamp(t, 17).second, 31);
}

}  // namespace
}  // namespace gnssemu::protocol::nmea

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/error.hpp"
#include "core/time/gps_time.hpp"

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

// Load time rejects a week shift that does not fit (a YUMA toa of 1e300
// once reached a float->int conversion); the per-epoch arithmetic saturates.
TEST(GpsTime, RejectsWeekShiftsThatDoNotFit) {
  using gnssemu::time::kMaxWeek;
  EXPECT_THROW(GpsTime(2190, 1e300), gnssemu::Error);
  EXPECT_THROW(GpsTime(2190, -1e300), gnssemu::Error);
  EXPECT_THROW(GpsTime(2190, std::nan("")), gnssemu::Error);
  EXPECT_THROW(GpsTime(2190, HUGE_VAL), gnssemu::Error);
  EXPECT_THROW(GpsTime(kMaxWeek, 604800.0), gnssemu::Error);  // carries into week kMaxWeek + 1
  EXPECT_THROW(GpsTime(2000000000, 0.0), gnssemu::Error);
  EXPECT_THROW(GpsTime::from_calendar({40000, 1, 1, 0, 0, 0.0}), gnssemu::Error);
  EXPECT_NO_THROW(GpsTime(kMaxWeek, 604799.0));
  EXPECT_NO_THROW(GpsTime(-kMaxWeek, 0.0));
  try {
    GpsTime(862, 1e300);
    ADD_FAILURE() << "no throw";
  } catch (const gnssemu::Error& e) {
    EXPECT_NE(std::string(e.what()).find("outside the supported weeks"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(GpsTime::make(2190, 1e300).has_value());
  EXPECT_FALSE(GpsTime::make(2190, std::nan("")).has_value());
  ASSERT_TRUE(GpsTime::make(2190, 604800.5).has_value());
  EXPECT_EQ(*GpsTime::make(2190, 604800.5), GpsTime(2191, 0.5));
}

TEST(GpsTime, ArithmeticNeverThrowsAndSaturates) {
  using gnssemu::time::kMaxWeek;
  const GpsTime t(2190, 1000.0);
  static_assert(noexcept(t + 1.0) && noexcept(t - 1.0) && noexcept(t - t));
  EXPECT_EQ(t + std::nan(""), t);  // a non-finite shift leaves the time
  EXPECT_EQ(t + HUGE_VAL, t);
  const GpsTime hi = t + 1e300;
  EXPECT_EQ(hi.week(), kMaxWeek);
  EXPECT_LT(hi.tow_s(), 604800.0);
  const GpsTime lo = t - 1e300;
  EXPECT_EQ(lo, GpsTime(-kMaxWeek, 0.0));
  EXPECT_EQ((t + 1e18).week(), kMaxWeek);  // finite but past the end
  EXPECT_NEAR((t + 86400.0 * 365.0 * 100.0) - t, 86400.0 * 365.0 * 100.0, 1e-6);  // a century still exact
}

TEST(GpsTime, CalendarText) {
  EXPECT_EQ(gnssemu::time::calendar_text(GpsTime(2190, 518400.0 + 3723.9)), "2022-01-01 01:02:03 GPST");
}

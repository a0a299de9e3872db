// SPDX-License-Identifier: Apache-2.0
// GST, BDT and GLONASST against GPST at every boundary: week starts, the
// systems' origins, the GLONASS day and four-year interval, a leap second.
#include <gtest/gtest.h>

#include "core/common/error.hpp"
#include "core/time/beidou_time.hpp"
#include "core/time/galileo_time.hpp"
#include "core/time/glonass_time.hpp"
#include "core/time/utc.hpp"

using namespace gnssemu::time;

namespace {
GpsTime gps_cal(int y, int mo, int d, int h, int mi, double s) { return GpsTime::from_calendar({y, mo, d, h, mi, s}); }
}  // namespace

TEST(GalileoTime, WeekOriginAndBoundaries) {
  // 1999-08-22 00:00 GPST is GPS week 1024 (the first rollover).
  EXPECT_EQ(gps_cal(1999, 8, 22, 0, 0, 0.0), GpsTime(1024, 0.0));
  WeekTime g = gst_from_gps(GpsTime(1024, 0.0));
  EXPECT_EQ(g.week, 0);
  EXPECT_EQ(g.tow_s, 0.0);
  g = gst_from_gps(GpsTime(1023, 604799.5));
  EXPECT_EQ(g.week, -1);
  EXPECT_EQ(g.tow_s, 604799.5);
  g = gst_from_gps(GpsTime(2296, 604799.75));  // 2024-01-13
  EXPECT_EQ(g.week, 1272);
  EXPECT_EQ(g.tow_s, 604799.75);
  EXPECT_EQ(gps_from_gst({1272, 604799.75}), GpsTime(2296, 604799.75));
  EXPECT_EQ(gps_from_gst({1273, 0.0}), GpsTime(2297, 0.0));
  // The broadcast 12-bit week rolls over after 4096 weeks (2078).
  EXPECT_EQ(gst_from_gps(GpsTime(1024 + kGalileoWeekModulus, 0.0)).week % kGalileoWeekModulus, 0);
}

TEST(BeiDouTime, OriginIsGpsWeek1356Plus14s) {
  // 2006-01-01 00:00:00 UTC = BDT origin; GPS - UTC was 14 s then.
  const GpsTime origin = utc_to_gps({2006, 1, 1, 0, 0, 0.0});
  EXPECT_EQ(origin, GpsTime(1356, 14.0));
  WeekTime b = bdt_from_gps(origin);
  EXPECT_EQ(b.week, 0);
  EXPECT_EQ(b.tow_s, 0.0);
  b = bdt_from_gps(origin - 0.25);
  EXPECT_EQ(b.week, -1);
  EXPECT_EQ(b.tow_s, 604799.75);
}

TEST(BeiDouTime, WeekBoundaryIs14sAfterGps) {
  // GPS week 2297 starts at tow 0; BDT week 941 starts 14 s later.
  WeekTime b = bdt_from_gps(GpsTime(2297, 0.0));
  EXPECT_EQ(b.week, 940);
  EXPECT_EQ(b.tow_s, 604786.0);
  b = bdt_from_gps(GpsTime(2297, 13.5));
  EXPECT_EQ(b.week, 940);
  EXPECT_EQ(b.tow_s, 604799.5);
  b = bdt_from_gps(GpsTime(2297, 14.0));
  EXPECT_EQ(b.week, 941);
  EXPECT_EQ(b.tow_s, 0.0);
  EXPECT_EQ(gps_from_bdt({941, 0.0}), GpsTime(2297, 14.0));
  EXPECT_EQ(gps_from_bdt({940, 604799.5}), GpsTime(2297, 13.5));
  for (double tow : {0.0, 13.0, 14.0, 302400.0, 604785.0, 604799.0}) {
    const GpsTime t(2296, tow);
    EXPECT_EQ(gps_from_bdt(bdt_from_gps(t)), t) << tow;
  }
}

TEST(GlonassTime, ThreeHoursAheadOfUtcWithLeapSeconds) {
  // 2024-01-10 00:00:00 UTC = 03:00:00 GLONASST, GPST = UTC + 18 s.
  const GpsTime t = utc_to_gps({2024, 1, 10, 0, 0, 0.0});
  EXPECT_EQ(t, gps_cal(2024, 1, 10, 0, 0, 18.0));
  const GlonassTime g = glonass_from_gps(t);
  EXPECT_EQ(g.n4, 8);   // 2024..2027
  EXPECT_EQ(g.nt, 10);  // 10 January of the leap year
  EXPECT_EQ(g.tod_s, 10800.0);
  EXPECT_EQ(gps_from_glonass(g), t);
  // A header's own leap count overrides the table.
  EXPECT_EQ(glonass_from_gps(t, 17).tod_s, 10801.0);
}

TEST(GlonassTime, DayBoundaryIsAt21hUtc) {
  const GpsTime midnight = utc_to_gps({2024, 1, 10, 21, 0, 0.0});
  GlonassTime g = glonass_from_gps(midnight - 0.5);
  EXPECT_EQ(g.nt, 10);
  EXPECT_EQ(g.tod_s, 86399.5);
  g = glonass_from_gps(midnight);
  EXPECT_EQ(g.nt, 11);
  EXPECT_EQ(g.tod_s, 0.0);
  EXPECT_EQ(gps_from_glonass({8, 11, 0.0}), midnight);
  EXPECT_EQ(gps_from_glonass({8, 10, 86399.5}), midnight - 0.5);
}

TEST(GlonassTime, FourYearIntervalBoundary) {
  // 2024-01-01 00:00 GLONASST = 2023-12-31 21:00 UTC starts N4 = 8.
  const GpsTime start = utc_to_gps({2023, 12, 31, 21, 0, 0.0});
  GlonassTime g = glonass_from_gps(start);
  EXPECT_EQ(g.n4, 8);
  EXPECT_EQ(g.nt, 1);
  EXPECT_EQ(g.tod_s, 0.0);
  g = glonass_from_gps(start - 1.0);
  EXPECT_EQ(g.n4, 7);
  EXPECT_EQ(g.nt, 1461);  // 2020 was the leap year of interval 7
  EXPECT_EQ(g.tod_s, 86399.0);
  EXPECT_EQ(gps_from_glonass({7, 1461, 86399.0}), start - 1.0);
  EXPECT_EQ(gps_from_glonass({8, 1, 0.0}), start);
  // Day 60 of a leap year's interval is 29 February.
  EXPECT_EQ(glonass_calendar(gps_from_glonass({8, 60, 43200.0})).month, 2);
  EXPECT_EQ(glonass_calendar(gps_from_glonass({8, 60, 43200.0})).day, 29);
  EXPECT_THROW(gps_from_glonass({8, 0, 0.0}), gnssemu::Error);
  EXPECT_THROW(gps_from_glonass({8, 1462, 0.0}), gnssemu::Error);
  EXPECT_THROW(gps_from_glonass({0, 1, 0.0}), gnssemu::Error);
  EXPECT_THROW(gps_from_glonass({8, 1, 86401.0}), gnssemu::Error);
}

TEST(GlonassTime, InsertedLeapSecondIs025960Glonasst) {
  // 2016-12-31 23:59:60 UTC: GPS - UTC went from 17 to 18 s.
  const GpsTime step = utc_to_gps({2017, 1, 1, 0, 0, 0.0});
  EXPECT_EQ(step, gps_cal(2017, 1, 1, 0, 0, 18.0));
  CalendarTime c = glonass_calendar(step - 0.5);
  EXPECT_EQ(c.day, 1);
  EXPECT_EQ(c.hour, 2);
  EXPECT_EQ(c.minute, 59);
  EXPECT_EQ(c.second, 60.5);
  c = glonass_calendar(step - 1.5);
  EXPECT_EQ(c.second, 59.5);
  c = glonass_calendar(step);
  EXPECT_EQ(c.hour, 3);
  EXPECT_EQ(c.second, 0.0);
  // Either side of the leap second GLONASST and GPST differ by leap - 3 h.
  const GlonassTime before = glonass_from_gps(step - 1.5);
  const GlonassTime after = glonass_from_gps(step + 0.5);
  EXPECT_EQ(before.tod_s, 10799.5);
  EXPECT_EQ(after.tod_s, 10800.5);
  EXPECT_EQ(gps_from_glonass(before), step - 1.5);
  EXPECT_EQ(gps_from_glonass(after), step + 0.5);
}

// The broadcast week numbers are truncated (GST 12 bits, BDT 13 bits):
// resolved against a reference week as GPS's 10-bit one.
TEST(SystemWeeks, TruncatedWeeksResolve) {
  const GpsTime t(2296, 302400.0);
  const WeekTime gst = gst_from_gps(t);
  EXPECT_EQ(resolve_week_nearest(gst.week % kGalileoWeekModulus, 1200, kGalileoWeekModulus), gst.week);
  const WeekTime bdt = bdt_from_gps(t);
  EXPECT_EQ(bdt.week, 940);
  EXPECT_EQ(resolve_week_nearest(bdt.week % kBeiDouWeekModulus, 900, kBeiDouWeekModulus), bdt.week);
  EXPECT_EQ(resolve_week_nearest(t.week() % kGpsWeekModulus, 2200), t.week());
  // After the GST rollover (GPS week 5120, 2078) the 12-bit week starts at 0 again.
  EXPECT_EQ(gst_from_gps(GpsTime(1024 + 4096, 0.0)).week % kGalileoWeekModulus, 0);
}

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "core/orbit/rinex_nav.hpp"
#include "daemon/epoch_schedule.hpp"
#include "daemon/truth/time_mapping.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;

TEST(TimeMapping, FirstToePlusHourOfBrdc) {
  const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  // First toe 2022-01-01 00:00 GPST = week 2190, tow 518400 (Saturday); +1 h.
  const time::GpsTime t = first_toe_plus_hour(nav.ephemerides);
  EXPECT_EQ(t.week(), 2190);
  EXPECT_DOUBLE_EQ(t.tow_s(), 518400.0 + 3600.0);
  EXPECT_EQ(first_toe_plus_hour({}), time::GpsTime());
}

TEST(TimeMapping, RunStartChoices) {
  std::vector<orbit::Ephemeris> ephs(2);
  ephs[0].toe = time::GpsTime(2190, 86400.0);
  ephs[1].toe = time::GpsTime(2190, 7200.0);
  const time::GpsTime now(2446, 210807.25);
  const time::GpsTime configured(2300, 1000.0);
  // A configured start wins; then today (the next whole second); then the data's first day.
  EXPECT_EQ(run_start(configured, true, ephs, now), configured);
  EXPECT_EQ(run_start(std::nullopt, true, ephs, now), time::GpsTime(2446, 210808.0));
  EXPECT_EQ(run_start(std::nullopt, false, ephs, now), time::GpsTime(2190, 7200.0 + 3600.0));
}

TEST(TimeMapping, SimClockAnchorsAndFollows) {
  SimClockMap m(0.2);
  const time::GpsTime a(2190, 522000.0);
  SimClockMap::Mapped r = m.map(100.0, a);
  EXPECT_TRUE(r.reanchored);
  EXPECT_EQ(r.t, a);
  // Network jitter within 0.2 s: sim spacing is kept exactly.
  r = m.map(100.1, a + 0.25);
  EXPECT_FALSE(r.reanchored);
  EXPECT_NEAR(r.t - a, 0.1, 1e-9);
  r = m.map(101.0, a + 0.85);
  EXPECT_FALSE(r.reanchored);
  EXPECT_NEAR(r.t - a, 1.0, 1e-9);
}

TEST(TimeMapping, SimClockReanchorsOnDrift) {
  SimClockMap m(0.2);
  const time::GpsTime a(2190, 522000.0);
  m.map(0.0, a);
  // Simulator at half speed: after 0.5 s of sim time 1 s of wall time passed.
  SimClockMap::Mapped r = m.map(0.35, a + 0.5);
  EXPECT_FALSE(r.reanchored);  // drift 0.15: still within
  r = m.map(0.5, a + 1.0);
  EXPECT_TRUE(r.reanchored);  // drift 0.5 > 0.2
  EXPECT_EQ(r.t, a + 1.0);
  r = m.map(0.6, a + 1.15);
  EXPECT_FALSE(r.reanchored);
  EXPECT_NEAR(r.t - a, 1.1, 1e-9);
  m.reset();
  EXPECT_FALSE(m.anchored());
}

TEST(TimeMapping, WallClockStartIsOnAWholeGpsSecond) {
  // The wall clock is read at an arbitrary instant; epochs must still fall on
  // whole multiples of the period in GPS time (iTOW ...000, ...200 at 5 Hz),
  // not on the instant's fraction (...455, ...655).
  const WholeSecondStart w = whole_second_start(time::GpsTime(2390, 345600.455));
  EXPECT_EQ(w.start.week(), 2390);
  EXPECT_DOUBLE_EQ(w.start.tow_s(), 345601.0);
  EXPECT_NEAR(w.wait_s, 0.545, 1e-9);
  for (int k = 0; k < 10; ++k) {  // 5 Hz from there: every iTOW a multiple of 200 ms
    const time::GpsTime t = w.start + epoch_offset_s(k, 5.0);
    const auto itow_ms = std::llround(t.tow_s() * 1000.0);
    EXPECT_EQ(itow_ms % 200, 0) << k;
  }
  const WholeSecondStart exact = whole_second_start(time::GpsTime(2390, 17.0));
  EXPECT_DOUBLE_EQ(exact.start.tow_s(), 17.0);
  EXPECT_EQ(exact.wait_s, 0.0);
  const WholeSecondStart carry = whole_second_start(time::GpsTime(2390, 604799.75));
  EXPECT_EQ(carry.start.week(), 2391);  // rounds into the next week
  EXPECT_DOUBLE_EQ(carry.start.tow_s(), 0.0);
  EXPECT_NEAR(carry.wait_s, 0.25, 1e-9);
}

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/orbit/constellation.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "orbit_test_data.hpp"

using namespace gnssemu;
using namespace gnssemu::orbit;

using test::brdc;
using test::kData;

namespace {

ConstellationRequest at(const time::GpsTime& start, NavMode mode = NavMode::kAuto) {
  ConstellationRequest r;
  r.mode = mode;
  r.start = start;
  return r;
}

// 2026-11-24 10:33:28 GPST, a Tuesday.
const time::GpsTime kToday(2446, 210808.0);
// 2022-01-01 12:00 GPST, inside brdc0010.22n.
const time::GpsTime kInside(2190, 518400.0 + 43200.0);

/// Largest error of Simpson's rule p(t+dt) = p(t) + dt (v0 + 4 v_mid + v1) / 6
/// over [from, from + span_s] for every satellite of the store: under 5 cm
/// at dt = 600 s for a smooth orbit, about the size of any jump otherwise.
struct Steps {
  double max_jump_m = 0.0;
  int max_sats = 0, min_sats = 99;
};
Steps walk(const EphemerisStore& store, const time::GpsTime& from, double span_s, double dt_s) {
  Steps s;
  for (double x = 0.0; x + dt_s <= span_s; x += dt_s) {
    const time::GpsTime t0 = from + x, t1 = t0 + dt_s;
    int n = 0;
    for (int prn = 1; prn <= system_size(GnssSystem::kGps); ++prn) {
      const time::GpsTime tm = t0 + dt_s / 2.0;
      const Ephemeris* e0 = store.select(SatId::gps(prn), t0);
      const Ephemeris* em = store.select(SatId::gps(prn), tm);
      const Ephemeris* e1 = store.select(SatId::gps(prn), t1);
      if (e0 == nullptr || em == nullptr || e1 == nullptr) continue;
      ++n;
      const SatState a = sat_state(*e0, t0), m = sat_state(*em, tm), b = sat_state(*e1, t1);
      const Vec3 predicted = a.pos_m + (a.vel_m_s + m.vel_m_s * 4.0 + b.vel_m_s) * (dt_s / 6.0);
      s.max_jump_m = std::max(s.max_jump_m, (b.pos_m - predicted).norm());
    }
    s.max_sats = std::max(s.max_sats, n);
    s.min_sats = std::min(s.min_sats, n);
  }
  return s;
}

}  // namespace

TEST(Constellation, ModeNames) {
  for (NavMode m : {NavMode::kAuto, NavMode::kAsIs, NavMode::kRelabel, NavMode::kAlmanac}) {
    EXPECT_EQ(nav_mode_from_name(nav_mode_name(m)), m);
  }
  EXPECT_FALSE(nav_mode_from_name("today").has_value());
}

TEST(Constellation, AutoUsesDataThatCoverTheStartAsTheyAre) {
  const Constellation c = build_constellation(brdc(), at(kInside));
  EXPECT_EQ(c.mode, NavMode::kAsIs);
  EXPECT_EQ(c.shift_s, 0.0);
  EXPECT_EQ(c.nav.leap_seconds, 18);  // the header's
  EXPECT_EQ(c.nav.ephemerides.size(), brdc().ephemerides.size());
  EXPECT_TRUE(c.continues);
  EXPECT_NE(c.describe().find("nav data as they are"), std::string::npos) << c.describe();
}

TEST(Constellation, AutoMovesOldDataToTodayByWholeDays) {
  const Constellation c = build_constellation(brdc(), at(kToday));
  EXPECT_EQ(c.mode, NavMode::kRelabel);
  EXPECT_EQ(c.shift_s, 1788.0 * kSecondsPerDay);  // 2022-01-01 -> 2026-11-24
  EXPECT_FALSE(c.nav.leap_seconds.has_value());   // today's count: the table
  ASSERT_EQ(c.coverage.size(), 1u);
  EXPECT_TRUE(c.coverage.front().contains(kToday));
  EXPECT_EQ(time::calendar_text(c.coverage.front().begin), "2026-11-23 22:00:00 GPST");
  EXPECT_NE(c.describe().find("nav data moved +1788 days"), std::string::npos) << c.describe();
  // The sky at the start is the data's sky at the same time of day.
  const EphemerisStore moved(c.nav.ephemerides, c.store_options()), original(brdc().ephemerides);
  for (int prn = 1; prn <= system_size(GnssSystem::kGps); ++prn) {
    const Ephemeris* a = moved.select(SatId::gps(prn), kToday);
    const Ephemeris* b = original.select(SatId::gps(prn), kToday - c.shift_s);
    ASSERT_EQ(a == nullptr, b == nullptr) << prn;
    if (a == nullptr) continue;
    EXPECT_LT((sat_state(*a, kToday).pos_m - sat_state(*b, kToday - c.shift_s).pos_m).norm(), 1e-3) << prn;
  }
  // Every start on the same day gets the same shift: restarts see the same sky.
  EXPECT_EQ(build_constellation(brdc(), at(kToday + 30000.0)).shift_s, c.shift_s);
}

TEST(Constellation, AsIsOutsideTheDataIsAnErrorNamingTheCoverage) {
  try {
    (void)build_constellation(brdc(), at(kToday, NavMode::kAsIs));
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              kData + "/nav/brdc0010.22n: start 2026-11-24 10:33:28 GPST lies outside the nav data "
                      "(2021-12-31 22:00:00 GPST to 2022-01-02 01:59:44 GPST); nav mode \"relabel\" (or \"auto\") "
                      "moves the data to that date, or give a nav file for it");
  }
  EXPECT_THROW((void)build_constellation(NavData{}, at(kToday)), Error);
  EXPECT_THROW((void)build_constellation(brdc(), at(kToday, NavMode::kAlmanac)), Error);
}

// A file that starts late in its day: a start earlier in the day is mapped
// to the day after the data, where the orbits continue.
TEST(Constellation, RelabelOfDataStartingLateInTheDay) {
  NavData late = brdc();
  late.ephemerides.clear();
  for (const Ephemeris& e : brdc().ephemerides)
    if (!(e.toe < time::GpsTime(2190, 518400.0 + 36000.0))) late.ephemerides.push_back(e);
  const time::GpsTime early_morning(2446, 172800.0 + 3.0 * 3600.0);  // Tuesday 03:00
  const Constellation c = build_constellation(late, at(early_morning, NavMode::kRelabel));
  EXPECT_EQ(c.shift_s, (1788.0 - 1.0) * kSecondsPerDay);
  const EphemerisStore store(c.nav.ephemerides, c.store_options());
  int served = 0;
  for (int prn = 1; prn <= system_size(GnssSystem::kGps); ++prn) served += store.select(SatId::gps(prn), early_morning) != nullptr;
  EXPECT_GE(served, 28);
}

// Several files with a gap: relabel keeps the block the start falls in, so
// the continued orbits are never replaced by other ones days later.
TEST(Constellation, RelabelKeepsOneBlockOfData) {
  const NavData a = read_rinex_nav(kData + "/nav/NYA100NOR_S_20241240000_01D_GN.rnx");
  const NavData b = read_rinex_nav(kData + "/nav/NYA100NOR_S_20241270000_01D_GN.rnx");
  const NavData both = merge({a, b});
  ASSERT_EQ(EphemerisStore(both.ephemerides).coverage().size(), 2u);
  const Constellation c = build_constellation(both, at(kToday, NavMode::kRelabel));
  ASSERT_EQ(c.data_coverage.size(), 1u);
  // The data's main day is the one with the most sets: 05-06 (217 against 215).
  EXPECT_EQ(c.nav.ephemerides.size(), b.ephemerides.size());
  // as_is keeps both, with the gap.
  const Constellation d = build_constellation(both, at(time::GpsTime::from_calendar({2024, 5, 3, 6, 0, 0.0})));
  EXPECT_EQ(d.mode, NavMode::kAsIs);
  EXPECT_EQ(d.coverage.size(), 2u);
}

// Issue 12: no jump in positions or in the satellite set over 72 h from
// today, through the end of the data (the orbits continue), day boundaries
// and a GPS week boundary (the start is a Friday noon, week 2446).
TEST(Constellation, SeventyTwoHoursWithoutAJump) {
  const time::GpsTime friday_noon(2446, 5.0 * kSecondsPerDay + 43200.0);
  const Constellation c = build_constellation(brdc(), at(friday_noon));
  const EphemerisStore store(c.nav.ephemerides, c.store_options());
  const Steps s = walk(store, friday_noon, 72.0 * 3600.0, 30.0);
  // The data's own set changes (every 2 h) move a satellite by decimetres,
  // as in the real broadcast; a chained day would be kilometres.
  EXPECT_LT(s.max_jump_m, 5.0);
  RecordProperty("max_jump_m", std::to_string(s.max_jump_m));
  EXPECT_EQ(s.min_sats, s.max_sats);  // the constellation never thins out
  EXPECT_GE(s.min_sats, 29);          // brdc0010.22n: 32 PRNs, 3 flagged unhealthy
  // The same walk with the orbits stopped at the data's end loses them all.
  const EphemerisStore strict(c.nav.ephemerides, StoreOptions{false});
  EXPECT_EQ(walk(strict, friday_noon + 48.0 * 3600.0, 600.0, 60.0).max_sats, 0);
}

// And across the 1024-week rollover of 2038-11-21 (week 3072).
TEST(Constellation, AcrossTheWeek3072Rollover) {
  const time::GpsTime before(3071, 6.0 * kSecondsPerDay);
  const Constellation c = build_constellation(brdc(), at(before));
  const EphemerisStore store(c.nav.ephemerides, c.store_options());
  const Steps s = walk(store, before, 36.0 * 3600.0, 60.0);
  EXPECT_LT(s.max_jump_m, 5.0);
  EXPECT_EQ(s.min_sats, s.max_sats);
}

TEST(Constellation, AlmanacMovedToTheStartAndPropagated) {
  const std::vector<AlmanacEntry> alm = read_yuma(kData + "/almanac/yuma_week862_toa319488.alm", kToday.week());
  const Constellation c = build_constellation(alm, "yuma", brdc(), at(kToday));
  EXPECT_EQ(c.mode, NavMode::kAlmanac);
  EXPECT_TRUE(c.continues);
  EXPECT_EQ(std::fmod(c.shift_s, kSecondsPerDay), 0.0);
  const time::GpsTime toa = c.nav.ephemerides.front().toe;
  EXPECT_GE(kToday - toa, 0.0);
  EXPECT_LT(kToday - toa, kSecondsPerDay);
  EXPECT_TRUE(c.nav.klobuchar.valid);  // from the nav header given
  const EphemerisStore store(c.nav.ephemerides, c.store_options());
  // Geometry at the start: the almanac's at the start minus the shift.
  const Ephemeris* e = store.select(alm.front().sat, kToday);
  ASSERT_NE(e, nullptr);
  EXPECT_LT((sat_state(*e, kToday).pos_m - almanac_state(alm.front(), kToday - c.shift_s).pos_m).norm(), 1e-3);
  // Weeks on, without a jump (an almanac is one orbit per satellite).
  const Steps s = walk(store, kToday, 30.0 * kSecondsPerDay, 600.0);
  EXPECT_LT(s.max_jump_m, 0.1);
  EXPECT_EQ(s.min_sats, s.max_sats);
  EXPECT_GE(s.min_sats, 29);  // 31 entries, 2 unhealthy
  // A current almanac (a few days old) is used at its own date.
  const Constellation own = build_constellation(alm, "yuma", NavData{}, at(alm.front().toa + 3.0 * kSecondsPerDay));
  EXPECT_EQ(own.shift_s, 0.0);
  EXPECT_FALSE(own.nav.klobuchar.valid);
}

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "orbit_test_data.hpp"
#include "tests/support/alloc_counter.hpp"

using namespace gnssemu;
using namespace gnssemu::orbit;
using test::kNav;

namespace {


// A real set (brdc0010.22n PRN 1) re-timed for the selection tests.
Ephemeris base() {
  static const Ephemeris e = read_rinex_nav(kNav + "brdc0010.22n").ephemerides.front();
  return e;
}

Ephemeris at(int prn, int week, double toe_tow, int iode, int health = 0) {
  Ephemeris e = base();
  e.sat = SatId::gps(prn);
  e.toe = time::GpsTime(week, toe_tow);
  e.toc = e.toe;
  e.iode = iode;
  e.iodc = iode;
  e.health = health;
  e.transmit_known = true;
  e.transmit_tow_s = toe_tow - 7200.0;
  return e;
}

int iode_at(const EphemerisStore& s, int prn, const time::GpsTime& t) {
  const Ephemeris* e = s.select(SatId::gps(prn), t);
  return e ? e->iode : -1;
}

}  // namespace

TEST(EphemerisStore, NearestToe) {
  const EphemerisStore s({at(5, 2000, 14400, 3), at(5, 2000, 0, 1), at(5, 2000, 7200, 2)});
  EXPECT_EQ(s.count(SatId::gps(5)), 3u);
  EXPECT_EQ(s.size(), 3u);
  EXPECT_EQ(iode_at(s, 5, time::GpsTime(2000, 0)), 1);
  EXPECT_EQ(iode_at(s, 5, time::GpsTime(2000, 3599.9)), 1);
  EXPECT_EQ(iode_at(s, 5, time::GpsTime(2000, 3600.1)), 2);
  EXPECT_EQ(iode_at(s, 5, time::GpsTime(2000, 3600.0)), 2);  // tie: later toe
  EXPECT_EQ(iode_at(s, 5, time::GpsTime(2000, 11000)), 3);
  EXPECT_EQ(iode_at(s, 6, time::GpsTime(2000, 0)), -1);      // no sets for PRN 6
  EXPECT_EQ(s.select(SatId::gps(0), time::GpsTime(2000, 0)), nullptr);
  EXPECT_EQ(s.select(SatId::gps(33), time::GpsTime(2000, 0)), nullptr);
  EXPECT_EQ(s.count(SatId::gps(33)), 0u);
}

TEST(EphemerisStore, EverySatelliteHasItsOwnSets) {
  Ephemeris e05 = at(5, 2000, 0, 7);
  e05.sat = SatId(GnssSystem::kGalileo, 5);
  e05.gal_data_sources = 517;  // I/NAV E1-B + E5b, clock (E1,E5b): what an E1 user selects
  Ephemeris c63 = at(5, 2000, 0, 9);
  c63.sat = SatId(GnssSystem::kBeiDou, 63);
  const EphemerisStore s({at(5, 2000, 0, 1), e05, c63});
  EXPECT_EQ(s.count(SatId::gps(5)), 1u);
  EXPECT_EQ(s.count(SatId(GnssSystem::kGalileo, 5)), 1u);
  EXPECT_EQ(s.select(SatId::gps(5), time::GpsTime(2000, 60))->iode, 1);
  EXPECT_EQ(s.select(SatId(GnssSystem::kGalileo, 5), time::GpsTime(2000, 60))->iode, 7);
  EXPECT_EQ(s.select(SatId(GnssSystem::kBeiDou, 63), time::GpsTime(2000, 60))->iode, 9);
  EXPECT_EQ(s.select(SatId(GnssSystem::kGlonass, 5), time::GpsTime(2000, 60)), nullptr);
  EXPECT_EQ(s.select(SatId(GnssSystem::kGalileo, 37), time::GpsTime(2000, 60)), nullptr);  // not a valid id
}

TEST(EphemerisStore, ValidityEdges) {
  const EphemerisStore s({at(7, 2000, 100000, 1)});
  EXPECT_EQ(iode_at(s, 7, time::GpsTime(2000, 100000 + 7200.0)), 1);
  EXPECT_EQ(iode_at(s, 7, time::GpsTime(2000, 100000 - 7200.0)), 1);
  EXPECT_EQ(iode_at(s, 7, time::GpsTime(2000, 100000 + 7200.001)), -1);
  EXPECT_EQ(iode_at(s, 7, time::GpsTime(2000, 100000 - 7200.001)), -1);
  EXPECT_EQ(s.first_valid(), time::GpsTime(2000, 100000 - 7200.0));
  EXPECT_EQ(s.last_valid(), time::GpsTime(2000, 100000 + 7200.0));

  // A 6 h fit interval (IS-GPS-200 Table 20-XII) widens the window to +-3 h.
  Ephemeris six = at(7, 2000, 100000, 2);
  six.fit_interval_h = 6.0;
  const EphemerisStore s6({six});
  EXPECT_EQ(iode_at(s6, 7, time::GpsTime(2000, 100000 + 10800.0)), 2);
  EXPECT_EQ(iode_at(s6, 7, time::GpsTime(2000, 100000 + 10800.5)), -1);
}

TEST(EphemerisStore, UnhealthySkipped) {
  const EphemerisStore s({at(9, 2000, 0, 1), at(9, 2000, 7200, 2, 1), at(9, 2000, 14400, 3)});
  // Nearest (toe 7200) is unhealthy: the satellite is not used, the older
  // healthy set is not a fallback.
  EXPECT_EQ(iode_at(s, 9, time::GpsTime(2000, 3500)), 1);
  EXPECT_EQ(iode_at(s, 9, time::GpsTime(2000, 3700)), -1);
  EXPECT_EQ(iode_at(s, 9, time::GpsTime(2000, 7000)), -1);
  EXPECT_EQ(iode_at(s, 9, time::GpsTime(2000, 7400)), -1);
  EXPECT_EQ(iode_at(s, 9, time::GpsTime(2000, 10900)), 3);  // healthy again
  EXPECT_EQ(s.count(SatId::gps(9)), 3u);
  const EphemerisStore only_bad({at(9, 2000, 7200, 2, 63)});
  EXPECT_EQ(iode_at(only_bad, 9, time::GpsTime(2000, 7200)), -1);
}

// Healthy at toe 0, flagged unhealthy in the set at toe +2 h: from +2 h on
// the satellite is not used (not even the toe-0 set, still inside its window).
TEST(EphemerisStore, NewlyUnhealthyNotUsed) {
  const EphemerisStore s({at(10, 2000, 0, 1), at(10, 2000, 7200, 2, 1)});
  EXPECT_EQ(iode_at(s, 10, time::GpsTime(2000, 0)), 1);
  EXPECT_EQ(s.select(SatId::gps(10), time::GpsTime(2000, 7200)), nullptr);
}

TEST(EphemerisStore, DuplicateToePrefersLaterTransmission) {
  Ephemeris early = at(11, 2000, 7200, 10);
  Ephemeris late = at(11, 2000, 7200, 11);
  early.transmit_tow_s = 100.0;
  late.transmit_tow_s = 200.0;
  for (const auto& list : {std::vector<Ephemeris>{early, late}, std::vector<Ephemeris>{late, early}}) {
    const EphemerisStore s(list);
    EXPECT_EQ(iode_at(s, 11, time::GpsTime(2000, 7200)), 11);
    EXPECT_EQ(s.count(SatId::gps(11)), 2u);
  }
  // Unknown transmission time counts as earliest.
  Ephemeris unknown = at(11, 2000, 7200, 12);
  unknown.transmit_known = false;
  unknown.transmit_tow_s = 0.0;
  EXPECT_EQ(iode_at(EphemerisStore({early, unknown}), 11, time::GpsTime(2000, 7200)), 10);
  // Equal transmission time: file order, the later one wins.
  Ephemeris twin = early;
  twin.iode = 13;
  EXPECT_EQ(iode_at(EphemerisStore({early, twin}), 11, time::GpsTime(2000, 7200)), 13);
  // A later transmitted duplicate flagged unhealthy is the current broadcast:
  // the satellite is not used.
  Ephemeris bad_late = late;
  bad_late.health = 1;
  EXPECT_EQ(iode_at(EphemerisStore({early, bad_late}), 11, time::GpsTime(2000, 7200)), -1);
}

TEST(EphemerisStore, AcrossWeekBoundary) {
  // toe 1 h before the end of week 2190 and 1 h into week 2191.
  const EphemerisStore s({at(3, 2190, 604800 - 3600, 1), at(3, 2191, 3600, 2)});
  EXPECT_EQ(iode_at(s, 3, time::GpsTime(2190, 604800 - 100)), 1);
  EXPECT_EQ(iode_at(s, 3, time::GpsTime(2191, 100)), 2);
  EXPECT_EQ(iode_at(s, 3, time::GpsTime(2191, 0)), 2);  // tie at the week start: later toe
  // Previous week's toe used early in the new week, next week's toe late in the old one.
  const EphemerisStore prev({at(4, 2190, 604800 - 3600, 7)});
  EXPECT_EQ(iode_at(prev, 4, time::GpsTime(2191, 3600)), 7);
  EXPECT_EQ(iode_at(prev, 4, time::GpsTime(2191, 3601)), -1);
  const EphemerisStore next({at(4, 2191, 3600, 8)});
  EXPECT_EQ(iode_at(next, 4, time::GpsTime(2190, 604800 - 3600)), 8);
  EXPECT_EQ(iode_at(next, 4, time::GpsTime(2190, 604800 - 3601)), -1);
}

TEST(EphemerisStore, RealFileAndNoAllocation) {
  const NavData d = read_rinex_nav(kNav + "brdc0010.22n");
  const EphemerisStore s(d.ephemerides);
  EXPECT_EQ(s.size(), 422u);
  const time::GpsTime noon(2190, 518400 + 43200);
  int selected = 0;
  const long before = gnssemu::support::allocation_count();
  for (int prn = 1; prn <= system_size(GnssSystem::kGps); ++prn) {
    const Ephemeris* e = s.select(SatId::gps(prn), noon);
    if (e == nullptr) continue;
    ++selected;
    EXPECT_LE(std::fabs(noon - e->toe), 3600.0) << prn;  // brdc has a set every 2 h
    EXPECT_EQ(e->health, 0);
  }
  EXPECT_EQ(gnssemu::support::allocation_count(), before);
  EXPECT_GE(selected, 29);
  // brdc: first toc 00:00 (toe 2190/518400 - 2 h), last set toe 2191/0 (+2 h).
  EXPECT_EQ(s.first_valid(), time::GpsTime(2190, 518400 - 7200));
  EXPECT_EQ(s.last_valid(), time::GpsTime(2191, 7184));
}

// RTKLIB's tie (src/rtkcmn.c uniqeph sorts by transmission time, then toe;
// src/ephemeris.c seleph keeps the last set at the smallest |t - toe|): at
// equal distance the set transmitted later wins, whatever its toe.
TEST(EphemerisStore, TieGoesToTheLaterTransmission) {
  Ephemeris early_toe = at(12, 2000, 0, 1);
  Ephemeris late_toe = at(12, 2000, 7200, 2);
  early_toe.transmit_tow_s = 3000.0;  // a re-upload of the toe-0 set, sent after the toe-7200 one
  late_toe.transmit_tow_s = 100.0;
  EXPECT_EQ(iode_at(EphemerisStore({early_toe, late_toe}), 12, time::GpsTime(2000, 3600)), 1);
  EXPECT_EQ(iode_at(EphemerisStore({early_toe, late_toe}), 12, time::GpsTime(2000, 3599)), 1);
  EXPECT_EQ(iode_at(EphemerisStore({early_toe, late_toe}), 12, time::GpsTime(2000, 3601)), 2);
  // Transmission unknown for both: the later toe.
  early_toe.transmit_known = late_toe.transmit_known = false;
  EXPECT_EQ(iode_at(EphemerisStore({early_toe, late_toe}), 12, time::GpsTime(2000, 3600)), 2);
  // Across weeks the transmission times compare as instants, not as times of week.
  Ephemeris sat = at(13, 2190, 604800 - 3600, 7);  // sent 2 h before its toe (week 2190)
  Ephemeris sun = at(13, 2191, 3600, 8);           // sent 2 h before its toe (week 2191, tow -3600)
  EXPECT_EQ(iode_at(EphemerisStore({sat, sun}), 13, time::GpsTime(2191, 0)), 8);
}

// Past a satellite's last set: with continue_after_data that set goes on
// (its orbit propagated); without, nothing (RTKLIB). Gaps inside the data
// stay gaps, and an unhealthy last set keeps the satellite out.
TEST(EphemerisStore, ContinuesAfterTheLastSet) {
  const std::vector<Ephemeris> sets{at(14, 2000, 0, 1), at(14, 2000, 7200, 2), at(14, 2000, 50000, 3),
                                    at(15, 2000, 7200, 4, 1)};
  const EphemerisStore strict(sets), open(sets, StoreOptions{true});
  EXPECT_FALSE(strict.continues_after_data());
  EXPECT_TRUE(open.continues_after_data());
  const time::GpsTime days_later(2001, 100000);
  EXPECT_EQ(iode_at(strict, 14, days_later), -1);
  EXPECT_EQ(iode_at(open, 14, days_later), 3);
  EXPECT_EQ(iode_at(open, 14, time::GpsTime(2000, 50000 + 7201)), 3);
  EXPECT_EQ(iode_at(open, 14, time::GpsTime(2000, 30000)), -1);  // a gap in the data stays a gap
  EXPECT_EQ(iode_at(open, 14, time::GpsTime(1999, 500000)), -1);  // nothing before the data
  EXPECT_EQ(iode_at(open, 15, days_later), -1);                   // last set unhealthy
  const long before = gnssemu::support::allocation_count();
  for (int k = 0; k < 100; ++k) (void)open.select(SatId::gps(14), days_later + 60.0 * k);  // per-epoch path
  EXPECT_EQ(gnssemu::support::allocation_count(), before);
  const Ephemeris* e = open.select(SatId::gps(14), days_later);
  ASSERT_NE(e, nullptr);
  const SatState s = sat_state(*e, days_later);
  EXPECT_NEAR(s.pos_m.norm(), 26.56e6, 0.4e6);  // still a GPS orbit a week on (e ~ 0.01: +-0.27e6)
}

TEST(EphemerisStore, CoverageShowsGaps) {
  const EphemerisStore s({at(16, 2000, 0, 1), at(17, 2000, 7200, 2), at(16, 2000, 100000, 3)});
  const std::vector<TimeSpan> c = s.coverage();
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].begin, time::GpsTime(2000, 0) - 7200.0);
  EXPECT_EQ(c[0].end, time::GpsTime(2000, 14400));
  EXPECT_EQ(c[1].begin, time::GpsTime(2000, 100000 - 7200));
  EXPECT_EQ(c[1].end, time::GpsTime(2000, 100000 + 7200));
  EXPECT_TRUE(c[0].contains(time::GpsTime(2000, 14400)));
  EXPECT_FALSE(c[0].contains(time::GpsTime(2000, 14401)));
  EXPECT_TRUE(EphemerisStore().coverage().empty());
}

// Two files into one store: a daily file cut at noon into two reads back as
// the whole file at every time, overlap included.
TEST(EphemerisStore, MergedFilesActAsOne) {
  const NavData whole = read_rinex_nav(kNav + "brdc0010.22n");
  NavData am = whole, pm = whole;
  am.ephemerides.clear();
  pm.ephemerides.clear();
  const time::GpsTime noon(2190, 518400 + 43200);
  for (const Ephemeris& e : whole.ephemerides) (e.toc < noon ? am : pm).ephemerides.push_back(e);
  am.source = "am";
  pm.source = "pm";
  ASSERT_FALSE(am.ephemerides.empty());
  ASSERT_FALSE(pm.ephemerides.empty());
  const NavData both = merge({pm, am});
  EXPECT_EQ(both.source, "pm + am");
  EXPECT_EQ(both.leap_seconds, whole.leap_seconds);
  EXPECT_TRUE(both.klobuchar.valid);
  const EphemerisStore one(whole.ephemerides), two(both.ephemerides);
  for (double tow = 518400 - 7200; tow <= 518400 + 86400 + 7200; tow += 450) {
    for (int prn = 1; prn <= system_size(GnssSystem::kGps); ++prn) {
      const Ephemeris* a = one.select(SatId::gps(prn), time::GpsTime(2190, tow));
      const Ephemeris* b = two.select(SatId::gps(prn), time::GpsTime(2190, tow));
      ASSERT_EQ(a == nullptr, b == nullptr) << prn << " " << tow;
      if (a) {
        EXPECT_EQ(a->iode, b->iode) << prn << " " << tow;
      }
    }
  }
  // Leap-second counts that disagree leave the decision to the table.
  NavData other = pm;
  other.leap_seconds = 17;
  EXPECT_FALSE(merge({am, other}).leap_seconds.has_value());
}

// select(sat, t, until): the set chosen at t stays select()'s answer over
// [t, until), at the switching times themselves (toes, midpoints, validity
// edges) and on a grid, for every system, with and without continuation.
TEST(EphemerisStore, SelectionSpanHoldsUpToItsEnd) {
  const NavData nav = read_rinex_nav(kNav + "BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  for (const bool cont : {false, true}) {
    const EphemerisStore store(nav.ephemerides, StoreOptions{cont});
    const time::GpsTime t0 = store.first_valid() - 3600.0;
    const double day_s = (store.last_valid() - t0) + 7200.0;
    long checked = 0, reused = 0;
    for (int i = 0; i < kNumSats; ++i) {
      const SatId sat = SatId::from_index(i);
      if (store.count(sat) == 0) continue;
      std::vector<double> at_s;
      for (double s = 0.0; s < day_s; s += 7.3) at_s.push_back(s);
      for (const Ephemeris& e : nav.ephemerides) {
        if (e.sat != sat) continue;
        const double toe_s = e.toe - t0, hw = validity_half_window_s(e);
        for (const double s : {toe_s, toe_s - hw, toe_s + hw, toe_s + 900.0, toe_s + 1800.0, toe_s + 3600.0})
          for (const double d : {-1e-3, 0.0, 1e-3}) at_s.push_back(s + d);
      }
      std::sort(at_s.begin(), at_s.end());
      time::GpsTime until = t0;
      const Ephemeris* held = nullptr;
      for (const double s : at_s) {
        const time::GpsTime t = t0 + s;
        const Ephemeris* now = store.select(sat, t);
        if (t < until) {
          ASSERT_EQ(now, held) << sat.index() << " at " << s;
          ++reused;
        } else {
          held = store.select(sat, t, until);
          ASSERT_EQ(held, now);
        }
        ++checked;
      }
    }
    EXPECT_GT(reused, checked / 2);  // the switching times come in clusters
  }
}

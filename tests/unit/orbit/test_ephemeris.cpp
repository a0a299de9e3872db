// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/common/constants.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "orbit_test_data.hpp"

using namespace gnssemu;
using namespace gnssemu::orbit;
using test::kNav;

namespace {
const char* kFiles[] = {"brdc0010.22n", "ab422100.18n", "NYA100NOR_S_20241240000_01D_GN.rnx",
                        "ELKO00USA_R_20182100000_01D_MN.rnx"};
}  // namespace

// Analytic velocity against a central difference of position (h = 0.5 s:
// truncation ~ h^2/6 * jerk ~ 1e-5 m/s, rounding ~ 1e-8 m / 1 s).
TEST(Ephemeris, VelocityMatchesFiniteDifference) {
  double worst = 0.0, worst_drift = 0.0;
  for (const char* f : kFiles) {
    for (const Ephemeris& e : read_rinex_nav(kNav + f).ephemerides) {
      // Unhealthy sets of the other systems hold test orbits (ELKO's C16:
      // e = 0.49, sqrt(A) = 1992), beyond the difference's truncation bound.
      if (e.sat.system != GnssSystem::kGps && e.health != 0) continue;
      for (double dt : {-7200.0, -1800.0, 0.0, 2500.0, 7200.0}) {
        const time::GpsTime t = e.toe + dt;
        const double h = 0.5;
        const SatState s = sat_state(e, t);
        const SatState p = sat_state(e, t + h), m = sat_state(e, t - h);
        const Vec3 fd = (p.pos_m - m.pos_m) / (2 * h);
        const double err = (s.vel_m_s - fd).norm();
        worst = std::max(worst, err);
        EXPECT_LE(err, 1e-3) << f << " " << sat_name(e.sat).data() << " dt " << dt;
        const double drift_fd = (p.clk_bias_s - m.clk_bias_s) / (2 * h);
        worst_drift = std::max(worst_drift, std::fabs(s.clk_drift_s_s - drift_fd));
        EXPECT_LE(std::fabs(s.clk_drift_s_s - drift_fd), 1e-15) << f << " PRN " << int(e.sat.number);
      }
    }
  }
  std::printf("worst |v - fd| %.3g m/s, |drift - fd| %.3g s/s\n", worst, worst_drift);
}

TEST(Ephemeris, PhysicalSanity) {
  for (const Ephemeris& e : read_rinex_nav(kNav + "brdc0010.22n").ephemerides) {
    const SatState s = sat_state(e, e.toe + 600.0);
    const double r = s.pos_m.norm();
    const double a = e.sqrt_a_sqrtm * e.sqrt_a_sqrtm;
    EXPECT_GT(r, a * (1 - e.e) - 2000.0);
    EXPECT_LT(r, a * (1 + e.e) + 2000.0);
    // ECEF speed of a GPS satellite: 1.5-4.5 km/s (inertial ~3.9 km/s).
    EXPECT_GT(s.vel_m_s.norm(), 1500.0);
    EXPECT_LT(s.vel_m_s.norm(), 4500.0);
    // |relativistic term| <= |F| e sqrt(A) (< 50 ns for e < 0.02).
    EXPECT_LE(std::fabs(s.relativity_s), std::fabs(kRelativityF_s_sqrtm) * e.e * e.sqrt_a_sqrtm + 1e-18);
    EXPECT_NEAR(s.clk_bias_s - s.relativity_s, e.af0_s + e.af1_s_s * (e.toe + 600.0 - e.toc), 1e-15);
  }
}

// Consecutive uploads describe the same orbit: at the midpoint between their
// toes they agree to a few metres (broadcast orbit error is ~1 m).
TEST(Ephemeris, ConsecutiveSetsAgreeAtMidpoint) {
  const NavData d = read_rinex_nav(kNav + "brdc0010.22n");
  std::map<int, std::vector<const Ephemeris*>> by_prn;
  for (const Ephemeris& e : d.ephemerides) by_prn[e.sat.number].push_back(&e);
  int pairs = 0;
  double worst_pos = 0, worst_clk = 0;
  for (auto& [prn, v] : by_prn) {
    for (std::size_t i = 1; i < v.size(); ++i) {
      const Ephemeris& a = *v[i - 1];
      const Ephemeris& b = *v[i];
      const double gap = b.toe - a.toe;
      if (gap < 3600 || gap > 7200 || a.health || b.health) continue;
      const time::GpsTime mid = a.toe + gap / 2;
      const SatState sa = sat_state(a, mid), sb = sat_state(b, mid);
      const double dp = (sa.pos_m - sb.pos_m).norm();
      const double dc = std::fabs(sa.clk_bias_s - sb.clk_bias_s) * kSpeedOfLight_m_s;
      worst_pos = std::max(worst_pos, dp);
      worst_clk = std::max(worst_clk, dc);
      EXPECT_LT(dp, 10.0) << "PRN " << prn << " toe " << a.toe.tow_s();
      EXPECT_LT(dc, 10.0) << "PRN " << prn << " toe " << a.toe.tow_s();
      ++pairs;
    }
  }
  EXPECT_GE(pairs, 300);
  std::printf("%d pairs: worst position %.2f m, clock %.2f m\n", pairs, worst_pos, worst_clk);
}

TEST(Ephemeris, ClockAtSatelliteTime) {
  const Ephemeris e = read_rinex_nav(kNav + "brdc0010.22n").ephemerides.front();
  const time::GpsTime t_sv = e.toc + 1234.5;
  const double dt = sat_clock_at_sv_time(e, t_sv);
  // Fixed point: dt = clk(t_sv - dt).
  EXPECT_NEAR(dt, sat_state(e, t_sv - dt).clk_bias_s, 1e-17);
  EXPECT_NEAR(dt, 0.469126738608e-03, 1e-7);  // af0 dominates
}

TEST(Ephemeris, ValidityWindow) {
  Ephemeris e;
  EXPECT_DOUBLE_EQ(validity_half_window_s(e), 7200.0);  // unknown -> 4 h fit
  e.fit_interval_h = 4.0;
  EXPECT_DOUBLE_EQ(validity_half_window_s(e), 7200.0);
  e.fit_interval_h = 6.0;
  EXPECT_DOUBLE_EQ(validity_half_window_s(e), 10800.0);
}

// Continuous times: evaluating a set whose toe is in the next week from the
// end of the previous week equals the same set shifted by a whole week.
TEST(Ephemeris, WeekCrossover) {
  const NavData d = read_rinex_nav(kNav + "ELKO00USA_R_20182100000_01D_MN.rnx");
  const Ephemeris* e = nullptr;
  for (const Ephemeris& x : d.ephemerides) {
    if (x.sat == SatId::gps(2) && x.toe == time::GpsTime(2012, 0.0)) e = &x;
  }
  ASSERT_NE(e, nullptr);
  const time::GpsTime t(2011, 604800 - 1800);  // 30 min before the week starts
  const SatState s = sat_state(*e, t);
  Ephemeris shifted = *e;
  shifted.toe = time::GpsTime(2013, 0.0);
  shifted.toc = time::GpsTime(2013, 0.0);
  const SatState s2 = sat_state(shifted, time::GpsTime(2012, 604800 - 1800));
  EXPECT_NEAR((s.pos_m - s2.pos_m).norm(), 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(s.clk_bias_s, s2.clk_bias_s);
  // And it is continuous with the previous week's set at that time (same orbit).
  const EphemerisStore store(d.ephemerides);
  const Ephemeris* prev = store.select(SatId::gps(2), t - 3600);
  ASSERT_NE(prev, nullptr);
  EXPECT_EQ(prev->toe, time::GpsTime(2011, 597600.0));
  EXPECT_LT((sat_state(*prev, t).pos_m - s.pos_m).norm(), 10.0);
}

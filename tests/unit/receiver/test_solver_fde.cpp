// SPDX-License-Identifier: Apache-2.0
// Fault detection and exclusion in the solver: a satellite with an NLOS
// bias is excluded (largest normalised residual) and the epoch re-solved,
// while at least 5 satellites remain; otherwise no fix.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/world/sky/sky.hpp"
#include "core/receiver/solution/solver.hpp"
#include "synthetic_sky.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::receiver::solver_fde_test {
namespace {

const time::GpsTime kToe(2190, 200000.0);
const time::GpsTime kT = kToe + 60.0;
const Lla kSite{48.87 * kDegToRad, 2.29 * kDegToRad, 60.0};

struct Sky {
  std::vector<orbit::Ephemeris> eph;
  Ecef truth = geo::ecef_from_lla(kSite);

  // (az, el) in deg; satellites in this order get measurement indices 0..n-1.
  explicit Sky(const std::vector<std::array<double, 2>>& az_el) {
    for (std::size_t i = 0; i < az_el.size(); ++i) {
      const Ecef p = test::sat_position_at(truth, kSite, az_el[i][0] * kDegToRad, az_el[i][1] * kDegToRad);
      eph.push_back(test::placed_eph(static_cast<int>(i) + 1, kToe, kT - 0.075, p));
    }
  }

  /// Pseudoranges the solver's own model predicts at the truth (receiver
  /// clock 0, no atmosphere corrections), plus noise_m[i] + bias_m[i].
  SolverInput input(const std::vector<double>& bias_m) const {
    SolverInput in;
    in.t_rx_local = kT;
    in.num_meas = static_cast<int>(eph.size());
    // A small fixed "noise" pattern (m) well within the solver's 1.2 m sigma.
    const double noise_m[] = {0.4, -0.7, 0.2, 0.9, -0.3, -0.5, 0.6, -0.1, 0.3, -0.8, 0.5, 0.1};
    for (std::size_t i = 0; i < eph.size(); ++i) {
      const orbit::Ephemeris& e = eph[i];
      double pr = 2.2e7;
      for (int it = 0; it < 10; ++it) {
        const time::GpsTime t_sv = kT - pr / kSpeedOfLight_m_s;
        const double dt0 = orbit::sat_state(e, t_sv).clk_bias_s - e.tgd_s;
        const time::GpsTime t_tx = t_sv - dt0;
        const orbit::SatState st = orbit::sat_state(e, t_tx);
        const Ecef p = world::rotate_earth(st.pos_m, kOmegaEarth_rad_s * (kT - t_tx));
        pr = (p - truth).norm() - kSpeedOfLight_m_s * (st.clk_bias_s - e.tgd_s);
      }
      Measurement& m = in.meas[i];
      m.eph = &e;
      m.pseudorange_m = pr + noise_m[i % 12] + (i < bias_m.size() ? bias_m[i] : 0.0);
      m.cn0_dbhz = 0.0;
    }
    return in;
  }
};

using test::plain_solver;

const std::vector<std::array<double, 2>> kNine = {{0, 75},  {30, 40},  {100, 40}, {170, 40}, {250, 40},
                                                  {320, 40}, {70, 15}, {200, 15}, {290, 15}};

TEST(SolverFde, OneNlosBiasedSatelliteAmongNineIsExcluded) {
  const Sky sky(kNine);
  Solver s(plain_solver(), 20.0);
  SolverOutput out;
  s.solve(sky.input({}), out);
  ASSERT_EQ(out.type, FixType::k3D);
  EXPECT_EQ(out.num_used, 9);
  EXPECT_EQ(out.num_excluded, 0);
  for (const int bad : {2, 6, 0}) {  // 40 deg, 15 deg, 75 deg elevation
    std::vector<double> bias(9, 0.0);
    bias[bad] = 60.0;
    s.solve(sky.input(bias), out);
    ASSERT_EQ(out.type, FixType::k3D) << bad;
    EXPECT_EQ(out.num_used, 8);
    EXPECT_EQ(out.num_excluded, 1);
    for (int i = 0; i < 9; ++i) EXPECT_EQ(out.excluded[i], i == bad) << bad << " " << i;
    EXPECT_EQ(out.residual_m[bad], 0.0);
    EXPECT_LT((out.pos_m - sky.truth).norm(), 3.0) << bad;
    EXPECT_LE(out.chi2, s.chi2_threshold(out.dof));
  }
  // Without the test, the bias pulls the fix.
  SolverConfig off = plain_solver();
  off.residual_test_pfa = 0.0;
  Solver unchecked(off, 20.0);
  std::vector<double> bias(9, 0.0);
  bias[2] = 60.0;
  unchecked.solve(sky.input(bias), out);
  ASSERT_EQ(out.type, FixType::k3D);
  EXPECT_EQ(out.num_used, 9);
  EXPECT_GT((out.pos_m - sky.truth).norm(), 10.0);
}

TEST(SolverFde, SingleFaultByDefaultTwoBiasedSatellitesGiveNoFix) {
  // RAIM's single-fault assumption: one exclusion cannot make the set consistent.
  const Sky sky(kNine);
  Solver s(plain_solver(), 20.0);
  SolverOutput out;
  std::vector<double> bias(9, 0.0);
  bias[1] = 60.0;
  bias[7] = 45.0;
  s.solve(sky.input(bias), out);
  EXPECT_EQ(out.type, FixType::kNone);
  EXPECT_EQ(out.num_used, 0);
  // Detection only: not even the one.
  SolverConfig none = plain_solver();
  none.max_exclusions = 0;
  Solver d(none, 20.0);
  bias[7] = 0.0;
  d.solve(sky.input(bias), out);
  EXPECT_EQ(out.type, FixType::kNone);
}

TEST(SolverFde, TwoBiasedSatellitesAreBothExcludedWhenTwoAreAllowed) {
  const Sky sky(kNine);
  SolverConfig two = plain_solver();
  two.max_exclusions = 2;
  Solver s(two, 20.0);
  SolverOutput out;
  std::vector<double> bias(9, 0.0);
  bias[1] = 60.0;
  bias[7] = 45.0;
  const long before = support::allocation_count();
  s.solve(sky.input(bias), out);
  ASSERT_EQ(out.type, FixType::k3D);
  EXPECT_EQ(out.num_used, 7);
  EXPECT_EQ(out.num_excluded, 2);
  EXPECT_TRUE(out.excluded[1]);
  EXPECT_TRUE(out.excluded[7]);
  EXPECT_LT((out.pos_m - sky.truth).norm(), 3.0);
  // The input is built outside the count; solve itself allocates nothing.
  const SolverInput in = sky.input(bias);
  const long mid = support::allocation_count();
  s.solve(in, out);
  EXPECT_EQ(support::allocation_count() - mid, 0);
  (void)before;
}

TEST(SolverFde, NoFixWhenExclusionWouldLeaveFewerThanFive) {
  // Five satellites, one biased: excluding it leaves 4, which cannot be
  // tested: no fix, as before fault exclusion.
  const Sky five({{0, 75}, {60, 35}, {150, 35}, {240, 35}, {320, 30}});
  Solver s(plain_solver(), 20.0);
  SolverOutput out;
  s.solve(five.input({}), out);
  ASSERT_EQ(out.type, FixType::k3D);
  s.solve(five.input({0.0, 60.0}), out);
  EXPECT_EQ(out.type, FixType::kNone);
  EXPECT_EQ(out.num_used, 0);
}

}  // namespace
}  // namespace gnssemu::receiver::solver_fde_test

// SPDX-License-Identifier: Apache-2.0
// The solver with several systems: one clock plus an inter-system bias per
// further system present, recovered from synthetic measurements; a system
// with one satellite; too few measurements for the states give no fix,
// never a crash; no allocation.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/receiver/solution/solver.hpp"
#include "core/world/sky/sky.hpp"
#include "synthetic_sky.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::receiver::solver_multi_gnss_test {
namespace {

const time::GpsTime kToe(2190, 200000.0);
const time::GpsTime kT = kToe + 60.0;
const Lla kSite{48.87 * kDegToRad, 2.29 * kDegToRad, 60.0};

struct Placed {
  SatId sat;
  double az_deg, el_deg;
};

struct Sky {
  std::vector<orbit::Ephemeris> eph;
  Ecef truth = geo::ecef_from_lla(kSite);

  explicit Sky(const std::vector<Placed>& sats) {
    for (std::size_t i = 0; i < sats.size(); ++i) {
      const Ecef p = test::sat_position_at(truth, kSite, sats[i].az_deg * kDegToRad, sats[i].el_deg * kDegToRad);
      orbit::Ephemeris e = test::placed_eph(static_cast<int>(i) + 1, kToe, kT - 0.075, p);
      e.sat = sats[i].sat;  // the Kepler orbit evaluated with that system's constants
      eph.push_back(e);
    }
  }

  /// Exact pseudoranges at the truth with receiver clock clock_m plus, per
  /// system, isb_m[system].
  SolverInput input(double clock_m, const std::array<double, kNumSystems>& isb_m) const {
    SolverInput in;
    in.t_rx_local = kT;
    in.num_meas = static_cast<int>(eph.size());
    for (std::size_t i = 0; i < eph.size(); ++i) {
      const orbit::Ephemeris& e = eph[i];
      const double rx_clock_m = clock_m + isb_m[static_cast<std::size_t>(e.sat.system)];
      double pr = 2.2e7;
      for (int it = 0; it < 10; ++it) {
        const time::GpsTime t_sv = kT - pr / kSpeedOfLight_m_s;
        const double dt0 = orbit::sat_state(e, t_sv).clk_bias_s - e.tgd_s;
        const time::GpsTime t_tx = t_sv - dt0;
        const orbit::SatState st = orbit::sat_state(e, t_tx);
        const double tau = (kT - t_tx) - rx_clock_m / kSpeedOfLight_m_s;
        const Ecef p = world::rotate_earth(st.pos_m, kOmegaEarth_rad_s * tau);
        pr = (p - truth).norm() + rx_clock_m - kSpeedOfLight_m_s * (st.clk_bias_s - e.tgd_s);
      }
      in.meas[i].eph = &e;
      in.meas[i].pseudorange_m = pr;
    }
    return in;
  }
};

using test::plain_solver;

constexpr GnssSystem G = GnssSystem::kGps, R = GnssSystem::kGlonass, E = GnssSystem::kGalileo,
                     C = GnssSystem::kBeiDou, J = GnssSystem::kQzss;

const std::vector<Placed> kMixed = {
    {{G, 3}, 0, 75},    {{G, 7}, 100, 40},  {{G, 12}, 250, 40}, {{G, 30}, 320, 20}, {{E, 11}, 30, 50},
    {{E, 24}, 170, 35}, {{E, 30}, 290, 15}, {{C, 21}, 60, 25},  {{C, 35}, 210, 60}, {{C, 44}, 140, 12},
};

TEST(SolverMultiGnss, RecoversKnownInterSystemBiases) {
  const Sky sky(kMixed);
  Solver s(plain_solver(), 20.0);
  SolverOutput out;
  std::array<double, kNumSystems> isb{};
  isb[static_cast<std::size_t>(E)] = 31.5;
  isb[static_cast<std::size_t>(C)] = -47.25;
  s.solve(sky.input(120.0, isb), out);
  ASSERT_EQ(out.type, FixType::k3D);
  EXPECT_EQ(out.num_used, 10);
  EXPECT_EQ(out.dof, 10 - 6);
  EXPECT_EQ(out.clock_systems, SystemSet::only(G).with(E).with(C));
  EXPECT_LT((out.pos_m - sky.truth).norm(), 1e-3);
  EXPECT_NEAR(out.clock_m, 120.0, 1e-3);
  EXPECT_NEAR(out.isb_m[static_cast<std::size_t>(E)], 31.5, 1e-3);
  EXPECT_NEAR(out.isb_m[static_cast<std::size_t>(C)], -47.25, 1e-3);
  EXPECT_EQ(out.isb_m[static_cast<std::size_t>(G)], 0.0);
  for (int i = 0; i < out.num_used; ++i) EXPECT_LT(std::fabs(out.residual_m[i]), 1e-3) << i;
  // DOP: more states than one clock, so worse than the same sky with one clock.
  Sky one_clock(kMixed);
  for (auto& e : one_clock.eph) e.sat.system = G;
  SolverOutput g;
  s.solve(one_clock.input(120.0, {}), g);
  ASSERT_EQ(g.type, FixType::k3D);
  EXPECT_GT(out.dop.pdop, g.dop.pdop);
  EXPECT_EQ(g.clock_systems, SystemSet::only(G));

  // The same per epoch without allocation.
  const SolverInput in = sky.input(120.0, isb);
  const long before = support::allocation_count();
  s.solve(in, out);
  EXPECT_EQ(support::allocation_count() - before, 0);
  ASSERT_EQ(out.type, FixType::k3D);
}

TEST(SolverMultiGnss, NavigationFilterRowsSeeOneClock) {
  const Sky sky(kMixed);
  Solver s(plain_solver(), 20.0);
  SolverOutput out;
  std::array<double, kNumSystems> isb{};
  isb[static_cast<std::size_t>(E)] = 12.0;
  isb[static_cast<std::size_t>(C)] = -8.0;
  const SolverInput in = sky.input(50.0, isb);
  s.solve(in, out);
  ASSERT_EQ(out.type, FixType::k3D);
  std::array<MeasurementRow, kMaxSatsInView> rows{};
  ASSERT_EQ(s.measurement_model(in, sky.truth, 50.0, rows), 10);
  for (int i = 0; i < 10; ++i) EXPECT_LT(std::fabs(rows[i].range_resid_m), 1e-3) << i;
}

TEST(SolverMultiGnss, ASystemWithOneSatelliteAddsNothingButItsBias) {
  std::vector<Placed> sats = {{{G, 3}, 0, 75}, {{G, 7}, 100, 40}, {{G, 12}, 250, 40}, {{G, 30}, 320, 20},
                              {{G, 5}, 30, 50}};
  const Sky gps(sats);
  sats.push_back({{R, 9}, 170, 35});
  sats.back().sat = SatId(E, 9);  // a Kepler system (the test sky places Keplerian orbits)
  const Sky mixed(sats);
  Solver s(plain_solver(), 20.0);
  SolverOutput a, b;
  std::array<double, kNumSystems> isb{};
  isb[static_cast<std::size_t>(E)] = 80.0;
  s.solve(gps.input(10.0, {}), a);
  s.solve(mixed.input(10.0, isb), b);
  ASSERT_EQ(a.type, FixType::k3D);
  ASSERT_EQ(b.type, FixType::k3D);
  EXPECT_EQ(b.num_used, 6);
  EXPECT_EQ(b.dof, a.dof);
  EXPECT_LT((a.pos_m - b.pos_m).norm(), 1e-6);
  EXPECT_NEAR(b.isb_m[static_cast<std::size_t>(E)], 80.0, 1e-3);
  EXPECT_NEAR(a.dop.pdop, b.dop.pdop, 1e-9);
}

TEST(SolverMultiGnss, QzssSharesTheGpsClockWhenConfigured) {
  const std::vector<Placed> sats = {{{G, 3}, 0, 75},  {{G, 7}, 100, 40}, {{G, 12}, 250, 40},
                                    {{J, 2}, 320, 20}, {{J, 3}, 30, 50}};
  const Sky sky(sats);
  SolverConfig cfg = plain_solver();
  cfg.qzss_own_clock = false;
  Solver shared(cfg, 20.0);
  SolverOutput out;
  shared.solve(sky.input(5.0, {}), out);
  ASSERT_EQ(out.type, FixType::k3D);
  EXPECT_EQ(out.clock_systems, SystemSet::only(G));
  EXPECT_EQ(out.dof, 1);
  Solver own(plain_solver(), 20.0);
  own.solve(sky.input(5.0, {}), out);
  ASSERT_EQ(out.type, FixType::k3D);  // 5 measurements, 5 states
  EXPECT_EQ(out.clock_systems, SystemSet::only(G).with(J));
  EXPECT_EQ(out.dof, 0);
}

TEST(SolverMultiGnss, TooFewMeasurementsForTheStatesGiveNoFix) {
  Solver s(plain_solver(), 20.0);
  SolverOutput out;
  // 5 measurements, 3 systems: 6 states.
  const Sky three({{{G, 3}, 0, 75}, {{G, 7}, 100, 40}, {{G, 12}, 250, 40}, {{E, 11}, 30, 50}, {{C, 21}, 200, 30}});
  s.solve(three.input(0.0, {}), out);
  EXPECT_EQ(out.type, FixType::kNone);
  EXPECT_EQ(out.num_used, 0);
  // One satellite per system, four systems: 7 states.
  const Sky lone({{{G, 3}, 0, 75}, {{E, 11}, 100, 40}, {{C, 21}, 250, 40}, {{J, 2}, 30, 50}});
  s.solve(lone.input(0.0, {}), out);
  EXPECT_EQ(out.type, FixType::kNone);
  // Every satellite at one place: singular, whatever the systems.
  const Sky same({{{G, 3}, 0, 75}, {{G, 4}, 0, 75}, {{E, 11}, 0, 75}, {{E, 12}, 0, 75}, {{C, 21}, 0, 75},
                  {{C, 22}, 0, 75}, {{G, 5}, 0, 75}});
  s.solve(same.input(0.0, {}), out);
  EXPECT_EQ(out.type, FixType::kNone);
  // A Galileo-only sky: its clock is the first clock.
  const Sky gal({{{E, 3}, 0, 75}, {{E, 7}, 100, 40}, {{E, 12}, 250, 40}, {{E, 30}, 320, 20}, {{E, 5}, 30, 50}});
  s.solve(gal.input(42.0, {}), out);
  ASSERT_EQ(out.type, FixType::k3D);
  EXPECT_EQ(out.clock_systems, SystemSet::only(E));
  EXPECT_NEAR(out.clock_m, 42.0, 1e-3);
}

TEST(SolverMultiGnss, ExclusionWorksAcrossSystems) {
  const Sky sky(kMixed);
  Solver s(plain_solver(), 20.0);
  SolverOutput out;
  SolverInput in = sky.input(0.0, {});
  in.meas[5].pseudorange_m += 60.0;  // E24
  s.solve(in, out);
  ASSERT_EQ(out.type, FixType::k3D);
  EXPECT_EQ(out.num_excluded, 1);
  EXPECT_TRUE(out.excluded[5]);
  EXPECT_LT((out.pos_m - sky.truth).norm(), 1e-2);
}

}  // namespace
}  // namespace gnssemu::receiver::solver_multi_gnss_test

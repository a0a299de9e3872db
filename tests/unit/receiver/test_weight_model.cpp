// SPDX-License-Identifier: Apache-2.0
// The solver's pseudorange variance: the default elevation + C/N0 model, the
// RTKLIB single-point model (pntpos varerr + URA + code bias + model
// variance of the broadcast corrections) and their use in the solver.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/geo/geodesy.hpp"
#include "core/receiver/solution/solver.hpp"
#include "core/receiver/solution/weight_model.hpp"
#include "core/world/sky/sky.hpp"
#include "synthetic_sky.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::receiver {
namespace {

TEST(WeightModel, UraBoundIsTheUpperEndOfTheIsGps200Interval) {
  // RINEX gives the URA in metres (N = 0 is often written 2.0 or 2.4 m).
  EXPECT_EQ(ura_bound_m(0.0), 2.4);
  EXPECT_EQ(ura_bound_m(2.0), 2.4);
  EXPECT_EQ(ura_bound_m(2.4), 2.4);
  EXPECT_EQ(ura_bound_m(2.8), 3.4);
  EXPECT_EQ(ura_bound_m(4.85), 4.85);
  EXPECT_EQ(ura_bound_m(5.0), 6.85);
  EXPECT_EQ(ura_bound_m(2000.0), 3072.0);
  EXPECT_EQ(ura_bound_m(7000.0), 6144.0);
  EXPECT_EQ(ura_bound_m(std::numeric_limits<double>::quiet_NaN()), 6144.0);
}

TEST(WeightModel, DefaultModelIsElevationSquaredPlusCn0Term) {
  const SolverConfig c;  // a 1.2 m, b 0.3 m, c 150 m sqrt(Hz)
  const double sin_el = 0.5;
  EXPECT_NEAR(measurement_variance_m2(c, sin_el, 45.0, 2.0),
              1.44 + 0.09 / 0.25 + 22500.0 * std::pow(10.0, -4.5), 1e-12);
  // No C/N0 (RINEX without S1C): the C/N0 term is left out; URA is not used.
  EXPECT_NEAR(measurement_variance_m2(c, sin_el, 0.0, 100.0), 1.44 + 0.36, 1e-12);
  EXPECT_NEAR(measurement_variance_m2(c, sin_el, std::numeric_limits<double>::quiet_NaN(), 2.0), 1.8, 1e-12);
  // The elevation is held at sin 0.05 (2.9 deg).
  EXPECT_NEAR(elevation_variance_m2(c, -0.3), 1.44 + 0.09 / 0.0025, 1e-9);
}

TEST(WeightModel, RtklibModelAsPntpos) {
  const SolverConfig c = rtklib_single_point();
  EXPECT_EQ(c.weights, WeightModel::kRtklib);
  // varerr: 100^2 (0.003^2 + 0.003^2 / sin el) = 0.09 + 0.09 / sin el; URA
  // 2.0 m -> index 0 -> 2.4 m; ERR_CBIAS 0.3 m. C/N0 is not used.
  for (double el_deg : {10.0, 30.0, 90.0}) {
    const double s = std::sin(el_deg * kDegToRad);
    EXPECT_NEAR(measurement_variance_m2(c, s, 45.0, 2.0), 0.09 + 0.09 / s + 2.4 * 2.4 + 0.09, 1e-12) << el_deg;
    EXPECT_NEAR(measurement_variance_m2(c, s, 25.0, 2.0), measurement_variance_m2(c, s, 50.0, 2.0), 1e-15);
  }
  // ERR_BRDCI 0.5 x the Klobuchar delay, ERR_SAAS 0.3 m / (sin el + 0.1).
  EXPECT_NEAR(correction_variance_m2(c, 5.0, 0.5), 0.25 * 25.0 + 0.25, 1e-12);
  SolverConfig off = c;
  off.iono = atmosphere::IonoCorrection::kNone;
  EXPECT_NEAR(correction_variance_m2(off, 5.0, 0.5), 0.25, 1e-12);
  off.tropo = atmosphere::TropoCorrection::kNone;
  EXPECT_EQ(correction_variance_m2(off, 5.0, 0.5), 0.0);
  // The default receiver has no model-variance terms.
  EXPECT_EQ(correction_variance_m2(SolverConfig{}, 5.0, 0.5), 0.0);
  // The preset is RTKLIB's single-point processing otherwise too.
  EXPECT_EQ(c.tropo, atmosphere::TropoCorrection::kSaastamoinenCosZ);
  EXPECT_EQ(c.iono, atmosphere::IonoCorrection::kKlobuchar);
  EXPECT_EQ(c.max_exclusions, 0);
  EXPECT_EQ(c.max_iterations, 10);
  EXPECT_NO_THROW(validate(c));
}

// Six satellites at known elevations: the solver's assumed sigma (reported
// as sigma_uere_m) is the weight model's, and the caller's correction
// variance joins it.
struct SixSats {
  const time::GpsTime toe{2190, 200000.0};
  const time::GpsTime t = toe + 60.0;
  const Lla site{45.0 * kDegToRad, 7.0 * kDegToRad, 300.0};
  const Ecef truth = geo::ecef_from_lla(site);
  const std::array<std::array<double, 2>, 6> az_el{{{0, 80}, {60, 45}, {140, 30}, {210, 20}, {280, 35}, {330, 15}}};
  std::vector<orbit::Ephemeris> eph;

  SixSats() {
    for (std::size_t i = 0; i < az_el.size(); ++i) {
      const Ecef p = test::sat_position_at(truth, site, az_el[i][0] * kDegToRad, az_el[i][1] * kDegToRad);
      eph.push_back(test::placed_eph(static_cast<int>(i) + 1, toe, t - 0.075, p));
      eph.back().sv_accuracy_m = i == 0 ? 5.0 : 2.0;  // one satellite with URA index 3
    }
  }

  SolverInput input(double correction_var_m2) const {
    SolverInput in;
    in.t_rx_local = t;
    in.num_meas = static_cast<int>(eph.size());
    for (std::size_t i = 0; i < eph.size(); ++i) {
      double pr = 2.2e7;
      for (int it = 0; it < 10; ++it) {
        const time::GpsTime t_sv = t - pr / kSpeedOfLight_m_s;
        const time::GpsTime t_tx = t_sv - (orbit::sat_state(eph[i], t_sv).clk_bias_s - eph[i].tgd_s);
        const orbit::SatState st = orbit::sat_state(eph[i], t_tx);
        pr = (world::rotate_earth(st.pos_m, kOmegaEarth_rad_s * (t - t_tx)) - truth).norm() -
             kSpeedOfLight_m_s * (st.clk_bias_s - eph[i].tgd_s);
      }
      in.meas[i].eph = &eph[i];
      in.meas[i].pseudorange_m = pr;
      in.meas[i].cn0_dbhz = 45.0;
      in.meas[i].correction_var_m2 = correction_var_m2;
    }
    return in;
  }

  double expected_sigma_uere_m(const SolverConfig& c, double correction_var_m2) const {
    double sum = 0.0;
    for (std::size_t i = 0; i < eph.size(); ++i)
      sum += measurement_variance_m2(c, std::sin(az_el[i][1] * kDegToRad), 45.0, eph[i].sv_accuracy_m) +
             correction_var_m2;
    return std::sqrt(sum / static_cast<double>(eph.size()));
  }
};

SolverConfig uncorrected(SolverConfig c) {
  c.iono = atmosphere::IonoCorrection::kNone;
  c.tropo = atmosphere::TropoCorrection::kNone;
  return c;
}

TEST(WeightModel, SolverWeightsWithTheConfiguredModel) {
  const SixSats sky;
  for (const SolverConfig& c : {uncorrected(SolverConfig{}), uncorrected(rtklib_single_point())}) {
    for (double extra_m2 : {0.0, 4.0}) {
      Solver s(c, 20.0);
      SolverOutput out;
      s.solve(sky.input(extra_m2), out);
      ASSERT_EQ(out.type, FixType::k3D);
      EXPECT_LT((out.pos_m - sky.truth).norm(), 1e-3);
      EXPECT_NEAR(out.sigma_uere_m, sky.expected_sigma_uere_m(c, extra_m2), 1e-3)
          << static_cast<int>(c.weights) << " " << extra_m2;
    }
  }
}

TEST(WeightModel, RtklibWeightsAllocateNothing) {
  const SixSats sky;
  Solver s(uncorrected(rtklib_single_point()), 20.0);
  const SolverInput in = sky.input(0.5);
  SolverOutput out;
  s.solve(in, out);  // warm-up
  const long before = support::allocation_count();
  for (int i = 0; i < 20; ++i) s.solve(in, out);
  EXPECT_EQ(support::allocation_count(), before);
  EXPECT_EQ(out.type, FixType::k3D);
}

}  // namespace
}  // namespace gnssemu::receiver

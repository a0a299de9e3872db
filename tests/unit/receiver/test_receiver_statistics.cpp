// SPDX-License-Identifier: Apache-2.0
// Receiver error statistics: the fix error against the solver's own
// accuracy estimate (ensembles over seeds), time correlation, velocity,
// and the chi-square residual test.
#include <gtest/gtest.h>

#include <cmath>

#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/pipeline/pipeline.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver::receiver_statistics_test {
namespace {

using test::truth_at;
using pipeline::Pipeline;
using pipeline::PipelineConfig;

const time::GpsTime kToe(2190, 200000.0);
const Lla kSite{52.0 * kDegToRad, 4.4 * kDegToRad, 30.0};

Enu error_enu(const Fix& f, const Ecef& truth) {
  return geo::ecef_to_enu_vector(f.pos_m - truth, kSite.lat_rad, kSite.lon_rad);
}

// test::gm_white_world errors: orbit/clock 1.2 m + thermal 0.3 m, elevation
// independent, so sigma_UERE = sqrt(1.2^2 + 0.3^2).
const double kSigmaUere_m = std::hypot(1.2, 0.3);

struct Ensemble {
  double rms_h_m = 0.0, rms_u_m = 0.0, mean_h_acc_m = 0.0, mean_v_acc_m = 0.0, hdop = 0.0, vdop = 0.0;
  int fixes = 0, no_fix = 0;
};

// One epoch per seed: every seed draws the Gauss–Markov states from their
// stationary distribution, so the samples are independent.
Ensemble run_ensemble(const orbit::EphemerisStore& store, PipelineConfig cfg, int seeds) {
  Ensemble e;
  const Ecef truth = geo::ecef_from_lla(kSite);
  for (int s = 0; s < seeds; ++s) {
    cfg.world.seed = 1000 + static_cast<uint64_t>(s);
    Pipeline rx(store, cfg);
    const Fix& f = rx.step(kToe, truth_at(truth, kToe));
    test::expect_consistent(f);
    if (f.type != FixType::k3D) {
      ++e.no_fix;
      continue;
    }
    const Enu d = error_enu(f, truth);
    e.rms_h_m += d.x * d.x + d.y * d.y;
    e.rms_u_m += d.z * d.z;
    e.mean_h_acc_m += f.h_acc_m;
    e.mean_v_acc_m += f.v_acc_m;
    e.hdop = f.dop.hdop;
    e.vdop = f.dop.vdop;
    ++e.fixes;
  }
  e.rms_h_m = std::sqrt(e.rms_h_m / e.fixes);
  e.rms_u_m = std::sqrt(e.rms_u_m / e.fixes);
  e.mean_h_acc_m /= e.fixes;
  e.mean_v_acc_m /= e.fixes;
  return e;
}

TEST(ReceiverStatistics, EnsembleErrorMatchesSigmaUereTimesDop) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = test::gm_white_world();
  // Solver weights equal to the world's sigma: WLS is then the BLUE and its
  // covariance sigma^2 (H'H)^-1 is exact, so rms error = sigma_UERE * DOP.
  cfg.receiver.solver.sigma_a_m = kSigmaUere_m;
  cfg.receiver.solver.sigma_b_m = 0.0;
  const Ensemble e = run_ensemble(store, cfg, 400);
  ASSERT_GE(e.fixes, 396);  // chi-square false alarms ~ 1e-3
  EXPECT_NEAR(e.mean_h_acc_m, kSigmaUere_m * e.hdop, 1e-6);
  EXPECT_NEAR(e.mean_v_acc_m, kSigmaUere_m * e.vdop, 1e-6);
  // ~800 squared components: the rms is known to ~3.5 % (1 sigma); 15 % is > 4 sigma.
  EXPECT_NEAR(e.rms_h_m / (kSigmaUere_m * e.hdop), 1.0, 0.15) << e.rms_h_m;
  EXPECT_NEAR(e.rms_u_m / (kSigmaUere_m * e.vdop), 1.0, 0.20) << e.rms_u_m;
}

TEST(ReceiverStatistics, DefaultSolverAccuracyIsConservativeButTight) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ensemble e = run_ensemble(store, test::snapshot(), 400);
  ASSERT_GE(e.fixes, 396);
  // The default solver assumes sigma^2 = 1.2^2 + 0.3^2 / sin^2(el) + 150^2 10^(-C/N0/10),
  // at least the default world's variance (GM 1.2 m, DLL noise, atmosphere
  // residuals) at every elevation, so its covariance bounds the true one:
  // ratio <= 1 up to sampling (~4 %); it over-weights low satellites only
  // mildly, so the bound is not loose (ratio > 0.6).
  const double ratio = e.rms_h_m / e.mean_h_acc_m;
  EXPECT_LT(ratio, 1.1) << e.rms_h_m << " " << e.mean_h_acc_m;
  EXPECT_GT(ratio, 0.6) << e.rms_h_m << " " << e.mean_h_acc_m;
  EXPECT_LT(e.rms_u_m / e.mean_v_acc_m, 1.1);
}

TEST(ReceiverStatistics, ErrorIsTimeCorrelatedNotWhite) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = test::gm_white_world();
  cfg.receiver.solver.sigma_a_m = kSigmaUere_m;
  cfg.receiver.solver.sigma_b_m = 0.0;
  const Ecef truth = geo::ecef_from_lla(kSite);
  double sum_xx = 0.0, sum_x1 = 0.0, sum_dd = 0.0, sum_pred_dd = 0.0;
  int n = 0, nd = 0;
  for (int s = 0; s < 20; ++s) {
    cfg.world.seed = 500 + static_cast<uint64_t>(s);
    Pipeline rx(store, cfg);
    double prev_e = 0.0;
    for (int k = 0; k < 300; ++k) {
      const time::GpsTime t = kToe + static_cast<double>(k);
      const Fix& f = rx.step(t, truth_at(truth, t));
      ASSERT_EQ(f.type, FixType::k3D);
      const double e = error_enu(f, truth).x;
      sum_xx += e * e;
      ++n;
      if (k > 0) {
        sum_x1 += e * prev_e;
        sum_dd += (e - prev_e) * (e - prev_e);
        // White thermal part only: var(diff) = 2 * (0.3 * EDOP)^2, EDOP = sigma_e / sigma_a.
        const double edop = f.sigma_e_m / kSigmaUere_m;
        sum_pred_dd += 2.0 * 0.09 * edop * edop;
        ++nd;
      }
      prev_e = e;
    }
  }
  // Lag-1 autocorrelation about the true (zero) mean. White noise gives ~0;
  // GM (tau 1800 s) plus the white part gives ~0.9 here.
  const double r1 = sum_x1 / sum_xx * n / nd;
  EXPECT_GT(r1, 0.8) << r1;
  // Epoch-to-epoch changes are the thermal noise alone (GM increments over
  // 1 s add < 1 % variance): 5980 differences pin the ratio to ~2 %.
  EXPECT_NEAR(std::sqrt(sum_dd / sum_pred_dd), 1.0, 0.1);
  // ... and much smaller than the error itself (white would be sqrt 2 larger).
  EXPECT_LT(std::sqrt(sum_dd / nd) / std::sqrt(sum_xx / n), 0.6);  // measured 0.44
}

TEST(ReceiverStatistics, MovingReceiverVelocityWithinSigma) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  Pipeline rx(store, test::snapshot());
  const Ecef p0 = geo::ecef_from_lla(kSite);
  const Vec3 v_ecef = geo::enu_to_ecef_vector(Enu(100.0, 0.0, 0.0), kSite.lat_rad, kSite.lon_rad);
  double sum_err2 = 0.0, sum_acc2 = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double dt = 0.5 * k;
    const time::GpsTime t = kToe + dt;
    const Ecef pos(p0 + v_ecef * dt);
    const Fix& f = rx.step(t, truth_at(pos, t, Ecef(v_ecef)));
    ASSERT_EQ(f.type, FixType::k3D);
    test::expect_consistent(f);
    const double err = (f.vel_m_s - v_ecef).norm();
    EXPECT_LT(err, 4.0 * f.speed_acc_m_s) << k;
    sum_err2 += err * err;
    sum_acc2 += f.speed_acc_m_s * f.speed_acc_m_s;
    EXPECT_NEAR(f.speed_m_s, 100.0, 0.3);
    EXPECT_NEAR(f.course_rad * kRadToDeg, 90.0, 0.3);
    EXPECT_NEAR(f.climb_m_s, 0.0, 0.5);
    EXPECT_LT((f.pos_m - pos).norm(), 15.0);
  }
  // World Doppler noise 0.03 m/s, solver assumes 0.05 m/s: ratio ~0.6.
  const double ratio = std::sqrt(sum_err2 / sum_acc2);
  EXPECT_GT(ratio, 0.4);
  EXPECT_LT(ratio, 0.9);
}

TEST(ReceiverStatistics, ResidualTestRejectsInconsistentMeasurements) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = test::gm_white_world();
  cfg.world.errors.thermal_sigma_m = 30.0;  // far beyond what the solver assumes
  Pipeline rx(store, cfg);
  cfg.receiver.solver.residual_test_pfa = 0.0;  // test disabled
  Pipeline unchecked(store, cfg);
  const Ecef truth = geo::ecef_from_lla(kSite);
  // Every satellite is inconsistent with the assumed sigma: the receiver
  // never reports a fix from all of them. Fault exclusion drops the worst
  // ones while 5 remain; what it keeps passes the test, or there is no fix.
  int none = 0, excluded = 0;
  for (int k = 0; k < 100; ++k) {
    const time::GpsTime t = kToe + static_cast<double>(k);
    const Fix& f = rx.step(t, truth_at(truth, t));
    test::expect_consistent(f);
    none += f.type == FixType::kNone;
    if (f.type != FixType::kNone && f.num_used < f.num_tracked) {
      ++excluded;
      EXPECT_GE(f.num_used, Solver::kMinSatsAfterExclusion);
    }
    const Fix& u = unchecked.step(t, truth_at(truth, t));
    EXPECT_EQ(u.type, FixType::k3D);
    EXPECT_EQ(u.num_used, u.num_tracked);
  }
  EXPECT_GE(none + excluded, 95);
  EXPECT_GT(none, 0);
}

TEST(ReceiverStatistics, ChiSquareThresholdMatchesTables) {
  const orbit::EphemerisStore store;
  Solver s(SolverConfig{}, 20.0);  // pfa 1e-3
  // chi^2 upper 0.1 % points (standard tables): dof 1: 10.83, 4: 18.47, 10: 29.59.
  EXPECT_NEAR(s.chi2_threshold(1), 10.83, 0.5);
  EXPECT_NEAR(s.chi2_threshold(4), 18.47, 0.3);
  EXPECT_NEAR(s.chi2_threshold(10), 29.59, 0.3);
}

}  // namespace
}  // namespace gnssemu::receiver::receiver_statistics_test

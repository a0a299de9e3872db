// SPDX-License-Identifier: Apache-2.0
// The error terms `gnssemu calibrate` fits beyond the original model: the
// per-satellite multipath process sigma / sin(el), the azimuthal delay
// gradient common to all satellites and the common relative error of the
// ionosphere (docs/models.md).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/pipeline/pipeline.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver::receiver_calibration_terms_test {
namespace {

using test::truth_at;
using pipeline::Pipeline;
using pipeline::PipelineConfig;

const time::GpsTime kToe(2190, 200000.0);
const Lla kSite{45.0 * kDegToRad, 7.0 * kDegToRad, 300.0};

/// No random process, no clock noise: pseudoranges differ only by what a test switches on.
PipelineConfig quiet() { return test::noiseless(); }

TEST(ReceiverCalibrationTerms, ConstantGradientIsNorthCosAzPlusEastSinAz) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig with = quiet();
  with.world.errors.gradient.north_m = 0.7;
  with.world.errors.gradient.east_m = -0.4;
  Pipeline a(store, quiet()), b(store, with);
  const Ecef pos = geo::ecef_from_lla(kSite);
  const Fix fa = a.step(kToe, truth_at(pos, kToe));
  const Fix& fb = b.step(kToe, truth_at(pos, kToe));
  int checked = 0;
  for (int i = 0; i < fb.num_sats; ++i) {
    if (!fb.sats[i].tracked) continue;
    ASSERT_EQ(fa.sats[i].sat.prn(), fb.sats[i].sat.prn());
    const double az = fb.sats[i].az_rad;
    EXPECT_NEAR(fb.sats[i].pseudorange_m - fa.sats[i].pseudorange_m, 0.7 * std::cos(az) - 0.4 * std::sin(az), 1e-6);
    ++checked;
  }
  EXPECT_GE(checked, 6);
  // A pattern cos(az) pushes the fix away from the side with the longer ranges.
  ASSERT_EQ(fb.type, FixType::k3D);
  const double dn = (fb.lla.lat_rad - fa.lla.lat_rad) * 6.37e6;
  EXPECT_LT(dn, -0.1);
}

TEST(ReceiverCalibrationTerms, DiurnalGradientFollowsLocalSolarTime) {
  // G_N = 0.1 + 0.6 cos(2 pi (LT - 15 h) / 24 h), G_E = 0.4 cos(2 pi (LT - 3 h) / 24 h),
  // LT = GPS time of day + longitude / 15 deg per hour (7 deg E: 28 min).
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig with = quiet();
  with.world.errors.gradient.north_m = 0.1;
  with.world.errors.gradient.north_diurnal_m = 0.6;
  with.world.errors.gradient.north_peak_h = 15.0;
  with.world.errors.gradient.east_diurnal_m = 0.4;
  with.world.errors.gradient.east_peak_h = 3.0;
  const Ecef pos = geo::ecef_from_lla(kSite);
  int checked = 0;
  for (double dt_s : {0.0, 3600.0, 5.0 * 3600.0, 11.0 * 3600.0}) {
    Pipeline a(store, quiet()), b(store, with);
    const time::GpsTime t = kToe + dt_s;
    const Fix fa = a.step(t, truth_at(pos, t));
    const Fix& fb = b.step(t, truth_at(pos, t));
    const double lt_h = std::fmod(t.tow_s(), 86400.0) / 3600.0 + 7.0 / 15.0;
    const double gn = 0.1 + 0.6 * std::cos(2.0 * kPi * (lt_h - 15.0) / 24.0);
    const double ge = 0.4 * std::cos(2.0 * kPi * (lt_h - 3.0) / 24.0);
    for (int i = 0; i < fb.num_sats; ++i) {
      if (!fb.sats[i].tracked) continue;
      const double az = fb.sats[i].az_rad;
      EXPECT_NEAR(fb.sats[i].pseudorange_m - fa.sats[i].pseudorange_m, gn * std::cos(az) + ge * std::sin(az), 1e-6)
          << "LT " << lt_h << " h";
      ++checked;
    }
  }
  EXPECT_GE(checked, 16);
}

TEST(ReceiverCalibrationTerms, MultipathScalesWithOneOverSinElevationAndDecorrelates) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig with = quiet();
  with.world.errors.multipath = {0.2, 60.0};
  Pipeline a(store, quiet()), b(store, with);
  const Ecef pos = geo::ecef_from_lla(kSite);
  // Normalised value d sin(el) / sigma is a unit Gauss–Markov with tau 60 s.
  std::vector<std::vector<double>> z(33);
  for (int k = 0; k < 3000; ++k) {
    const time::GpsTime t = kToe + static_cast<double>(k);
    const Fix fa = a.step(t, truth_at(pos, t));
    const Fix& fb = b.step(t, truth_at(pos, t));
    for (int i = 0; i < fb.num_sats; ++i) {
      if (!fb.sats[i].tracked || !fa.sats[i].tracked) continue;
      const double d = fb.sats[i].pseudorange_m - fa.sats[i].pseudorange_m;
      z[fb.sats[i].sat.prn()].push_back(d * std::sin(std::max(fb.sats[i].el_rad, 5.0 * kDegToRad)) / 0.2);
    }
  }
  double s0 = 0, s60 = 0, n0 = 0, n60 = 0;
  for (const auto& v : z) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      s0 += v[i] * v[i], n0 += 1;
      if (i + 60 < v.size()) s60 += v[i] * v[i + 60], n60 += 1;
    }
  }
  ASSERT_GT(n0, 10000);
  // ~ 8 satellites x 50 correlation times: the variance within 15 %, rho(60 s) = 0.37 within 0.1.
  EXPECT_NEAR(s0 / n0, 1.0, 0.15);
  EXPECT_NEAR((s60 / n60) / (s0 / n0), std::exp(-1.0), 0.1);
}

TEST(ReceiverCalibrationTerms, GradientProcessHasItsSigmaAndIsDeterministic) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ecef pos = geo::ecef_from_lla(kSite);
  double ss = 0.0;
  int n = 0;
  // Four seeds x 130 correlation times: the RMS is known to ~4 %.
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    PipelineConfig without = quiet();
    without.world.seed = seed;
    PipelineConfig with = without;
    with.world.errors.gradient.process = {0.3, 30.0};
    Pipeline a(store, without), b(store, with), c(store, with);
    for (int k = 0; k < 4000; k += 2) {
      const time::GpsTime t = kToe + static_cast<double>(k);
      const Fix fa = a.step(t, truth_at(pos, t));
      const Fix fb = b.step(t, truth_at(pos, t));
      const Fix& fc = c.step(t, truth_at(pos, t));
      // Two satellites give G_N and G_E exactly: d = G_N cos az + G_E sin az.
      int idx[2], m = 0;
      for (int i = 0; i < fb.num_sats && m < 2; ++i)
        if (fb.sats[i].tracked && fa.sats[i].tracked) idx[m++] = i;
      ASSERT_EQ(m, 2);
      const double a0 = fb.sats[idx[0]].az_rad, a1 = fb.sats[idx[1]].az_rad;
      const double d0 = fb.sats[idx[0]].pseudorange_m - fa.sats[idx[0]].pseudorange_m;
      const double d1 = fb.sats[idx[1]].pseudorange_m - fa.sats[idx[1]].pseudorange_m;
      const double det = std::cos(a0) * std::sin(a1) - std::sin(a0) * std::cos(a1);
      if (std::fabs(det) < 0.3) continue;
      const double gn = (d0 * std::sin(a1) - d1 * std::sin(a0)) / det;
      const double ge = (std::cos(a0) * d1 - std::cos(a1) * d0) / det;
      ss += gn * gn + ge * ge;
      n += 2;
      EXPECT_EQ(fb.sats[idx[0]].pseudorange_m, fc.sats[idx[0]].pseudorange_m);  // same seed, same world
    }
  }
  ASSERT_GT(n, 4000);
  EXPECT_NEAR(std::sqrt(ss / n), 0.3, 0.03);
}

TEST(ReceiverCalibrationTerms, IonoScaleIsOneFactorForTheWholeSky) {
  // World ionosphere x (1 + 0.3 x(t)), x a unit Gauss-Markov process of 600 s.
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig with = quiet();
  with.world.errors.iono_scale = {0.3, 600.0};
  Pipeline a(store, quiet()), b(store, with), c(store, with);
  const Ecef pos = geo::ecef_from_lla(kSite);
  std::vector<double> x;
  for (int k = 0; k < 20000; k += 10) {
    const time::GpsTime t = kToe + static_cast<double>(k);
    a.step(t, truth_at(pos, t));
    const Fix& fb = b.step(t, truth_at(pos, t));
    const Fix& fc = c.step(t, truth_at(pos, t));
    double factor = 0.0;
    int n = 0;
    for (int i = 0; i < fb.num_sats; ++i) {
      if (!fb.sats[i].tracked) continue;
      const int prn = fb.sats[i].sat.prn();
      const double base_m = a.world().path_effects(SatId::gps(prn)).iono_m;
      ASSERT_GT(base_m, 0.5);
      const double f = b.world().path_effects(SatId::gps(prn)).iono_m / base_m - 1.0;
      if (n > 0) {
        EXPECT_NEAR(f, factor, 1e-9) << "one factor for every line of sight";
      }
      factor = f;
      ++n;
      EXPECT_EQ(fb.sats[i].pseudorange_m, fc.sats[i].pseudorange_m);  // same seed, same world
    }
    ASSERT_GE(n, 6);
    x.push_back(factor);
  }
  double s0 = 0.0, s60 = 0.0;  // lag 60 s = 6 samples
  for (std::size_t i = 0; i < x.size(); ++i) {
    s0 += x[i] * x[i];
    if (i + 6 < x.size()) s60 += x[i] * x[i + 6];
  }
  s0 /= static_cast<double>(x.size());
  s60 /= static_cast<double>(x.size() - 6);
  // 2000 samples over 33 correlation times: sigma within 20 %, rho(60 s) = 0.905.
  EXPECT_NEAR(std::sqrt(s0), 0.3, 0.06);
  EXPECT_NEAR(s60 / s0, std::exp(-60.0 / 600.0), 0.05);
}

TEST(ReceiverCalibrationTerms, IonoScaleOffChangesNothing) {
  // sigma 0: not a draw, not a bit of the pseudoranges changes.
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig with = quiet();
  with.world.errors.iono_scale = {0.0, 123.0};
  Pipeline a(store, quiet()), b(store, with);
  const Ecef pos = geo::ecef_from_lla(kSite);
  for (int k = 0; k < 100; ++k) {
    const time::GpsTime t = kToe + static_cast<double>(k);
    const Fix fa = a.step(t, truth_at(pos, t));
    const Fix& fb = b.step(t, truth_at(pos, t));
    for (int i = 0; i < fb.num_sats; ++i) EXPECT_EQ(fa.sats[i].pseudorange_m, fb.sats[i].pseudorange_m);
  }
}

TEST(ReceiverCalibrationTerms, BadValuesAreRejected) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig c = quiet();
  c.world.errors.multipath = {-0.1, 60.0};
  EXPECT_THROW(Pipeline(store, c), Error);
  c = quiet();
  c.world.errors.multipath = {0.1, 0.0};
  EXPECT_THROW(Pipeline(store, c), Error);
  c = quiet();
  c.world.errors.gradient.north_m = std::nan("");
  EXPECT_THROW(Pipeline(store, c), Error);
  c = quiet();
  c.world.errors.gradient.process = {0.1, -1.0};
  EXPECT_THROW(Pipeline(store, c), Error);
  c = quiet();
  c.world.errors.gradient.north_diurnal_m = -0.1;
  EXPECT_THROW(Pipeline(store, c), Error);
  c = quiet();
  c.world.errors.gradient.east_peak_h = 24.0;
  EXPECT_THROW(Pipeline(store, c), Error);
  c = quiet();
  c.world.errors.iono_scale = {-0.1, 600.0};
  EXPECT_THROW(Pipeline(store, c), Error);
  c = quiet();
  c.world.errors.iono_scale = {0.2, 0.0};
  EXPECT_THROW(Pipeline(store, c), Error);
}

}  // namespace
}  // namespace gnssemu::receiver::receiver_calibration_terms_test

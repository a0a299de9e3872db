// SPDX-License-Identifier: Apache-2.0
// Receiver hard cases: poles, antimeridian, extreme heights, near-singular
// geometry, 2D/none with three satellites, mask at zenith, GPS week
// boundary, clock jumps, teleport. No NaN anywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/pipeline/pipeline.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver::receiver_hard_cases_test {
namespace {

using test::truth_at;
using pipeline::Pipeline;
using pipeline::PipelineConfig;

using test::errors_off_config;
using test::expect_consistent;

const time::GpsTime kToe(2190, 300000.0);

struct Site {
  const char* name;
  Lla lla;
};

class HardSites : public ::testing::TestWithParam<Site> {};

TEST_P(HardSites, ExactWithErrorsOffAndSaneWithDefaults) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ecef pos = geo::ecef_from_lla(GetParam().lla);
  // Airborne: the portable model's sanity limit (12 km MSL) would void the aircraft's fix.
  PipelineConfig exact_cfg = errors_off_config(), noisy_cfg = test::snapshot();
  exact_cfg.receiver.filter.dynamic_model = noisy_cfg.receiver.filter.dynamic_model = DynamicModel::kAirborne1g;
  Pipeline exact(store, exact_cfg);
  Pipeline noisy(store, noisy_cfg);
  for (int k = 0; k < 24; ++k) {
    const time::GpsTime t = kToe + 600.0 * k - 7200.0;
    const Fix& f = exact.step(t, truth_at(pos, t));
    ASSERT_EQ(f.type, FixType::k3D) << k;
    expect_consistent(f);
    EXPECT_LT((f.pos_m - pos).norm(), 1e-3) << k;
    EXPECT_NEAR(f.lla.height_m, GetParam().lla.height_m, 1e-3);
    EXPECT_GE(f.lla.lon_rad, -kPi);
    EXPECT_LE(f.lla.lon_rad, kPi);
    const Fix& g = noisy.step(t, truth_at(pos, t));
    ASSERT_EQ(g.type, FixType::k3D) << k;
    expect_consistent(g);
    EXPECT_LT((g.pos_m - pos).norm(), 20.0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Receiver, HardSites,
    ::testing::Values(Site{"NorthPole", {kPi / 2.0, 0.0, 0.0}}, Site{"SouthPole", {-kPi / 2.0, 1.0, 2800.0}},
                      Site{"LonPlus180", {0.3, kPi, 10.0}}, Site{"LonMinus180", {-0.7, -kPi + 1e-12, 10.0}},
                      Site{"DeadSeaMinus400m", {31.5 * kDegToRad, 35.5 * kDegToRad, -400.0}},
                      Site{"Aircraft12km", {45.0 * kDegToRad, -100.0 * kDegToRad, 12000.0}}),
    [](const ::testing::TestParamInfo<Site>& i) { return std::string(i.param.name); });

TEST(ReceiverHardCases, CrossingTheAntimeridianAt100MetresPerSecond) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  Pipeline rx(store, errors_off_config());
  const Lla start{20.0 * kDegToRad, (180.0 - 0.005) * kDegToRad, 50.0};
  const Ecef p0 = geo::ecef_from_lla(start);
  const Vec3 v = geo::enu_to_ecef_vector(Enu(100.0, 0.0, 0.0), start.lat_rad, start.lon_rad);
  bool saw_east = false, saw_west = false;
  for (int k = 0; k < 20; ++k) {
    const double dt = 1.0 * k;
    const Ecef pos(p0 + v * dt);
    const Fix& f = rx.step(kToe + dt, truth_at(pos, kToe + dt, Ecef(v)));
    ASSERT_EQ(f.type, FixType::k3D);
    expect_consistent(f);
    EXPECT_LT((f.pos_m - pos).norm(), 1e-3);
    EXPECT_LT((f.vel_m_s - v).norm(), 1e-3);
    EXPECT_NEAR(f.course_rad * kRadToDeg, 90.0, 0.01);
    saw_east |= f.lla.lon_rad > 0.0;
    saw_west |= f.lla.lon_rad < 0.0;
  }
  EXPECT_TRUE(saw_east && saw_west);
}

// Satellites placed at (az, el) from the site at t, valid +-24 h.
std::vector<orbit::Ephemeris> placed(const Lla& site, const time::GpsTime& t,
                                     const std::vector<std::pair<double, double>>& az_el_deg) {
  const Ecef rx = geo::ecef_from_lla(site);
  std::vector<orbit::Ephemeris> v;
  int prn = 1;
  for (const auto& [az, el] : az_el_deg) {
    const Ecef sat = test::sat_position_at(rx, site, az * kDegToRad, el * kDegToRad);
    v.push_back(test::placed_eph(prn++, t, t, sat));
  }
  return v;
}

const Lla kSite{40.0 * kDegToRad, -3.7 * kDegToRad, 650.0};

TEST(ReceiverHardCases, PlacedSatellitesAppearWhereRequested) {
  const orbit::EphemerisStore store(placed(kSite, kToe, {{30.0, 60.0}, {200.0, 10.0}}));
  Pipeline rx(store, test::snapshot());
  const Fix& f = rx.step(kToe, truth_at(geo::ecef_from_lla(kSite), kToe));
  ASSERT_EQ(f.num_sats, 2);
  EXPECT_NEAR(f.sats[0].az_rad * kRadToDeg, 30.0, 0.05);
  EXPECT_NEAR(f.sats[0].el_rad * kRadToDeg, 60.0, 0.05);
  EXPECT_NEAR(f.sats[1].az_rad * kRadToDeg, 200.0, 0.05);
  EXPECT_NEAR(f.sats[1].el_rad * kRadToDeg, 10.0, 0.05);
  EXPECT_EQ(f.type, FixType::kNone);  // two satellites
}

TEST(ReceiverHardCases, FourSatellitesInOneSkyPatchGiveNoFix) {
  const orbit::EphemerisStore store(placed(kSite, kToe, {{10.0, 45.0}, {11.0, 45.5}, {12.0, 44.5}, {13.0, 45.2}}));
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    PipelineConfig cfg = test::snapshot();
    cfg.world.seed = seed;
    Pipeline rx(store, cfg);
    const Ecef pos = geo::ecef_from_lla(kSite);
    for (int k = 0; k < 3; ++k) {
      const Fix& f = rx.step(kToe + k, truth_at(pos, kToe + k));
      EXPECT_EQ(f.num_tracked, 4);
      EXPECT_EQ(f.type, FixType::kNone);
      expect_consistent(f);
    }
  }
}

TEST(ReceiverHardCases, PoorGeometryIsRejectedOrHonestAboutIt) {
  // Four satellites in a 30-degree azimuth band at 30-42 degrees elevation.
  const orbit::EphemerisStore store(placed(kSite, kToe, {{0.0, 30.0}, {10.0, 42.0}, {20.0, 34.0}, {30.0, 40.0}}));
  const Ecef pos = geo::ecef_from_lla(kSite);
  int fixes_default = 0, fixes_lenient = 0;
  double worst_ratio = 0.0, pdop = 0.0;
  for (uint64_t seed = 1; seed <= 100; ++seed) {
    PipelineConfig cfg = test::snapshot();
    cfg.world.seed = seed;
    Pipeline rx(store, cfg);
    const Fix& f = rx.step(kToe, truth_at(pos, kToe));
    expect_consistent(f);
    fixes_default += f.type != FixType::kNone;
    cfg.receiver.max_pdop = receiver::ReceiverRanges::max_pdop.max;  // accept all the receiver can
    Pipeline lenient(store, cfg);
    const Fix& g = lenient.step(kToe, truth_at(pos, kToe));
    expect_consistent(g);
    if (g.type == FixType::kNone) continue;
    ++fixes_lenient;
    pdop = g.dop.pdop;
    const double sigma3d = std::sqrt(g.sigma_e_m * g.sigma_e_m + g.sigma_n_m * g.sigma_n_m + g.sigma_u_m * g.sigma_u_m);
    worst_ratio = std::max(worst_ratio, (g.pos_m - pos).norm() / sigma3d);
  }
  EXPECT_EQ(fixes_default, 0);       // PDOP > max_pdop 20
  EXPECT_EQ(fixes_lenient, 100);
  EXPECT_GT(pdop, 20.0) << pdop;
  EXPECT_GT(worst_ratio, 0.3);  // the errors are real (tens to hundreds of metres)
  // Low-confidence fix: its covariance covers the actual error (3D error
  // over the 1-sigma 3D radius; chi(3) exceeds 4 with p < 1e-3).
  EXPECT_LT(worst_ratio, 4.0);
}

TEST(ReceiverHardCases, ThreeSatellitesGive2DOnlyAfterA3DFix) {
  // Three long-lived satellites; a fourth whose ephemeris expires 10 s after t0.
  std::vector<orbit::Ephemeris> ephs = placed(kSite, kToe, {{0.0, 35.0}, {120.0, 40.0}, {240.0, 30.0}});
  const Ecef rx_pos = geo::ecef_from_lla(kSite);
  const Ecef zenith_sat = test::sat_position_at(rx_pos, kSite, 0.0, 80.0 * kDegToRad);
  orbit::Ephemeris short_lived = test::placed_eph(4, kToe - 7190.0, kToe, zenith_sat);
  short_lived.fit_interval_h = 0.0;  // +-2 h validity
  ephs.push_back(short_lived);
  const orbit::EphemerisStore store(ephs);

  Pipeline rx(store, errors_off_config());
  const Fix& f0 = rx.step(kToe, truth_at(rx_pos, kToe));
  ASSERT_EQ(f0.type, FixType::k3D);
  EXPECT_EQ(f0.num_used, 4);
  for (int k = 1; k <= 10; ++k) {
    const time::GpsTime t = kToe + 20.0 * k;
    const Fix& f = rx.step(t, truth_at(rx_pos, t));
    ASSERT_EQ(f.type, FixType::k2D) << k;
    expect_consistent(f);
    EXPECT_EQ(f.num_used, 3);
    EXPECT_LT((f.pos_m - rx_pos).norm(), 1e-3);  // height held = true height here
    EXPECT_NEAR(f.lla.height_m, 650.0, 1e-3);
    EXPECT_NEAR(f.clock_bias_s, rx.world().true_clock_bias_s(), 3.4e-12);
  }

  // Same sky, but the receiver starts after the fourth set expired: none.
  Pipeline late(store, errors_off_config());
  for (int k = 1; k <= 5; ++k) {
    const Fix& f = late.step(kToe + 20.0 * k, truth_at(rx_pos, kToe + 20.0 * k));
    EXPECT_EQ(f.num_tracked, 3);
    EXPECT_EQ(f.type, FixType::kNone);
    expect_consistent(f);
  }

  // 2D with errors: horizontal error stays metre-level, height stays held.
  Pipeline noisy(store, test::snapshot());
  ASSERT_EQ(noisy.step(kToe, truth_at(rx_pos, kToe)).type, FixType::k3D);
  const double held_h = noisy.last_fix().lla.height_m;
  const Fix& f2 = noisy.step(kToe + 30.0, truth_at(rx_pos, kToe + 30.0));
  ASSERT_EQ(f2.type, FixType::k2D);
  EXPECT_NEAR(f2.lla.height_m, held_h, 0.5);
  EXPECT_LT((f2.pos_m - rx_pos).norm(), 30.0);
}

// 2D DOP comes from the 3 satellites only: VDOP/PDOP/GDOP unavailable
// (99.99), HDOP/TDOP from the E, N, clock geometry with the height known.
TEST(ReceiverHardCases, TwoDFixDopFromSatelliteGeometryOnly) {
  std::vector<orbit::Ephemeris> ephs = placed(kSite, kToe, {{0.0, 35.0}, {120.0, 40.0}, {240.0, 30.0}});
  const Ecef rx_pos = geo::ecef_from_lla(kSite);
  orbit::Ephemeris short_lived =
      test::placed_eph(4, kToe - 7190.0, kToe, test::sat_position_at(rx_pos, kSite, 0.0, 80.0 * kDegToRad));
  short_lived.fit_interval_h = 0.0;
  ephs.push_back(short_lived);
  const orbit::EphemerisStore store(ephs);
  Pipeline rx(store, errors_off_config());
  ASSERT_EQ(rx.step(kToe, truth_at(rx_pos, kToe)).type, FixType::k3D);
  const Fix& f = rx.step(kToe + 20.0, truth_at(rx_pos, kToe + 20.0));
  ASSERT_EQ(f.type, FixType::k2D);
  EXPECT_EQ(f.dop.vdop, Dop::kNoDop);
  EXPECT_EQ(f.dop.pdop, Dop::kNoDop);
  EXPECT_EQ(f.dop.gdop, Dop::kNoDop);
  // Expected: inverse of sum h h' with h = (-cos el sin az, -cos el cos az, 1).
  double n[3][3] = {};
  int used = 0;
  for (int k = 0; k < f.num_sats; ++k) {
    const SatInfo& s = f.sats[static_cast<std::size_t>(k)];
    if (!s.used) continue;
    ++used;
    const double h[3] = {-std::cos(s.el_rad) * std::sin(s.az_rad), -std::cos(s.el_rad) * std::cos(s.az_rad), 1.0};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) n[i][j] += h[i] * h[j];
  }
  ASSERT_EQ(used, 3);
  const double det = n[0][0] * (n[1][1] * n[2][2] - n[1][2] * n[2][1]) -
                     n[0][1] * (n[1][0] * n[2][2] - n[1][2] * n[2][0]) +
                     n[0][2] * (n[1][0] * n[2][1] - n[1][1] * n[2][0]);
  const double q00 = (n[1][1] * n[2][2] - n[1][2] * n[2][1]) / det;
  const double q11 = (n[0][0] * n[2][2] - n[0][2] * n[2][0]) / det;
  const double q22 = (n[0][0] * n[1][1] - n[0][1] * n[1][0]) / det;
  EXPECT_NEAR(f.dop.hdop, std::sqrt(q00 + q11), 1e-6);
  EXPECT_NEAR(f.dop.tdop, std::sqrt(q22), 1e-6);
  EXPECT_LT(f.dop.hdop, Dop::kNoDop);
}

TEST(ReceiverHardCases, MaskNearZenithGivesNoFix) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = test::snapshot();
  cfg.receiver.elevation_mask_rad = kPi / 2.0 - 1e-9;
  Pipeline rx(store, cfg);
  const Fix& f = rx.step(kToe, truth_at(geo::ecef_from_lla(kSite), kToe));
  EXPECT_EQ(f.type, FixType::kNone);
  EXPECT_EQ(f.num_tracked, 0);
  EXPECT_EQ(f.num_visible, 0);
  EXPECT_GE(f.num_sats, 6);  // still in the sky, just below the mask
  expect_consistent(f);
}

TEST(ReceiverHardCases, ChannelLimitKeepsHighestSatellites) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = test::snapshot();
  cfg.receiver.max_channels = 5;
  Pipeline rx(store, cfg);
  const Fix& f = rx.step(kToe, truth_at(geo::ecef_from_lla(kSite), kToe));
  ASSERT_GT(f.num_visible, 5);
  EXPECT_EQ(f.num_tracked, 5);
  EXPECT_EQ(f.type, FixType::k3D);
  double lowest_tracked = 10.0, highest_untracked = -10.0;
  for (int i = 0; i < f.num_sats; ++i) {
    const SatInfo& s = f.sats[i];
    if (s.tracked) {
      lowest_tracked = std::min(lowest_tracked, s.el_rad);
    } else if (s.above_mask) {
      highest_untracked = std::max(highest_untracked, s.el_rad);
    }
  }
  EXPECT_GT(lowest_tracked, highest_untracked);
}

TEST(ReceiverHardCases, EpochsStraddlingTheGpsWeekBoundary) {
  const time::GpsTime toe(2190, kSecondsPerWeek - 300.0);
  const orbit::EphemerisStore store(test::nominal_constellation(toe, 5));
  PipelineConfig gm_only = test::gm_white_world();  // GM residuals only: steps across the boundary must be tiny
  gm_only.world.errors.thermal_sigma_m = 0.0;
  gm_only.world.errors.doppler_sigma_m_s = 0.0;
  Pipeline exact(store, errors_off_config()), gm(store, gm_only);
  const Ecef pos = geo::ecef_from_lla(kSite);
  Ecef prev;
  for (int k = 0; k < 40; ++k) {
    const time::GpsTime t(2190, kSecondsPerWeek - 20.0 + 1.0 * k);
    EXPECT_EQ(t.week(), k < 20 ? 2190 : 2191);
    const Fix& f = exact.step(t, truth_at(pos, t));
    ASSERT_EQ(f.type, FixType::k3D) << k;
    EXPECT_EQ(f.t, t);
    expect_consistent(f);
    EXPECT_LT((f.pos_m - pos).norm(), 1e-3) << k;
    const Fix& g = gm.step(t, truth_at(pos, t));
    ASSERT_EQ(g.type, FixType::k3D);
    // GM increments over 1 s: sigma * sqrt(2/1800) = 4 cm per satellite.
    if (k > 0) {
      EXPECT_LT((g.pos_m - prev).norm(), 0.3) << k;
    }
    prev = g.pos_m;
  }
}

TEST(ReceiverHardCases, ClockMillisecondJumpsAreHarmless) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = errors_off_config();
  cfg.world.clock.drift_s_s = 1.0e-6;  // crosses 1 ms after 900 s
  Pipeline rx(store, cfg);
  const Ecef pos = geo::ecef_from_lla(kSite);
  int jumps = 0;
  double prev_bias = rx.world().true_clock_bias_s();
  for (int k = 0; k < 40; ++k) {
    const time::GpsTime t = kToe + 60.0 * k;
    const Fix& f = rx.step(t, truth_at(pos, t));
    ASSERT_EQ(f.type, FixType::k3D);
    EXPECT_LT((f.pos_m - pos).norm(), 1e-3) << k;
    EXPECT_LE(std::fabs(rx.world().true_clock_bias_s()), 1.0e-3);
    EXPECT_NEAR(f.clock_bias_s, rx.world().true_clock_bias_s(), 3.4e-12);
    jumps += rx.world().true_clock_bias_s() < prev_bias;
    prev_bias = rx.world().true_clock_bias_s();
  }
  EXPECT_EQ(jumps, 2);  // 1e-4 + 40*60*1e-6 = 2.5 ms
}

TEST(ReceiverHardCases, TeleportedReceiverReconverges) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  Pipeline rx(store, errors_off_config());
  const Ecef a = geo::ecef_from_lla(kSite);
  const Ecef b = geo::ecef_from_lla({-35.0 * kDegToRad, 140.0 * kDegToRad, 0.0});
  ASSERT_EQ(rx.step(kToe, truth_at(a, kToe)).type, FixType::k3D);
  const Fix& f = rx.step(kToe + 1.0, truth_at(b, kToe + 1.0));
  ASSERT_EQ(f.type, FixType::k3D);
  EXPECT_LT((f.pos_m - b).norm(), 1e-3);
}

}  // namespace
}  // namespace gnssemu::receiver::receiver_hard_cases_test

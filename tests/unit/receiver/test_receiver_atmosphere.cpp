// SPDX-License-Identifier: Apache-2.0
// The world's atmosphere and signal inside the receiver: delays and C/N0 as
// the models say, the receiver's broadcast corrections, tracking thresholds,
// stages off costing nothing, caching, determinism, no allocation.
#include <gtest/gtest.h>

#include <cmath>

#include "core/atmosphere/ionosphere.hpp"
#include "core/atmosphere/klobuchar.hpp"
#include "core/atmosphere/troposphere.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/signal/link_budget.hpp"
#include "synthetic_sky.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::receiver::receiver_atmosphere_test {
namespace {

using test::truth_at;
using pipeline::Pipeline;
using pipeline::PipelineConfig;
using test::noiseless;
using world::Truth;
using world::PathEffects;

using test::expect_consistent;

const time::GpsTime kToe(2190, 200000.0);
const Lla kSite{45.0 * kDegToRad, 7.0 * kDegToRad, 300.0};


/// A world whose atmosphere is exactly what the receiver models: Klobuchar
/// shape x 1 with Klobuchar's own slant factor, Saastamoinen ZHD + ZWD.
PipelineConfig world_equals_receiver_models() {
  PipelineConfig c = noiseless();
  c.world.atmosphere.troposphere.zhd_model = atmosphere::ZhdModel::kSaastamoinen;
  c.world.atmosphere.troposphere.zwd_model = atmosphere::ZwdModel::kSaastamoinen;
  c.world.atmosphere.troposphere.rel_humidity = 0.7;
  return c;
}

TEST(ReceiverAtmosphere, WorldDelaysAreTheConfiguredModels) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = noiseless();
  cfg.world.atmosphere.ionosphere.source = atmosphere::VtecSource::kFixed;
  cfg.world.atmosphere.ionosphere.vtec_tecu = 25.0;
  Pipeline rx(store, cfg);
  const Ecef pos = geo::ecef_from_lla(kSite);
  const Fix& f = rx.step(kToe, truth_at(pos, kToe));
  ASSERT_EQ(f.type, FixType::k3D);
  const atmosphere::Troposphere tropo(cfg.world.atmosphere.troposphere);
  const signal::LinkBudgetModel link(cfg.world.signal.link);
  int checked = 0;
  for (int i = 0; i < f.num_sats; ++i) {
    const SatInfo& s = f.sats[i];
    if (!s.tracked) continue;
    const PathEffects& e = rx.world().path_effects(s.sat);
    // 25 TECU x 0.16237 m/TECU x (1 + 16 (0.53 - E)^3).
    EXPECT_NEAR(e.iono_m, 25.0 * 0.1623718 * atmosphere::klobuchar_slant_factor(s.el_rad), 1e-4);
    EXPECT_NEAR(e.tropo_m, tropo.slant_delay_m(kSite.lat_rad, kSite.height_m, s.el_rad, kToe.fractional_day_of_year()), 1e-9);
    EXPECT_NEAR(e.delay_m, e.iono_m + e.tropo_m, 1e-12);
    EXPECT_GT(e.loss_db, 0.04);  // gases: 0.046 dB at the zenith, more lower down
    EXPECT_LT(e.loss_db, 0.6);
    EXPECT_GT(e.tropo_m, 2.2);
    EXPECT_NEAR(s.cn0_dbhz, link.cn0_dbhz((s.pseudorange_m - e.delay_m - kSpeedOfLight_m_s * rx.world().true_clock_bias_s()), s.el_rad, e.loss_db), 0.01);
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

TEST(ReceiverAtmosphere, ExactWhenTheWorldIsTheReceiversModel) {
  const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store(nav.ephemerides);
  Pipeline rx(store, world_equals_receiver_models(), {.klobuchar = nav.klobuchar});
  const Ecef larm(4549397.1706, 1874003.1392, 4045167.6109);
  const time::GpsTime t0 = time::GpsTime::from_calendar({2022, 1, 1, 10, 0, 0.0});
  for (int k = 0; k < 12; ++k) {
    const time::GpsTime t = t0 + 300.0 * k;
    const Fix& f = rx.step(t, truth_at(larm, t));
    ASSERT_EQ(f.type, FixType::k3D);
    expect_consistent(f);
    // Iono several metres and tropo 2.3-25 m are removed to a few mm (the
    // receiver evaluates them at its estimate, within 5 m of the truth).
    EXPECT_LT((f.pos_m - larm).norm(), 0.02) << k;
    double max_delay = 0.0;
    for (int i = 0; i < f.num_sats; ++i)
      if (f.sats[i].used) max_delay = std::max(max_delay, rx.world().path_effects(f.sats[i].sat).delay_m);
    EXPECT_GT(max_delay, 10.0);
  }
}

TEST(ReceiverAtmosphere, CorrectionsRemoveMostOfTheDelay) {
  const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store(nav.ephemerides);
  PipelineConfig with = noiseless();
  PipelineConfig without = with;
  without.receiver.solver.iono = atmosphere::IonoCorrection::kNone;
  without.receiver.solver.tropo = atmosphere::TropoCorrection::kNone;
  Pipeline a(store, with, {.klobuchar = nav.klobuchar}), b(store, without, {.klobuchar = nav.klobuchar});
  const Ecef larm(4549397.1706, 1874003.1392, 4045167.6109);
  const time::GpsTime t0 = time::GpsTime::from_calendar({2022, 1, 1, 12, 0, 0.0});
  double sum_a = 0.0, sum_b = 0.0;
  for (int k = 0; k < 12; ++k) {
    const time::GpsTime t = t0 + 300.0 * k;
    const Fix& fa = a.step(t, truth_at(larm, t));
    ASSERT_EQ(fa.type, FixType::k3D);
    sum_a += (fa.pos_m - larm).norm();
    const Fix& fb = b.step(t, truth_at(larm, t));
    if (fb.type == FixType::k3D) sum_b += (fb.pos_m - larm).norm();
  }
  // World: Klobuchar shape x 1 (removed exactly), exponential ZHD + 0.1 m ZWD
  // versus Saastamoinen: a few cm remain. Uncorrected: metres (mostly height).
  EXPECT_LT(sum_a / 12.0, 0.15);
  EXPECT_GT(sum_b / 12.0, 3.0);
}

TEST(ReceiverAtmosphere, TrackingThresholdsAndHysteresis) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = test::snapshot();
  cfg.receiver.tracking.acquire_dbhz = 44.0;
  cfg.receiver.tracking.lose_dbhz = 20.0;
  cfg.receiver.elevation_mask_rad = 0.0;
  Pipeline rx(store, cfg);
  const Ecef pos = geo::ecef_from_lla(kSite);
  std::array<bool, system_size(GnssSystem::kGps) + 1> was_tracked{};
  int kept_below_acquire = 0;
  for (int k = 0; k < 120; ++k) {
    const time::GpsTime t = kToe + 30.0 * k;
    const Fix& f = rx.step(t, truth_at(pos, t));
    expect_consistent(f);
    std::array<bool, system_size(GnssSystem::kGps) + 1> now{};
    for (int i = 0; i < f.num_sats; ++i) {
      const SatInfo& s = f.sats[i];
      if (!s.tracked) {
        EXPECT_EQ(s.cn0_dbhz, 0.0);  // GSV shows it without C/N0
        continue;
      }
      now[s.sat.prn()] = true;
      if (!was_tracked[s.sat.prn()]) {
        EXPECT_GE(s.cn0_dbhz, 44.0) << "acquired below the threshold";
      }
      EXPECT_GE(s.cn0_dbhz, 20.0);
      if (s.cn0_dbhz < 44.0) ++kept_below_acquire;
    }
    was_tracked = now;
  }
  EXPECT_GT(kept_below_acquire, 10);
}

TEST(ReceiverAtmosphere, NoiseRiseDropsLowSatellitesThenEverything) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ecef pos = geo::ecef_from_lla(kSite);
  PipelineConfig suburban_low = test::snapshot();
  suburban_low.world.signal.link.environment_noise_rise_db = 15.0;
  PipelineConfig industrial = test::snapshot();
  industrial.world.signal.link.environment_noise_rise_db = signal::environment_noise_rise_db("industrial");
  Pipeline a(store, test::snapshot()), b(store, suburban_low), c(store, industrial);
  for (int k = 0; k < 10; ++k) {
    const time::GpsTime t = kToe + 60.0 * k;
    const Fix& fa = a.step(t, truth_at(pos, t));
    const Fix& fb = b.step(t, truth_at(pos, t));
    const Fix& fc = c.step(t, truth_at(pos, t));
    expect_consistent(fa);
    expect_consistent(fb);
    expect_consistent(fc);
    EXPECT_EQ(fa.type, FixType::k3D);
    // 15 dB more noise: satellites below ~35 deg fall under 30 dB-Hz.
    EXPECT_LT(fb.num_tracked, fa.num_tracked);
    EXPECT_GT(fb.num_visible, fb.num_tracked);
    // Industrial (20 dB): the zenith gives ~28 dB-Hz, below acquisition:
    // nothing tracked, a clean no-fix, satellites still listed for GSV.
    EXPECT_EQ(fc.type, FixType::kNone);
    EXPECT_EQ(fc.num_tracked, 0);
    EXPECT_EQ(fc.num_visible, fa.num_visible);
    EXPECT_EQ(fc.dop.pdop, Dop::kNoDop);
    // The fix carries the world's noise floor (MON-HW jamInd / AGC read it).
    EXPECT_EQ(fa.noise_rise_db, test::snapshot().world.signal.link.environment_noise_rise_db);
    EXPECT_EQ(fb.noise_rise_db, 15.0);
    EXPECT_EQ(fc.noise_rise_db, 20.0);
  }
  // With the signal stage off the C/N0 curve is fixed: a quiet sky.
  PipelineConfig off = industrial;
  off.world.signal.enabled = false;
  Pipeline d(store, off);
  EXPECT_EQ(d.step(kToe, truth_at(pos, kToe)).noise_rise_db, Fix{}.noise_rise_db);
}

TEST(ReceiverAtmosphere, ModelErrorVarianceWidensTheAccuracyOnlyWhenCorrecting) {
  // sigma^2 += (f I_klobuchar)^2 + (s / (sin el + 0.1))^2: the fix is the same
  // geometry re-weighted, its hAcc/vAcc grow; without corrections nothing changes.
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ecef pos = geo::ecef_from_lla(kSite);
  PipelineConfig base = test::snapshot();  // default world and corrections
  ASSERT_NE(base.receiver.solver.iono, atmosphere::IonoCorrection::kNone);
  ASSERT_NE(base.receiver.solver.tropo, atmosphere::TropoCorrection::kNone);
  PipelineConfig wide = base;
  wide.receiver.solver.iono_model_fraction = 0.5;
  wide.receiver.solver.tropo_model_sigma_m = 0.3;
  Pipeline a(store, base), b(store, wide);
  const Fix fa = a.step(kToe, truth_at(pos, kToe));
  const Fix& fb = b.step(kToe, truth_at(pos, kToe));
  ASSERT_EQ(fa.type, FixType::k3D);
  ASSERT_EQ(fb.type, FixType::k3D);
  EXPECT_GT(fb.h_acc_m, 1.05 * fa.h_acc_m);
  EXPECT_GT(fb.v_acc_m, 1.05 * fa.v_acc_m);
  PipelineConfig none = base;
  none.receiver.solver.iono = atmosphere::IonoCorrection::kNone;
  none.receiver.solver.tropo = atmosphere::TropoCorrection::kNone;
  PipelineConfig none_wide = none;
  none_wide.receiver.solver.iono_model_fraction = 0.5;
  none_wide.receiver.solver.tropo_model_sigma_m = 0.3;
  Pipeline c(store, none), d(store, none_wide);
  const Fix fc = c.step(kToe, truth_at(pos, kToe));
  const Fix& fd = d.step(kToe, truth_at(pos, kToe));
  EXPECT_EQ(fc.h_acc_m, fd.h_acc_m);
  EXPECT_EQ(fc.v_acc_m, fd.v_acc_m);
}

TEST(ReceiverAtmosphere, AllStagesOffIsExactAndCostsNothing) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = test::errors_off_config();
  EXPECT_FALSE(cfg.world.atmosphere.ionosphere.enabled || cfg.world.atmosphere.troposphere.enabled || cfg.world.atmosphere.gases);
  Pipeline rx(store, cfg);
  const Ecef pos = geo::ecef_from_lla(kSite);
  for (int k = 0; k < 30; ++k) {
    const time::GpsTime t = kToe + 10.0 * k;
    const Fix& f = rx.step(t, truth_at(pos, t));
    ASSERT_EQ(f.type, FixType::k3D);
    EXPECT_LT((f.pos_m - pos).norm(), 1e-3);
    for (int i = 0; i < f.num_sats; ++i) EXPECT_EQ(rx.world().path_effects(f.sats[i].sat).delay_m, 0.0);
  }
  EXPECT_EQ(rx.world().atmosphere_refreshes(), 0);
}

TEST(ReceiverAtmosphere, CacheRefreshesOnScheduleWithSmallError) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ecef pos = geo::ecef_from_lla(kSite);
  PipelineConfig ref = noiseless();
  PipelineConfig cached = ref;
  cached.world.atmosphere.cache_refresh_s = 30.0;
  cached.world.atmosphere.cache_mode = atmosphere::CacheMode::kLinear;
  Pipeline a(store, ref), b(store, cached);
  double max_diff = 0.0;
  long sat_epochs = 0;
  for (int k = 0; k < 600; ++k) {
    const time::GpsTime t = kToe + 1.0 * k;
    const Fix& fa = a.step(t, truth_at(pos, t));
    const Fix& fb = b.step(t, truth_at(pos, t));
    ASSERT_EQ(fa.type, FixType::k3D);
    ASSERT_EQ(fb.type, FixType::k3D);
    max_diff = std::max(max_diff, (fa.pos_m - fb.pos_m).norm());
    sat_epochs += fa.num_visible;
  }
  EXPECT_EQ(a.world().atmosphere_refreshes(), sat_epochs);  // no cache: every satellite, every epoch
  // 30 s refresh plus one bootstrap refresh per satellite for the slope.
  EXPECT_LT(b.world().atmosphere_refreshes(), sat_epochs / 10);
  EXPECT_GT(b.world().atmosphere_refreshes(), sat_epochs / 31);
  EXPECT_LT(max_diff, 0.05);
}

TEST(ReceiverAtmosphere, DeterministicWithEveryStageOn) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = test::snapshot();
  cfg.world.atmosphere.clouds_rain.layers[0] = atmosphere::cloud_preset("thunderstorm");
  cfg.world.atmosphere.clouds_rain.layers[1] = atmosphere::cloud_preset("fog");
  cfg.world.atmosphere.clouds_rain.layer_count = 2;
  cfg.world.atmosphere.clouds_rain.rain.rate_mm_h = 100.0;
  cfg.world.seed = 99;
  Pipeline a(store, cfg), b(store, cfg);
  cfg.world.seed = 100;
  Pipeline c(store, cfg);
  const Ecef pos = geo::ecef_from_lla(kSite);
  int differ = 0;
  for (int k = 0; k < 50; ++k) {
    const time::GpsTime t = kToe + 1.0 * k;
    const Fix fa = a.step(t, truth_at(pos, t));
    const Fix& fb = b.step(t, truth_at(pos, t));
    const Fix& fc = c.step(t, truth_at(pos, t));
    ASSERT_EQ(fa.type, FixType::k3D);
    EXPECT_EQ(fa.pos_m.x, fb.pos_m.x);
    EXPECT_EQ(fa.pos_m.z, fb.pos_m.z);
    for (int i = 0; i < fa.num_sats; ++i) EXPECT_EQ(fa.sats[i].pseudorange_m, fb.sats[i].pseudorange_m);
    differ += fa.pos_m.x != fc.pos_m.x;
  }
  EXPECT_EQ(differ, 50);
}

TEST(ReceiverAtmosphere, RainAndThunderstormCostDecibelsNotTracking) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig wet = noiseless();
  wet.world.atmosphere.clouds_rain.layers[0] = atmosphere::cloud_preset("thunderstorm");
  wet.world.atmosphere.clouds_rain.layer_count = 1;
  wet.world.atmosphere.clouds_rain.rain.rate_mm_h = 100.0;
  Pipeline dry_rx(store, noiseless()), wet_rx(store, wet);
  const Ecef pos = geo::ecef_from_lla(kSite);
  const Fix dry = dry_rx.step(kToe, truth_at(pos, kToe));
  const Fix& f = wet_rx.step(kToe, truth_at(pos, kToe));
  ASSERT_EQ(f.type, FixType::k3D);
  EXPECT_EQ(f.num_tracked, dry.num_tracked);
  for (int i = 0; i < f.num_sats; ++i) {
    if (!f.sats[i].tracked) continue;
    const double drop = dry.sats[i].cn0_dbhz - f.sats[i].cn0_dbhz;
    // Honest L1 magnitudes: hundredths of a dB at the zenith, < 1 dB at 5 deg.
    EXPECT_GT(drop, 0.01);
    EXPECT_LT(drop, 1.0);
  }
}

TEST(ReceiverAtmosphere, NoAllocationWithEveryStageAndTheCache) {
  const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store(nav.ephemerides);
  PipelineConfig cfg = test::snapshot();
  cfg.world.atmosphere.clouds_rain.layers[0] = atmosphere::cloud_preset("cumulus");
  cfg.world.atmosphere.clouds_rain.layer_count = 1;
  cfg.world.atmosphere.clouds_rain.rain.rate_mm_h = 20.0;
  cfg.world.atmosphere.cache_refresh_s = 5.0;
  cfg.world.signal.link.environment_noise_rise_db = 6.0;
  Pipeline rx(store, cfg, {.klobuchar = nav.klobuchar});
  const Lla site{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0};
  const Ecef p0 = geo::ecef_from_lla(site);
  const Vec3 v = geo::enu_to_ecef_vector(Enu(20.0, 15.0, 3.0), site.lat_rad, site.lon_rad);
  const time::GpsTime t0 = time::GpsTime::from_calendar({2022, 1, 1, 3, 0, 0.0});
  rx.step(t0, truth_at(p0, t0));
  const long before = support::allocation_count();
  int fixes = 0;
  for (int k = 1; k <= 1500; ++k) {
    const double dt = 0.5 * k;
    Truth tr = truth_at(Ecef(p0 + v * dt), t0 + dt);
    tr.vel_m_s = Ecef(v);
    if (k % 97 == 0) tr.valid = false;                                                  // antenna lost
    if (k == 1000) tr.pos_m = geo::ecef_from_lla({-10.0 * kDegToRad, 60.0 * kDegToRad, 0.0});  // cache reset
    fixes += rx.step(t0 + dt, tr).type == FixType::k3D;
  }
  EXPECT_EQ(support::allocation_count() - before, 0);
  EXPECT_GT(fixes, 1400);
}

}  // namespace
}  // namespace gnssemu::receiver::receiver_atmosphere_test

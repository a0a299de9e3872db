// SPDX-License-Identifier: Apache-2.0
// Receiver: exactness with the error model off (synthetic and real
// ephemerides), determinism, no-truth epochs, config validation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver::receiver_basic_test {
namespace {

using pipeline::Pipeline;
using pipeline::PipelineConfig;
using world::Truth;

using test::errors_off_config;
using test::expect_consistent;

const time::GpsTime kToe(2190, 100800.0);

Truth static_truth(const Lla& lla, const time::GpsTime& t) {
  Truth tr;
  tr.t = t;
  tr.pos_m = geo::ecef_from_lla(lla);
  tr.valid = true;
  return tr;
}

TEST(ReceiverBasic, ErrorsOffRecoversTruthAndClock) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const PipelineConfig cfg = errors_off_config();
  Pipeline rx(store, cfg);
  const Lla lla{48.15 * kDegToRad, 11.58 * kDegToRad, 520.0};
  for (int k = 0; k < 20; ++k) {
    const time::GpsTime t = kToe + 60.0 * k;
    const Truth tr = static_truth(lla, t);
    const Fix& f = rx.step(t, tr);
    ASSERT_EQ(f.type, FixType::k3D) << k;
    expect_consistent(f);
    EXPECT_GE(f.num_used, 6);
    EXPECT_LT((f.pos_m - tr.pos_m).norm(), 1e-3) << k;
    // Clock bias: 1 mm of range is 3.3e-12 s.
    EXPECT_NEAR(f.clock_bias_s, rx.world().true_clock_bias_s(), 3.4e-12) << k;
    EXPECT_NEAR(f.clock_drift_s_s, rx.world().true_clock_drift_s_s(), 1e-13) << k;
    EXPECT_LT(f.vel_m_s.norm(), 1e-3);
    EXPECT_NEAR(f.lla.height_m, 520.0, 1e-3);
    EXPECT_LT(f.range_rms_m, 1e-3);
    // Without noise the clock is bias + drift * elapsed (ReceiverClockConfig defaults).
    EXPECT_NEAR(rx.world().true_clock_bias_s(), cfg.world.clock.bias_s + cfg.world.clock.drift_s_s * 60.0 * k, 1e-15);
  }
}

TEST(ReceiverBasic, RealBroadcastEphemerisErrorsOffWithin1mm) {
  const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store(nav.ephemerides);
  Pipeline rx(store, errors_off_config());
  rx.receiver().set_leap_seconds(nav.leap_seconds.value_or(18));
  // Station LARM (obs/LARM0010.22O header), 2022-01-01 over two hours.
  const Ecef larm(4549397.1706, 1874003.1392, 4045167.6109);
  const time::GpsTime t0 = time::GpsTime::from_calendar({2022, 1, 1, 0, 0, 0.0});
  for (int k = 0; k < 24; ++k) {
    const time::GpsTime t = t0 + 300.0 * k + 3600.0;
    Truth tr;
    tr.pos_m = larm;
    tr.valid = true;
    const Fix& f = rx.step(t, tr);
    ASSERT_EQ(f.type, FixType::k3D);
    expect_consistent(f);
    EXPECT_LT((f.pos_m - larm).norm(), 1e-3) << k;
    EXPECT_NEAR(f.clock_bias_s, rx.world().true_clock_bias_s(), 3.4e-12);
    EXPECT_GE(f.num_visible, 6);
    EXPECT_LE(f.num_visible, 14);
    EXPECT_GT(f.dop.pdop, 1.0);
    EXPECT_LT(f.dop.pdop, 4.0);
    EXPECT_EQ(f.leap_seconds, 18);
  }
}

TEST(ReceiverBasic, DefaultErrorsGiveMetreLevelFixWithRealData) {
  const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store(nav.ephemerides);
  Pipeline rx(store, test::snapshot());
  const Ecef larm(4549397.1706, 1874003.1392, 4045167.6109);
  const time::GpsTime t0 = time::GpsTime::from_calendar({2022, 1, 1, 6, 0, 0.0});
  double worst_m = 0.0;
  for (int k = 0; k < 120; ++k) {
    Truth tr;
    tr.pos_m = larm;
    tr.valid = true;
    const Fix& f = rx.step(t0 + static_cast<double>(k), tr);
    ASSERT_EQ(f.type, FixType::k3D);
    expect_consistent(f);
    worst_m = std::max(worst_m, (f.pos_m - larm).norm());
    // Default sigma_uere ~1.24 m with PDOP < 4: beyond 20 m would be a bug.
    EXPECT_GT(f.sigma_uere_m, 1.2);
    EXPECT_NEAR(f.clock_bias_s, rx.world().true_clock_bias_s(), 30.0 / kSpeedOfLight_m_s);
  }
  EXPECT_LT(worst_m, 20.0);
  EXPECT_GT(worst_m, 0.05);  // the error model is on
}

TEST(ReceiverBasic, SameSeedIdenticalDifferentSeedDiffers) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig cfg = test::snapshot();
  cfg.world.seed = 42;
  Pipeline a(store, cfg), b(store, cfg);
  cfg.world.seed = 43;
  Pipeline c(store, cfg);
  const Lla lla{-33.9 * kDegToRad, 151.2 * kDegToRad, 40.0};
  int differing = 0;
  for (int k = 0; k < 50; ++k) {
    const time::GpsTime t = kToe + 0.2 * k;
    const Truth tr = static_truth(lla, t);
    const Fix fa = a.step(t, tr);
    const Fix fb = b.step(t, tr);
    const Fix fc = c.step(t, tr);
    ASSERT_EQ(fa.type, FixType::k3D);
    EXPECT_EQ(std::memcmp(&fa.pos_m, &fb.pos_m, sizeof(Ecef)), 0);
    EXPECT_EQ(fa.clock_bias_s, fb.clock_bias_s);
    EXPECT_EQ(fa.vel_m_s, fb.vel_m_s);
    for (int i = 0; i < fa.num_sats; ++i) {
      EXPECT_EQ(fa.sats[i].pseudorange_m, fb.sats[i].pseudorange_m);
      EXPECT_EQ(fa.sats[i].doppler_hz, fb.sats[i].doppler_hz);
    }
    differing += (fa.pos_m - fc.pos_m).norm() > 1e-3;
  }
  EXPECT_EQ(differing, 50);
}

TEST(ReceiverBasic, NoiseOfOneSatelliteDoesNotDependOnOthersVisible) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig low = test::snapshot(), high = test::snapshot();
  low.world.seed = high.world.seed = 7;
  high.receiver.elevation_mask_rad = 35.0 * kDegToRad;
  Pipeline a(store, low), b(store, high);
  const Lla lla{10.0 * kDegToRad, -70.0 * kDegToRad, 0.0};
  int compared = 0;
  for (int k = 0; k < 5; ++k) {
    const time::GpsTime t = kToe + 1.0 * k;
    const Truth tr = static_truth(lla, t);
    const Fix fa = a.step(t, tr);
    const Fix fb = b.step(t, tr);
    ASSERT_LT(fb.num_tracked, fa.num_tracked);
    for (int i = 0; i < fa.num_sats; ++i) {
      for (int j = 0; j < fb.num_sats; ++j) {
        if (fa.sats[i].sat != fb.sats[j].sat || !fb.sats[j].tracked) continue;
        EXPECT_EQ(fa.sats[i].pseudorange_m, fb.sats[j].pseudorange_m);
        EXPECT_EQ(fa.sats[i].doppler_hz, fb.sats[j].doppler_hz);
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, 10);
}

TEST(ReceiverBasic, SatellitesOfEverySystemGoThroughInSatIdOrder) {
  // Every other satellite of one constellation relabelled Galileo (the same
  // Keplerian orbits under their own identity): they are tracked and used,
  // listed after GPS, and draw their own noise, so a GPS satellite's
  // pseudorange is the same with or without them.
  const std::vector<orbit::Ephemeris> gps = test::nominal_constellation(kToe, 5);
  std::vector<orbit::Ephemeris> mixed, gps_half;
  for (std::size_t i = 0; i < gps.size(); ++i) {
    orbit::Ephemeris e = gps[i];
    if (i % 2 == 0) {
      e.sat = SatId(GnssSystem::kGalileo, e.sat.number);
      e.gal_data_sources = 517;  // I/NAV: the sets an E1 receiver selects
    } else {
      gps_half.push_back(e);
    }
    mixed.push_back(e);
  }
  const orbit::EphemerisStore mixed_store(mixed), gps_store(gps_half);
  PipelineConfig cfg = test::snapshot();
  cfg.receiver.max_channels = kMaxSatsInView;
  cfg.world.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGalileo);
  Pipeline a(mixed_store, cfg), b(gps_store, cfg);
  PipelineConfig gps_only = cfg;
  gps_only.world.systems = SystemSet::only(GnssSystem::kGps);
  Pipeline c(mixed_store, gps_only);
  const Lla lla{10.0 * kDegToRad, -70.0 * kDegToRad, 0.0};
  int galileo_used = 0, compared = 0;
  for (int k = 0; k < 5; ++k) {
    const time::GpsTime t = kToe + 1.0 * (k + 1);  // Galileo sets are used from after their toe (RTKLIB)
    const Truth tr = static_truth(lla, t);
    const Fix fa = a.step(t, tr);
    const Fix fb = b.step(t, tr);
    const Fix fc = c.step(t, tr);  // constellations = ["G"]: the Galileo sets in the store are not in its sky
    for (int i = 0; i < fc.num_sats; ++i) EXPECT_EQ(fc.sats[i].sat.system, GnssSystem::kGps);
    EXPECT_GT(fc.num_sats, 0);
    ASSERT_EQ(fa.type, FixType::k3D) << k;
    expect_consistent(fa);
    for (int i = 0; i < fa.num_sats; ++i) {
      const SatInfo& s = fa.sats[i];
      if (s.sat.system == GnssSystem::kGalileo) {
        galileo_used += s.used;
        continue;
      }
      for (int j = 0; j < fb.num_sats; ++j) {
        if (fb.sats[j].sat != s.sat || !s.tracked) continue;
        EXPECT_EQ(s.pseudorange_m, fb.sats[j].pseudorange_m);
        ++compared;
      }
    }
  }
  EXPECT_GE(galileo_used, 10);
  EXPECT_GE(compared, 10);
}

/// The nominal constellation of per_plane satellites per plane with every
/// other satellite relabelled Galileo (I/NAV E1-B sets).
std::vector<orbit::Ephemeris> gps_and_galileo(int per_plane) {
  std::vector<orbit::Ephemeris> mixed = test::nominal_constellation(kToe, per_plane);
  for (std::size_t i = 0; i < mixed.size(); i += 2) {
    mixed[i].sat = SatId(GnssSystem::kGalileo, mixed[i].sat.number);
    mixed[i].gal_data_sources = 517;
  }
  return mixed;
}

TEST(ReceiverBasic, DisabledSystemIsNeitherTrackedNorReported) {
  // CFG-GNSS with Galileo off: its satellites stay in the sky (the world
  // models them) but the receiver neither tracks nor lists them; enabled
  // again, they come back.
  const orbit::EphemerisStore store(gps_and_galileo(6));
  PipelineConfig cfg = test::snapshot();
  cfg.receiver.max_channels = kMaxSatsInView;
  cfg.world.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGalileo);
  Pipeline p(store, cfg);
  const Lla lla{10.0 * kDegToRad, -70.0 * kDegToRad, 0.0};
  const auto count = [](const Fix& f, GnssSystem s, bool used) {
    int n = 0;
    for (int i = 0; i < f.num_sats; ++i) n += f.sats[i].sat.system == s && (!used || f.sats[i].used);
    return n;
  };
  for (int k = 1; k <= 3; ++k) p.step(kToe + 1.0 * k, static_truth(lla, kToe + 1.0 * k));
  ASSERT_GT(count(p.receiver().last_fix(), GnssSystem::kGalileo, true), 0);
  p.receiver().set_systems(SystemSet::only(GnssSystem::kGps));
  for (int k = 4; k <= 6; ++k) {
    const Fix& f = p.step(kToe + 1.0 * k, static_truth(lla, kToe + 1.0 * k));
    EXPECT_EQ(count(f, GnssSystem::kGalileo, false), 0) << k;
    EXPECT_NE(f.type, FixType::kNone) << k;
    EXPECT_GE(count(f, GnssSystem::kGps, true), 3) << k;
    expect_consistent(f);
  }
  p.receiver().set_systems(SystemSet::all());
  const Fix& f = p.step(kToe + 7.0, static_truth(lla, kToe + 7.0));
  EXPECT_GT(count(f, GnssSystem::kGalileo, false), 0);
}

TEST(ReceiverBasic, NoTruthGivesNoFixAndKeepsTime) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  Pipeline rx(store, test::snapshot());
  const Lla lla{0.5, 0.3, 100.0};
  Truth lost;  // valid == false
  const Fix& f0 = rx.step(kToe, lost);
  EXPECT_EQ(f0.type, FixType::kNone);
  EXPECT_FALSE(f0.time_valid);
  EXPECT_EQ(f0.num_sats, 0);
  expect_consistent(f0);
  EXPECT_EQ(rx.step(kToe + 1.0, static_truth(lla, kToe + 1.0)).type, FixType::k3D);
  const Fix& f2 = rx.step(kToe + 2.0, lost);
  EXPECT_EQ(f2.type, FixType::kNone);
  EXPECT_TRUE(f2.time_valid);
  EXPECT_EQ(f2.num_sats, 0);
  EXPECT_EQ(f2.num_tracked, 0);
  EXPECT_EQ(f2.h_acc_m, 9999.0);
  EXPECT_EQ(f2.t, kToe + 2.0);
  expect_consistent(f2);
  // NaN truth is treated like no truth.
  Truth nan_truth = static_truth(lla, kToe + 3.0);
  nan_truth.pos_m.x = std::nan("");
  EXPECT_EQ(rx.step(kToe + 3.0, nan_truth).type, FixType::kNone);
  EXPECT_TRUE(test::all_finite(rx.last_fix()));
  // And the antenna comes back: fix again.
  EXPECT_EQ(rx.step(kToe + 4.0, static_truth(lla, kToe + 4.0)).type, FixType::k3D);
}

TEST(ReceiverBasic, LeapSecondsFromTableOrOverride) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  Pipeline rx(store, test::snapshot());
  Truth lost;
  EXPECT_EQ(rx.step(kToe, lost).leap_seconds, 18);
  const time::GpsTime t2010 = time::GpsTime::from_calendar({2010, 6, 1, 0, 0, 0.0});
  EXPECT_EQ(rx.step(t2010, lost).leap_seconds, 15);
  rx.receiver().set_leap_seconds(17);
  EXPECT_EQ(rx.step(kToe, lost).leap_seconds, 17);
}

TEST(ReceiverBasic, InvalidConfigThrows) {
  const orbit::EphemerisStore store;
  auto bad = [&](auto mutate) {
    PipelineConfig c = test::snapshot();
    mutate(c);
    EXPECT_THROW(Pipeline(store, c), Error);
  };
  bad([](PipelineConfig& c) { c.receiver.elevation_mask_rad = kPi / 2.0; });
  bad([](PipelineConfig& c) { c.receiver.elevation_mask_rad = -0.1; });
  bad([](PipelineConfig& c) { c.world.errors.thermal_sigma_m = -1.0; });
  bad([](PipelineConfig& c) { c.world.errors.orbit_clock.tau_s = 0.0; });
  bad([](PipelineConfig& c) { c.world.errors.orbit_clock.sigma_m = std::nan(""); });
  bad([](PipelineConfig& c) { c.receiver.max_channels = 0; });
  bad([](PipelineConfig& c) { c.receiver.max_channels = kMaxSatsInView + 1; });
  bad([](PipelineConfig& c) { c.receiver.max_pdop = 0.0; });
  bad([](PipelineConfig& c) { c.receiver.solver.sigma_a_m = 0.0, c.receiver.solver.sigma_b_m = 0.0; });
  bad([](PipelineConfig& c) { c.receiver.solver.residual_test_pfa = 0.7; });
  bad([](PipelineConfig& c) { c.world.clock.bias_s = 2.0; });
  EXPECT_NO_THROW(Pipeline(store, test::snapshot()));
  // An empty store is not an error: no satellites, no fix.
  Pipeline rx(store, test::snapshot());
  const Fix& f = rx.step(kToe, static_truth({0.1, 0.2, 0.0}, kToe));
  EXPECT_EQ(f.type, FixType::kNone);
  EXPECT_TRUE(f.time_valid);
  EXPECT_EQ(f.num_sats, 0);
}

TEST(ReceiverBasic, RawMeasurementsFollowTheTrackedSatellites) {
  // Every tracked satellite has one L1-band measurement on the receiver's
  // clock; its carrier lock time grows by the epoch interval while the
  // world's phase stays continuous, and the phase moves with the range.
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 6));
  Pipeline p(store, test::snapshot());
  const Lla lla{0.6, 0.2, 50.0};
  double prev_lock_s = -1.0, prev_pr_m = 0.0, prev_cp_m = 0.0;
  SatId first;
  for (int k = 1; k <= 10; ++k) {
    const Fix& f = p.step(kToe + 1.0 * k, static_truth(lla, kToe + 1.0 * k));
    const RawEpoch& raw = p.receiver().raw();
    EXPECT_EQ(raw.num_meas, f.num_tracked) << k;
    EXPECT_TRUE(raw.time_valid);
    ASSERT_GT(raw.num_meas, 0);
    for (int i = 0; i < raw.num_meas; ++i) {
      const RawMeasurement& m = raw.meas[static_cast<std::size_t>(i)];
      EXPECT_EQ(signal_info(m.signal).system, m.sat.system);
      EXPECT_EQ(signal_info(m.signal).band, 0);
      EXPECT_TRUE(m.pseudorange_valid);
      EXPECT_GT(m.pseudorange_m, 1.9e7);
      EXPECT_LT(m.pseudorange_m, 2.9e7);
    }
    const RawMeasurement& m0 = raw.meas[0];
    if (k == 1) first = m0.sat;
    if (m0.sat != first || !m0.carrier_valid) continue;
    if (prev_lock_s >= 0.0) {
      EXPECT_NEAR(m0.lock_time_s, prev_lock_s + 1.0, 1e-9) << k;
      // Phase and code change alike (code-carrier divergence only from the ionosphere and noise).
      const double dcp_m = m0.carrier_phase_cycles * kL1Wavelength_m - prev_cp_m;
      EXPECT_NEAR(dcp_m, m0.pseudorange_m - prev_pr_m, 10.0) << k;
    }
    prev_lock_s = m0.lock_time_s;
    prev_pr_m = m0.pseudorange_m;
    prev_cp_m = m0.carrier_phase_cycles * kL1Wavelength_m;
  }
  EXPECT_GE(prev_lock_s, 6.0);
  EXPECT_TRUE(p.receiver().raw().meas[0].half_cycle_resolved);
}

TEST(ReceiverBasic, ChannelBudgetPerSystem) {
  // CFG-GNSS maxTrkCh: at most 4 GPS channels; the rest go to Galileo.
  const orbit::EphemerisStore store(gps_and_galileo(8));
  PipelineConfig cfg = test::snapshot();
  cfg.world.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGalileo);
  Pipeline p(store, cfg);
  std::array<int, kNumSystems> lim{};
  lim.fill(kMaxSatsInView);
  lim[static_cast<std::size_t>(GnssSystem::kGps)] = 4;
  p.receiver().set_channel_limits(lim);
  const Lla lla{0.3, 0.1, 0.0};
  const Fix& f = p.step(kToe + 1.0, static_truth(lla, kToe + 1.0));
  int gps = 0, gal = 0;
  for (int i = 0; i < f.num_sats; ++i) {
    gps += f.sats[i].tracked && f.sats[i].sat.system == GnssSystem::kGps;
    gal += f.sats[i].tracked && f.sats[i].sat.system == GnssSystem::kGalileo;
  }
  EXPECT_EQ(gps, 4);
  EXPECT_GT(gal, 4);
  EXPECT_NE(f.type, FixType::kNone);
}

TEST(ReceiverBasic, SolutionSatelliteCapKeepsTheHighest) {
  // The NEO-M9N above 8 Hz uses at most 16 satellites: the cap keeps the
  // highest ones, the others stay tracked and unused, and the fix holds.
  const orbit::EphemerisStore store(gps_and_galileo(8));
  PipelineConfig cfg = test::snapshot();
  cfg.receiver.max_channels = kMaxSatsInView;
  cfg.world.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGalileo);
  Pipeline p(store, cfg);
  const Lla lla{0.3, 0.1, 0.0};
  const Fix& f0 = p.step(kToe + 1.0, static_truth(lla, kToe + 1.0));
  ASSERT_GT(f0.num_used, 8);
  p.receiver().set_max_solution_sats(8);
  const Fix& f = p.step(kToe + 2.0, static_truth(lla, kToe + 2.0));
  EXPECT_EQ(f.num_used, 8);
  EXPECT_NE(f.type, FixType::kNone);
  double lowest_used = 10.0, highest_unused = -10.0;
  for (int i = 0; i < f.num_sats; ++i) {
    const SatInfo& si = f.sats[i];
    if (!si.tracked) continue;
    if (si.used) lowest_used = std::min(lowest_used, si.el_rad);
    else highest_unused = std::max(highest_unused, si.el_rad);
  }
  EXPECT_GE(lowest_used, highest_unused);
  expect_consistent(f);
  p.receiver().set_max_solution_sats(kMaxSatsInView);
  EXPECT_EQ(p.step(kToe + 3.0, static_truth(lla, kToe + 3.0)).num_used, f0.num_used);
}

TEST(ReceiverBasic, RawSigmasFollowCn0AndClockStepsAreFlagged) {
  // The loops' own sigmas fall as C/N0 rises (the DLL, PLL and FLL jitter
  // formulas); a millisecond step of the receiver clock sets clock_reset at
  // that epoch only.
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 6));
  PipelineConfig c = test::snapshot();
  c.world.clock.bias_s = 0.9995e-3;
  c.world.clock.drift_s_s = 1.0e-6;  // beyond 1 ms after about 0.5 s
  c.world.clock.jump_threshold_s = 1.0e-3;
  Pipeline p(store, c);
  const Lla lla{0.6, 0.2, 50.0};
  int resets = 0, reset_epoch = 0;
  for (int k = 1; k <= 5; ++k) {
    p.step(kToe + 1.0 * k, static_truth(lla, kToe + 1.0 * k));
    const RawEpoch& raw = p.receiver().raw();
    if (raw.clock_reset) {
      ++resets;
      reset_epoch = k;
    }
    ASSERT_GT(raw.num_meas, 1);
    const RawMeasurement* weak = &raw.meas[0];
    const RawMeasurement* strong = &raw.meas[0];
    for (int i = 0; i < raw.num_meas; ++i) {
      const RawMeasurement& m = raw.meas[static_cast<std::size_t>(i)];
      EXPECT_GT(m.pseudorange_sigma_m, 0.0);
      EXPECT_LT(m.pseudorange_sigma_m, 10.0);
      EXPECT_GT(m.carrier_sigma_cycles, 0.0);
      EXPECT_LT(m.carrier_sigma_cycles, 0.25);
      EXPECT_GT(m.doppler_sigma_hz, 0.0);
      if (m.cn0_dbhz < weak->cn0_dbhz) weak = &m;
      if (m.cn0_dbhz > strong->cn0_dbhz) strong = &m;
    }
    if (strong->cn0_dbhz > weak->cn0_dbhz + 1.0) {
      EXPECT_LT(strong->pseudorange_sigma_m, weak->pseudorange_sigma_m);
      EXPECT_LT(strong->carrier_sigma_cycles, weak->carrier_sigma_cycles);
      EXPECT_LT(strong->doppler_sigma_hz, weak->doppler_sigma_hz);
    }
  }
  EXPECT_EQ(resets, 1);
  EXPECT_GT(reset_epoch, 1);  // the first epoch has no previous clock to compare with
}

}  // namespace
}  // namespace gnssemu::receiver::receiver_basic_test

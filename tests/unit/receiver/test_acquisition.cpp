// SPDX-License-Identifier: Apache-2.0
// Acquisition and reacquisition: start modes, ephemeris download at its
// GPS-time slots, C/N0 and what the receiver knows, blockages, a moved
// antenna, the unmodelled mode.
#include <gtest/gtest.h>

#include <cmath>

#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver {
namespace {

using pipeline::Pipeline;
using pipeline::PipelineConfig;
using test::kSite;
using test::kToe;
using test::truth_at;

/// Seconds from the first epoch to the first fix at rate_hz; NaN when none within limit_s.
double first_fix_s(Pipeline& rx, const Ecef& pos, const time::GpsTime& t0, double rate_hz = 1.0,
                   double limit_s = 120.0) {
  for (int k = 0; k <= static_cast<int>(limit_s * rate_hz); ++k) {
    const time::GpsTime t = t0 + k / rate_hz;
    if (rx.step(t, truth_at(pos, t)).type != FixType::kNone) return k / rate_hz;
  }
  return std::nan("");
}

PipelineConfig started(StartMode m, PipelineConfig c = {}) {
  c.receiver.acquisition.start = m;
  return c;
}

TEST(Acquisition, EphemerisWaitFollowsTheSubframeSlots) {
  EXPECT_DOUBLE_EQ(ephemeris_wait_s(0.0), 18.0);          // words 3-10 of subframes 1-3 all ahead
  EXPECT_NEAR(ephemeris_wait_s(1.2), 16.8, 1e-9);         // word 3 of subframe 1 just starting
  EXPECT_NEAR(ephemeris_wait_s(1.3), 30.5, 1e-9);         // it is under way: next frame's
  EXPECT_NEAR(ephemeris_wait_s(18.0), 30.0, 1e-9);        // subframes 4, 5: the next frame's 1-3
  EXPECT_NEAR(ephemeris_wait_s(29.9), 18.1, 1e-9);
  EXPECT_NEAR(ephemeris_wait_s(30.0 + 1.2), 16.8, 1e-9);  // the phase is taken modulo 30 s
  double sum = 0.0;
  for (int i = 0; i < 3000; ++i) {
    const double w = ephemeris_wait_s(0.01 * i);
    EXPECT_GE(w, 16.8 - 1e-9);
    EXPECT_LE(w, 30.6 + 1e-9);
    sum += w;
  }
  EXPECT_NEAR(sum / 3000.0, 27.0, 0.5);
}

TEST(Acquisition, HotWarmColdStartsTakeTheirTime) {
  const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store(nav.ephemerides);
  const Ecef pos = geo::ecef_from_lla(kSite);
  for (int k = 0; k < 6; ++k) {
    const time::GpsTime t0 = store.first_valid() + 3600.0 + 997.0 * k;
    Pipeline hot(store, started(StartMode::kHot)), warm(store, started(StartMode::kWarm)),
        cold(store, started(StartMode::kCold));
    const double t_hot = first_fix_s(hot, pos, t0);
    const double t_warm = first_fix_s(warm, pos, t0);
    const double t_cold = first_fix_s(cold, pos, t0);
    // M8 data sheet (GPS): hot 1 s, cold 29 s. Ours: an aided search, then
    // the ephemeris download (16.8..30.6 s) after 1 s of bit synchronisation.
    EXPECT_EQ(t_hot, 1.0) << k;
    EXPECT_GE(t_warm, 18.0) << k;
    EXPECT_LE(t_warm, 34.0) << k;
    EXPECT_GE(t_cold, t_warm) << k;
    EXPECT_LE(t_cold, 36.0) << k;
  }
}

TEST(Acquisition, ColdStartKnowsNoTimeUntilTheFirstHandOverWord) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  Pipeline rx(store, started(StartMode::kCold));
  const Ecef pos = geo::ecef_from_lla(kSite);
  int first_time = -1;
  for (int k = 0; k < 20; ++k) {
    const Fix& f = rx.step(kToe + 1.0 * k, truth_at(pos, kToe + 1.0 * k));
    EXPECT_EQ(f.type, FixType::kNone);
    if (f.time_valid && first_time < 0) first_time = k;
    // Tracked satellites list C/N0 but have no ephemeris yet.
    for (int i = 0; i < f.num_sats; ++i) EXPECT_FALSE(f.sats[i].ephemeris && f.sats[i].tracked && k < 15) << k;
  }
  // Acquisition (~1.5 s), bit sync (1 s), the next subframe's TLM + HOW (<= 7.2 s).
  EXPECT_GE(first_time, 2);
  EXPECT_LE(first_time, 11);
}

TEST(Acquisition, InstantModeTracksAtTheFirstEpoch) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig c;
  c.receiver.acquisition.modelled = false;
  Pipeline rx(store, c);
  EXPECT_EQ(first_fix_s(rx, geo::ecef_from_lla(kSite), kToe), 0.0);
}

TEST(Acquisition, ReacquisitionAfterABlockageTakesAboutOneSecond) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ecef pos = geo::ecef_from_lla(kSite);
  for (const double outage_s : {10.0, 60.0}) {
    Pipeline rx(store, PipelineConfig{});
    for (int k = 0; k < 30; ++k) rx.step(kToe + 1.0 * k, truth_at(pos, kToe + 1.0 * k));
    ASSERT_NE(rx.last_fix().type, FixType::kNone);
    for (int k = 30; k < 30 + static_cast<int>(outage_s); ++k) {
      world::Truth none = truth_at(pos, kToe + 1.0 * k);
      none.valid = false;
      rx.step(none.t, none);
    }
    EXPECT_EQ(rx.last_fix().type, FixType::kNone) << outage_s;
    const time::GpsTime back = kToe + 30.0 + outage_s;
    EXPECT_EQ(first_fix_s(rx, pos, back), 1.0) << outage_s;  // data sheet: reacquisition 1 s
  }
}

TEST(Acquisition, ColdSearchNeedsStrongerSignalsThanAHotOne) {
  // A receiver at the M8's own thresholds (data sheet: hot start -157 dBm =
  // 14 dB-Hz, tracking -166 dBm): a 27 dB noise rise leaves the zenith near
  // 21 dB-Hz, enough for the aided search, not for the unaided one
  // (-148 dBm = 23 dB-Hz).
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig c;
  c.receiver.tracking.acquire_dbhz = 14.0;
  c.receiver.tracking.lose_dbhz = 8.0;
  c.world.signal.link.environment_noise_rise_db = 27.0;
  Pipeline hot(store, started(StartMode::kHot, c)), cold(store, started(StartMode::kCold, c));
  const Ecef pos = geo::ecef_from_lla(kSite);
  // Weak signals take long to find (the dwell grows as 1 / (C/N0)).
  EXPECT_LE(first_fix_s(hot, pos, kToe, 1.0, 200.0), 200.0);
  EXPECT_TRUE(std::isnan(first_fix_s(cold, pos, kToe, 1.0, 200.0)));
}

TEST(Acquisition, WeakSignalsTakeLongerToFind) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ecef pos = geo::ecef_from_lla(kSite);
  double quiet_sum = 0.0, noisy_sum = 0.0;
  for (int seed = 1; seed <= 10; ++seed) {
    PipelineConfig q, n;
    q.world.seed = n.world.seed = static_cast<uint64_t>(seed);
    n.world.signal.link.environment_noise_rise_db = 10.0;
    Pipeline a(store, q), b(store, n);
    quiet_sum += first_fix_s(a, pos, kToe + 61.0 * seed, 10.0);
    noisy_sum += first_fix_s(b, pos, kToe + 61.0 * seed, 10.0);
  }
  EXPECT_GT(noisy_sum, 1.5 * quiet_sum);
}

TEST(Acquisition, RestartKeepsWhatItIsTold) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ecef pos = geo::ecef_from_lla(kSite);
  Pipeline rx(store, PipelineConfig{});
  for (int k = 0; k < 10; ++k) rx.step(kToe + 1.0 * k, truth_at(pos, kToe + 1.0 * k));
  ASSERT_NE(rx.last_fix().type, FixType::kNone);
  rx.receiver().restart(start_state(StartMode::kHot));
  EXPECT_EQ(rx.last_fix().type, FixType::kNone);
  EXPECT_EQ(first_fix_s(rx, pos, kToe + 10.0), 1.0);
  rx.receiver().restart(start_state(StartMode::kCold));
  EXPECT_FALSE(rx.receiver().acquisition().time_known());
  const double t_cold = first_fix_s(rx, pos, kToe + 20.0);
  EXPECT_GE(t_cold, 18.0);
  EXPECT_LE(t_cold, 36.0);
}

TEST(Acquisition, AFarMoveFailsTheAidedSearchAndCostsTheFullOne) {
  // Antenna carried 3000 km while the receiver ran (a simulator's teleport):
  // every signal jumps, the receiver coasts where it was, its aided search
  // misses, the full search finds the signals; satellites it had no
  // ephemeris of need the download. 15 m away, tracking just goes on.
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const Ecef here = geo::ecef_from_lla(kSite);
  const Ecef there = geo::ecef_from_lla({kSite.lat_rad - 27.0 * kDegToRad, kSite.lon_rad, 0.0});
  const Ecef nearby = geo::ecef_from_lla({kSite.lat_rad, kSite.lon_rad + 3e-6, 300.0});
  const auto fix_at = [&](Pipeline& rx, const Ecef& pos) {
    for (int k = 0; k <= 60; ++k) {
      const time::GpsTime t = kToe + 30.0 + k;
      const Fix& f = rx.step(t, truth_at(pos, t));
      if ((f.type == FixType::k2D || f.type == FixType::k3D) && (f.pos_m - pos).norm() < 50.0) {
        return static_cast<double>(k);
      }
    }
    return std::nan("");
  };
  Pipeline near(store, PipelineConfig{}), far(store, PipelineConfig{});
  for (int k = 0; k < 30; ++k) {
    near.step(kToe + 1.0 * k, truth_at(here, kToe + 1.0 * k));
    far.step(kToe + 1.0 * k, truth_at(here, kToe + 1.0 * k));
  }
  EXPECT_LE(fix_at(near, nearby), 1.0);
  const double t_far = fix_at(far, there);
  EXPECT_GE(t_far, 2.0);  // the full search at least
  EXPECT_LE(t_far, 40.0);
  // The same move for a receiver whose aided search covers every Doppler.
  PipelineConfig wide;
  wide.receiver.acquisition.aided_doppler_window_hz = 9999.0;
  Pipeline lucky(store, wide);
  for (int k = 0; k < 30; ++k) lucky.step(kToe + 1.0 * k, truth_at(here, kToe + 1.0 * k));
  EXPECT_LT(fix_at(lucky, there), t_far);
}

}  // namespace
}  // namespace gnssemu::receiver

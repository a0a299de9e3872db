// SPDX-License-Identifier: Apache-2.0
// SkyErrors: the grid processes have unit variance and the Gauss–Markov
// correlation; two receivers under one sky share the satellites' and the
// atmosphere's errors but not their own noise; a value does not depend on
// how often or by whom the sky is read.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/world/sky/shared_sky.hpp"
#include "core/world/sky/sky_errors.hpp"
#include "core/world/world.hpp"

namespace gnssemu::world {
namespace sky_errors_test {
namespace {

const orbit::NavData& nav() {
  static const orbit::NavData d =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  return d;
}

// 2024-01-10 02:00 GPST.
const time::GpsTime kStart(2296, 259200.0 + 7200.0);

SystemSet every_system() {
  return SystemSet::only(GnssSystem::kGps)
      .with(GnssSystem::kGlonass)
      .with(GnssSystem::kGalileo)
      .with(GnssSystem::kBeiDou)
      .with(GnssSystem::kQzss);
}

Truth truth_at(const time::GpsTime& t, const Vec3& offset_m = Vec3(0.0, 0.0, 0.0)) {
  const Lla site{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0};
  Truth tr;
  tr.t = t;
  tr.pos_m = Ecef(geo::ecef_from_lla(site) + offset_m);
  tr.valid = true;
  return tr;
}

TEST(SkyErrors, DefaultConfigIsTheDefaultWorlds) {
  const SkyErrorsConfig d;
  const SkyErrorsConfig w = sky_errors_config(WorldConfig{});
  EXPECT_EQ(d.seed, w.seed);
  for (std::size_t p = 0; p < d.tau_s.size(); ++p) EXPECT_EQ(d.tau_s[p], w.tau_s[p]) << p;
  WorldConfig c;
  c.seed = 7;
  EXPECT_EQ(sky_errors_config(c).seed, 7u);  // no sky seed: the seed
  c.sky_seed = 3;
  EXPECT_EQ(sky_errors_config(c).seed, 3u);
}

// A slow process (the orbit/clock residual's 1800 s) is smooth over
// seconds and keeps unit variance and its correlation across coarse nodes:
// its 1-s change is a few per mille of sigma, a rough first-order path's
// would be sqrt(2 / 1800) = 3.3 %.
TEST(SkyErrors, SlowProcessIsSmoothWithUnitVariance) {
  SkyErrorsConfig c;
  c.tau_s = {1800.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  SkyErrors e(c);
  std::vector<SatId> sats;
  for (int i = 0; i < kNumSats; ++i) sats.push_back(SatId::from_index(i));
  constexpr int kSteps = 20000;  // 1 s apart
  constexpr int kLag = 900;      // tau / 2
  std::vector<std::vector<double>> x(sats.size(), std::vector<double>(kSteps));
  for (int k = 0; k < kSteps; ++k) {
    e.begin(kStart + 1.0 * k + 0.25, sats, 0);
    for (std::size_t i = 0; i < sats.size(); ++i) {
      e.step(sats[i]);
      x[i][static_cast<std::size_t>(k)] = e.value(SkyProcess::kOrbitClock, sats[i]);
    }
  }
  double s2 = 0.0, d2 = 0.0, lag = 0.0;
  long m = 0, m_d = 0, m_lag = 0;
  for (const std::vector<double>& xs : x) {
    for (std::size_t k = 0; k < xs.size(); ++k) {
      s2 += xs[k] * xs[k];
      ++m;
      if (k > 0) {
        d2 += (xs[k] - xs[k - 1]) * (xs[k] - xs[k - 1]);
        ++m_d;
      }
      if (k + kLag < xs.size()) {
        lag += xs[k] * xs[k + kLag];
        ++m_lag;
      }
    }
  }
  // ~250 satellites x 11 correlation times: the variance is known to ~3 %.
  EXPECT_NEAR(s2 / static_cast<double>(m), 1.0, 0.08);
  EXPECT_NEAR(lag / static_cast<double>(m_lag), std::exp(-0.5), 0.06);
  const double rms_step = std::sqrt(d2 / static_cast<double>(m_d));
  EXPECT_LT(rms_step, 0.006);
  EXPECT_GT(rms_step, 0.001);  // still moving
}

// Unit variance at every fine node and between them, and the correlation
// exp(-lag / tau) across coarse nodes, over many independent satellites.
TEST(SkyErrors, GridProcessIsUnitGaussMarkov) {
  SkyErrorsConfig c;
  c.tau_s = {30.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  SkyErrors e(c);
  std::vector<SatId> sats;
  for (int i = 0; i < kNumSats; ++i) sats.push_back(SatId::from_index(i));
  const int n = static_cast<int>(sats.size());
  constexpr int kSteps = 3000;  // 0.5 s apart: 1500 s
  constexpr int kLag = 60;     // 30 s
  std::vector<std::vector<double>> x(static_cast<std::size_t>(n), std::vector<double>(kSteps));
  for (int k = 0; k < kSteps; ++k) {
    e.begin(kStart + 0.5 * k, sats, 0);
    for (int i = 0; i < n; ++i) {
      e.step(sats[static_cast<std::size_t>(i)]);
      x[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] =
          e.value(SkyProcess::kOrbitClock, sats[static_cast<std::size_t>(i)]);
    }
  }
  double s2 = 0.0, s2_half = 0.0, lag = 0.0;
  long m = 0, m_half = 0, m_lag = 0;
  for (const std::vector<double>& xs : x) {
    for (int k = 0; k < kSteps; ++k) {
      const double v = xs[static_cast<std::size_t>(k)];
      s2 += v * v;
      ++m;
      if (k % 2 == 1) {
        s2_half += v * v;  // half-way between fine nodes
        ++m_half;
      }
      if (k + kLag < kSteps) {
        lag += v * xs[static_cast<std::size_t>(k + kLag)];
        ++m_lag;
      }
    }
  }
  // ~250 satellites x 50 correlation times: the variance is known to ~1 %.
  EXPECT_NEAR(s2 / static_cast<double>(m), 1.0, 0.06);
  EXPECT_NEAR(s2_half / static_cast<double>(m_half), 1.0, 0.06);
  EXPECT_NEAR(lag / static_cast<double>(m_lag), std::exp(-1.0), 0.05);
}

// Two receivers with their own seeds under one sky (a metre apart): the
// same orbit/clock residual and atmosphere per satellite, their own noise,
// multipath and carrier ambiguities.
TEST(SkyErrors, ReceiversUnderOneSkyShareItsErrorsNotTheirNoise) {
  const orbit::EphemerisStore store(nav().ephemerides);
  WorldConfig quiet;
  quiet.systems = every_system();
  quiet.seed = 11;
  quiet.sky_seed = 5;
  quiet.errors.thermal_model = ThermalModel::kFixed;
  quiet.errors.thermal_sigma_m = 0.0;
  quiet.clock.drift_noise_s_s_sqrt_s = 0.0;
  quiet.errors.gradient.process.sigma_m = 0.05;
  quiet.errors.iono_scale.sigma = 0.2;
  WorldConfig quiet_b = quiet;
  quiet_b.seed = 12;
  WorldConfig noisy = quiet;
  noisy.errors.thermal_model = ThermalModel::kDll;
  noisy.errors.multipath.sigma_m = 0.3;
  WorldConfig noisy_b = noisy;
  noisy_b.seed = 12;
  WorldConfig other_sky = quiet;
  other_sky.sky_seed = 6;
  const SkyErrorsConfig sky_cfg = sky_errors_config(quiet);
  ASSERT_EQ(sky_cfg.seed, 5u);
  SharedSky sky(store, every_system(), sky_cfg);
  SharedSky sky6(store, every_system(), sky_errors_config(other_sky));
  World qa(store, quiet), qb(store, quiet_b), na(store, noisy), nb(store, noisy_b), q6(store, other_sky);
  int compared = 0, noise_differs = 0, other_sky_differs = 0;
  for (int k = 0; k < 200; ++k) {
    const time::GpsTime t = kStart + 1.0 * k;
    const Truth a = truth_at(t), b = truth_at(t, Vec3(1.0, 0.0, 0.0));
    const std::array<Ecef, 2> antennas{a.pos_m, b.pos_m};
    sky.update(t, antennas);
    sky6.update(t, antennas);
    const Observables& oqa = qa.step(sky, a, 5.0 * kDegToRad);
    const Observables& oqb = qb.step(sky, a, 5.0 * kDegToRad);  // the same antenna: the same geometry
    const Observables& ona = na.step(sky, b, 5.0 * kDegToRad);
    const Observables& onb = nb.step(sky, b, 5.0 * kDegToRad);
    const Observables& oq6 = q6.step(sky6, a, 5.0 * kDegToRad);
    ASSERT_EQ(oqa.num_sats, oqb.num_sats);
    ASSERT_EQ(ona.num_sats, onb.num_sats);
    ASSERT_EQ(oqa.num_sats, oq6.num_sats);
    ASSERT_GT(oqa.num_sats, 30);
    for (int i = 0; i < oqa.num_sats; ++i) {
      const SatObservable& x = oqa.sats[i];
      ASSERT_EQ(x.sat, oqb.sats[i].sat);
      if (!x.received) continue;
      // Same antenna, noise-free, different seeds: every term is the sky's.
      EXPECT_EQ(x.pseudorange_m, oqb.sats[i].pseudorange_m) << x.sat.index();
      const PathEffects& pa = qa.path_effects(x.sat);
      EXPECT_EQ(pa.iono_m, qb.path_effects(x.sat).iono_m);
      EXPECT_EQ(pa.tropo_m, qb.path_effects(x.sat).tropo_m);
      if (std::fabs(x.pseudorange_m - oq6.sats[i].pseudorange_m) > 1e-3) ++other_sky_differs;
      ++compared;
    }
    for (int i = 0; i < ona.num_sats; ++i) {
      const SatObservable& x = ona.sats[i];
      ASSERT_EQ(x.sat, onb.sats[i].sat);
      if (!x.received) continue;
      EXPECT_EQ(na.path_effects(x.sat).delay_m, nb.path_effects(x.sat).delay_m);
      if (x.pseudorange_m != onb.sats[i].pseudorange_m) ++noise_differs;
    }
  }
  ASSERT_GT(compared, 5000);
  EXPECT_GT(other_sky_differs, compared * 99 / 100);  // another sky seed: other errors
  EXPECT_GT(noise_differs, compared * 9 / 10);
}

// A value is a function of (seed, satellite, time): a sky read at 5 Hz, one
// at 1 Hz and one evaluated for every satellite without antennas give the
// same values at their common epochs, across coarse nodes.
TEST(SkyErrors, ValuesDoNotDependOnWhoReadsOrHowOften) {
  const orbit::EphemerisStore store(nav().ephemerides);
  WorldConfig cfg;
  cfg.systems = every_system();
  cfg.errors.gradient.process.sigma_m = 0.05;
  cfg.errors.iono_scale.sigma = 0.2;
  const SkyErrorsConfig sc = sky_errors_config(cfg);
  SharedSky fast(store, every_system(), sc), slow(store, every_system(), sc), all(store, every_system(), sc);
  World w_fast(store, cfg), w_slow(store, cfg);
  int compared = 0;
  for (int k = 0; k <= 5 * 300; ++k) {
    const time::GpsTime t = kStart + 0.2 * k;
    const Truth tr = truth_at(t);
    fast.update(t, std::span<const Ecef>(&tr.pos_m, 1));
    w_fast.step(fast, tr, 5.0 * kDegToRad);
    if (k % 5 != 0) continue;
    slow.update(t, std::span<const Ecef>(&tr.pos_m, 1));
    w_slow.step(slow, tr, 5.0 * kDegToRad);
    if (k % 100 == 0) all.update(t);  // every 20 s, every satellite
    for (int p = kNumSatProcesses; p < kNumSkyProcesses; ++p) {
      const auto sp = static_cast<SkyProcess>(p);
      ASSERT_EQ(fast.errors().value(sp), slow.errors().value(sp)) << p;
    }
    const Observables& o = w_slow.observables();
    for (int i = 0; i < o.num_sats; ++i) {
      const SatId sat = o.sats[i].sat;
      for (const SkyProcess sp : {SkyProcess::kOrbitClock, SkyProcess::kIono}) {
        ASSERT_EQ(fast.errors().value(sp, sat), slow.errors().value(sp, sat));
        if (k % 100 == 0) {
          ASSERT_EQ(all.errors().value(sp, sat), slow.errors().value(sp, sat));
        }
      }
      if (!o.sats[i].received) continue;
      // The slow-term cache refreshes at other epochs: within its error.
      ASSERT_NEAR(w_fast.path_effects(sat).iono_m, w_slow.path_effects(sat).iono_m, 1e-3);
      ++compared;
    }
  }
  EXPECT_GT(compared, 3000);
}

// Across block boundaries (tau 100 s: a block of 32 coarse nodes) a sky
// started late holds the same values as one running since long before, and
// the walk taking over at a block's start moves the value by nothing visible.
TEST(SkyErrors, BlocksKeepValuesPureAndContinuous) {
  SkyErrorsConfig c;
  c.tau_s = {100.0, 0.0, 100.0, 0.0, 0.0, 0.0};
  SkyErrors early(c), late(c);
  const std::array<SatId, 2> sats{SatId::from_index(0), SatId::from_index(40)};
  double last = 0.0, largest_step = 0.0;
  int compared = 0;
  for (int k = 0; k < 3 * 2048 * 2; ++k) {
    const time::GpsTime t = kStart + 0.5 * k;
    early.begin(t, sats, 1);
    for (const SatId s : sats) early.step(s);
    const double v = early.value(SkyProcess::kOrbitClock, sats[1]);
    if (k > 0) largest_step = std::max(largest_step, std::fabs(v - last));
    last = v;
    if (k < 3001) continue;
    late.begin(t, sats, 1);
    for (const SatId s : sats) late.step(s);
    for (const SatId s : sats) ASSERT_EQ(early.value(SkyProcess::kOrbitClock, s), late.value(SkyProcess::kOrbitClock, s));
    ASSERT_EQ(early.value(SkyProcess::kIonoScale), late.value(SkyProcess::kIonoScale));
    ++compared;
  }
  EXPECT_GT(compared, 9000);
  // A 0.5 s step of a unit process with tau 100 s: sqrt(1 - e^-0.01) ~ 0.1 sigma; a jump would stand out.
  EXPECT_LT(largest_step, 0.5);
}

// A receiver's observables do not depend on the sky it reads beyond its own
// antenna: a sky of its systems started at its first epoch with its antenna
// alone, and a sky of every system started 50 min earlier off the second
// grid with a second antenna 4000 km away (other satellites evaluated and
// culled), give it bit-identical observables across coarse nodes.
TEST(SkyErrors, ObservablesDoNotDependOnOtherAntennasOrTheSkysStart) {
  const orbit::EphemerisStore store(nav().ephemerides);
  WorldConfig cfg;
  cfg.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGlonass);
  cfg.errors.gradient.process.sigma_m = 0.05;
  cfg.errors.iono_scale.sigma = 0.2;
  const SkyErrorsConfig sc = sky_errors_config(cfg);
  SharedSky own(store, cfg.systems, sc), fleet(store, every_system(), sc);
  World w_own(store, cfg), w_fleet(store, cfg);
  const Vec3 far_m(-2.0e6, 3.0e6, -1.5e6);
  for (int k = -3000; k < 0; k += 7) {
    const Truth other = truth_at(kStart + (0.3 + k), far_m);
    fleet.update(kStart + (0.3 + k), std::span<const Ecef>(&other.pos_m, 1));
  }
  int compared = 0;
  for (int k = 0; k <= 5 * 200; ++k) {
    const time::GpsTime t = kStart + 0.2 * k;
    const Truth tr = truth_at(t), other = truth_at(t, far_m);
    const std::array<Ecef, 2> antennas{other.pos_m, tr.pos_m};
    own.update(t, std::span<const Ecef>(&tr.pos_m, 1));
    fleet.update(t, antennas);
    const Observables& a = w_own.step(own, tr, 5.0 * kDegToRad);
    const Observables& b = w_fleet.step(fleet, tr, 5.0 * kDegToRad);
    ASSERT_EQ(a.num_sats, b.num_sats) << k;
    for (int i = 0; i < a.num_sats; ++i) {
      const SatObservable& x = a.sats[i];
      const SatObservable& y = b.sats[i];
      ASSERT_EQ(x.sat, y.sat);
      ASSERT_EQ(x.received, y.received);
      ASSERT_EQ(x.pseudorange_m, y.pseudorange_m) << k << " " << x.sat.index();
      ASSERT_EQ(x.doppler_hz, y.doppler_hz);
      ASSERT_EQ(x.cn0_dbhz, y.cn0_dbhz);
      ASSERT_EQ(x.carrier_valid, y.carrier_valid);
      ASSERT_EQ(x.carrier_phase_cycles, y.carrier_phase_cycles);
      if (x.received) ++compared;
    }
  }
  EXPECT_GT(compared, 10000);
}

}  // namespace
}  // namespace sky_errors_test
}  // namespace gnssemu::world

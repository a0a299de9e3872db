// SPDX-License-Identifier: Apache-2.0
// gnssemu calibrate recovers the error model it is given: the world with
// known processes makes three NYA1 days (the real day's epochs and
// geometry, three seeds), and the pooled fit of those gives the processes
// back within what three days of one realisation allow.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "core/observation/rinex_obs.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "tools/gnssemu/stations/calibrate.hpp"
#include "tools/gnssemu/stations/simulated_station.hpp"

namespace gnssemu::cli {
namespace {

const std::string kData = GNSSEMU_TEST_DATA;

TEST(CalibrateRecovery, PooledFitOfSimulatedDaysGivesTheWorldBack) {
  const observation::ObsData real = observation::read_rinex_obs(kData + "/obs/NYA100NOR_S_20241240000_01D_30S_GO_L1.rnx.gz");
  const orbit::NavData nav = orbit::read_rinex_nav(kData + "/nav/NYA100NOR_S_20241240000_01D_GN.rnx");
  const orbit::EphemerisStore store(nav.ephemerides);
  const Ecef station = antenna_reference_point(real.header, real.source);
  const double mask_rad = 10.0 * kDegToRad;

  // The truth: a world like the fitted ones, with every term on.
  const config::Config base = config::default_config();
  CalibrationResult truth;
  truth.cn0.n = 100;
  truth.cn0.antenna = {8.0, -9.0, 1.0};
  truth.cn0.zenith_dbhz = 52.0;
  truth.bias.klobuchar_alpha = -0.25;
  truth.bias.scale_sigma = 0.3;
  truth.bias.scale_tau_s = 20000.0;
  truth.bias.gradient_north_m = -0.4;
  truth.bias.gradient_east_m = -0.2;
  truth.bias.gradient_sigma_m = 0.3;
  truth.bias.gradient_tau_s = 10000.0;
  truth.processes = {0.1, 0.05, 600.0, 0.6, 5400.0, 0.8, 3600.0, 0};
  world::WorldConfig w = fitted_world(truth, base.world);

  std::vector<observation::ObsData> days;
  for (uint64_t seed : {11, 12, 13}) {
    w.seed = seed;
    days.push_back(simulate_station(real, nav, store, w, station, mask_rad));
  }
  std::vector<CalibrationInput> in(days.size());
  for (std::size_t i = 0; i < days.size(); ++i) in[i] = {&days[i], &nav, "nav", station, mask_rad};
  const CalibrationResult r = calibrate(in, base);

  EXPECT_EQ(r.epochs, 3 * 2880);
  // C/N0 is the world's own curve: exact to the gases' few hundredths of a dB.
  EXPECT_NEAR(r.cn0.antenna.zenith_gain_dbi, 8.0, 0.2);
  EXPECT_NEAR(r.cn0.antenna.horizon_gain_dbi, -9.0, 0.5);
  EXPECT_LT(r.cn0.rms_db, 0.3);
  // White DLL noise: its bandwidth.
  EXPECT_NEAR(r.processes.dll_bandwidth_hz, 0.1, 0.03);
  // The slow per-satellite processes (three days, each a handful of
  // independent samples of an hours-long process): sigma within 25 %, tau
  // within a factor 2.
  EXPECT_NEAR(r.processes.orbit_clock_sigma_m, 0.6, 0.15);
  EXPECT_GT(r.processes.orbit_clock_tau_s, 2700.0);
  EXPECT_LT(r.processes.orbit_clock_tau_s, 10800.0);
  // The means of the common terms (the day means of slow processes scatter
  // by sigma sqrt(2 tau / T) / sqrt(3): 0.15 m and 0.07 here).
  EXPECT_NEAR(r.bias.klobuchar_alpha, -0.25, 0.15);
  EXPECT_NEAR(r.bias.gradient_north_m, -0.4, 0.25);
  EXPECT_NEAR(r.bias.gradient_east_m, -0.2, 0.25);
  // Their processes, after the per-satellite leakage is removed. A day
  // holds ~8.6 correlation times of the 10000 s gradient: three days give
  // its sigma to sigma sqrt(2 tau / T) / sqrt(3) = 0.083 m (1 sigma); these
  // seeds' draws on GPS time's grid give 0.148 m, 1.8 sigma low.
  EXPECT_NEAR(r.bias.gradient_sigma_m, 0.3, 0.17);
  // Three days hold ~26 correlation times of the 10000 s gradient: its tau
  // comes out low and scattered (the sky process itself has exp(-1) at 10000 s, test_sky_errors).
  EXPECT_GT(r.bias.gradient_tau_s, 1500.0);
  EXPECT_NEAR(r.bias.scale_sigma, 0.3, 0.15);
  // The world written for the fitted model carries them.
  const world::WorldConfig back = fitted_world(r, base.world);
  EXPECT_EQ(back.errors.iono_scale.sigma, r.bias.scale_sigma);
  EXPECT_EQ(back.errors.gradient.process.sigma_m, r.bias.gradient_sigma_m);
  EXPECT_EQ(back.atmosphere.troposphere.zwd_model, atmosphere::ZwdModel::kSaastamoinen);
}

}  // namespace
}  // namespace gnssemu::cli

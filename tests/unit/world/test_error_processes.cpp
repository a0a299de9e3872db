// SPDX-License-Identifier: Apache-2.0
// Error-process building blocks: Gauss–Markov exact
// discretisation, receiver clock.
#include <gtest/gtest.h>

#include <cmath>

#include "core/world/measurement/error_processes.hpp"
#include "core/world/random.hpp"

namespace gnssemu::world {
namespace {

TEST(GaussMarkov, StationaryVarianceAndCorrelationTime) {
  const CounterRng rng(5);
  const GaussMarkovConfig cfg{2.0, 100.0};
  const double dt = 10.0;
  double x = gauss_markov_init(cfg, rng.normal(1, 0, Purpose::kGaussMarkovInit));
  double sum2 = 0.0, lag = 0.0;
  const int n = 200000;
  for (int k = 1; k <= n; ++k) {
    const double next = gauss_markov_step(x, dt, cfg, rng.normal(1, static_cast<uint64_t>(k), Purpose::kGaussMarkovStep));
    sum2 += next * next;
    lag += next * x;
    x = next;
  }
  EXPECT_NEAR(std::sqrt(sum2 / n), 2.0, 0.06);
  EXPECT_NEAR(lag / sum2, std::exp(-dt / cfg.tau_s), 0.01);  // 0.905
  EXPECT_EQ(gauss_markov_step(1.5, 0.0, cfg, 3.0), 1.5);     // no time, no change
  EXPECT_EQ(gauss_markov_step(1.5, 5.0, GaussMarkovConfig{0.0, 10.0}, 3.0), 0.0);
  // Large steps decorrelate completely: x_k = sigma * w.
  EXPECT_NEAR(gauss_markov_step(1.5, 1e6, cfg, 0.5), 1.0, 1e-12);
}

TEST(ReceiverClock, IntegratesDriftAndJumpsByMilliseconds) {
  ClockConfig c;
  c.bias_s = 9.0e-4;
  c.drift_s_s = 1.0e-6;
  c.drift_noise_s_s_sqrt_s = 0.0;
  ReceiverClock clk(c);
  clk.advance(50.0, 0.0);
  EXPECT_NEAR(clk.bias_s(), 9.5e-4, 1e-15);
  clk.advance(100.0, 0.0);  // 1.05 ms -> jumps to 0.05 ms
  EXPECT_NEAR(clk.bias_s(), 5.0e-5, 1e-15);
  EXPECT_EQ(clk.drift_s_s(), 1.0e-6);
  // Random walk of the drift: variance q^2 dt.
  c.drift_noise_s_s_sqrt_s = 1e-9;
  ReceiverClock walk(c);
  walk.advance(4.0, 1.0);
  EXPECT_NEAR(walk.drift_s_s(), 1.0e-6 + 2.0e-9, 1e-18);
}

TEST(OrbitClockProcess, ScalesTheGpsSigmaBySystemSisre) {
  const GaussMarkovConfig gps{1.2, 1800.0};
  EXPECT_EQ(orbit_clock_process(gps, GnssSystem::kGps).sigma_m, 1.2);  // GPS exactly as configured
  EXPECT_EQ(orbit_clock_process(gps, GnssSystem::kGps).tau_s, 1800.0);
  // The SISRE share swapped: sqrt(1.2^2 - 0.6^2 + SISRE^2).
  EXPECT_NEAR(orbit_clock_process(gps, GnssSystem::kGalileo).sigma_m, std::sqrt(1.44 - 0.36 + 0.04), 1e-12);
  EXPECT_NEAR(orbit_clock_process(gps, GnssSystem::kGlonass).sigma_m, std::sqrt(1.44 - 0.36 + 4.0), 1e-12);
  EXPECT_NEAR(orbit_clock_process(gps, GnssSystem::kBeiDou).sigma_m, std::sqrt(1.44 - 0.36 + 1.0), 1e-12);
  EXPECT_EQ(orbit_clock_process(gps, GnssSystem::kQzss).sigma_m, 1.2);
  // A fitted sigma below GPS's SISRE is all SISRE: scaled by the ratio.
  EXPECT_NEAR(orbit_clock_process(GaussMarkovConfig{0.3, 1800.0}, GnssSystem::kGlonass).sigma_m, 0.3 * 2.0 / 0.6,
              1e-12);
  EXPECT_EQ(orbit_clock_process(gps, GnssSystem::kGalileo).tau_s, 1800.0);
  EXPECT_EQ(orbit_clock_process(GaussMarkovConfig{0.0, 60.0}, GnssSystem::kGlonass).sigma_m, 0.0);
}

}  // namespace
}  // namespace gnssemu::world

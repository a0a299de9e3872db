// SPDX-License-Identifier: Apache-2.0
// Every configuration calibrate writes loads again: fits with no power or
// no correlation (sigma or tau 0, NaN, beyond the ranges) are written as
// processes that are off or clamped, never as values the loader rejects.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "tools/gnssemu/stations/calibrate.hpp"

using namespace gnssemu;

namespace {

cli::CalibrationResult degenerate(double sigma, double tau_s) {
  cli::CalibrationResult r;
  r.processes.orbit_clock_sigma_m = sigma;
  r.processes.orbit_clock_tau_s = tau_s;
  r.processes.multipath_sigma_m = sigma;
  r.processes.multipath_tau_s = tau_s;
  r.processes.iono_sigma_tecu = sigma;
  r.processes.iono_tau_s = tau_s;
  r.bias.gradient_sigma_m = sigma;
  r.bias.gradient_tau_s = tau_s;
  return r;
}

}  // namespace

TEST(CalibrateRoundTrip, EveryDegenerateFitLoadsAgain) {
  const config::Config base = config::default_config();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<double, double>> fits = {
      {0.0, 0.0}, {0.0, 900.0}, {1.5, 0.0}, {1.5, -3.0}, {nan, 900.0}, {1.5, nan}, {1e9, 1e12}, {-1.0, 900.0},
      {0.8, 1200.0}};
  for (const auto& [sigma, tau] : fits) {
    cli::CalibrationResult r = degenerate(sigma, tau);
    r.config = base;
    r.config.world = cli::fitted_world(r, base.world);
    const std::string text = cli::calibration_toml(r, ".");
    SCOPED_TRACE("sigma " + std::to_string(sigma) + " tau " + std::to_string(tau));
    config::Config back;
    ASSERT_NO_THROW(back = config::parse_config(text, "fitted.toml", ".")) << text;
    const auto& em = back.world.errors;
    if (sigma == 0.8) {  // a good fit is written as fitted
      EXPECT_DOUBLE_EQ(em.orbit_clock.sigma_m, 0.8);
      EXPECT_DOUBLE_EQ(em.orbit_clock.tau_s, 1200.0);
      EXPECT_DOUBLE_EQ(em.multipath.tau_s, 1200.0);
    } else if (!(sigma > 0.0) || !(tau > 0.0)) {  // no power or no correlation: off
      EXPECT_EQ(em.orbit_clock.sigma_m, 0.0);
      EXPECT_EQ(em.multipath.sigma_m, 0.0);
      EXPECT_GT(em.orbit_clock.tau_s, 0.0);
      EXPECT_GT(em.multipath.tau_s, 0.0);
    }
  }
}

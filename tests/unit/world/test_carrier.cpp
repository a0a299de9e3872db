// SPDX-License-Identifier: Apache-2.0
// Carrier loop noise and slips as pure functions of C/N0 (core/world/measurement/carrier.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/error.hpp"
#include "core/world/measurement/carrier.hpp"

namespace gnssemu::world {
namespace {

TEST(Carrier, PllJitterFollowsTheThermalFormula) {
  // 45 dB-Hz, B_n 10 Hz, T 20 ms: sqrt(10 / 31623 (1 + 1 / (2 0.02 31623))) = 0.017790 rad.
  EXPECT_NEAR(pll_jitter_rad(45.0, 10.0, 0.02), 0.017790, 2e-6);
  EXPECT_GT(pll_jitter_rad(25.0, 10.0, 0.02), 5.0 * pll_jitter_rad(45.0, 10.0, 0.02));
  EXPECT_TRUE(std::isfinite(pll_jitter_rad(std::nan(""), 10.0, 0.02)));  // NaN C/N0: no signal, finite
}

TEST(Carrier, FllDopplerNoiseFollowsCn0) {
  const CarrierConfig c;
  // lambda / (2 pi T) sqrt(4 B / C/N0 (1 + 1 / (T C/N0))) at 45 dB-Hz = 0.02411 m/s.
  EXPECT_NEAR(fll_range_rate_sigma_m_s(45.0, c), 0.02411, 2e-5);
  double prev = 1e9;
  for (double cn0 = 20.0; cn0 <= 55.0; cn0 += 5.0) {
    const double s = fll_range_rate_sigma_m_s(cn0, c);
    EXPECT_LT(s, prev) << cn0;
    prev = s;
  }
}

TEST(Carrier, SlipsRareOnStrongSignalsFrequentNearThreshold) {
  const CarrierConfig c;
  const auto p = [&](double cn0) {
    const double sigma = std::hypot(pll_jitter_rad(cn0, c.pll_bandwidth_hz, c.integration_s), c.oscillator_sigma_rad);
    return cycle_slip_probability(sigma, c.pll_bandwidth_hz, 1.0);
  };
  EXPECT_LT(p(45.0), 1e-9);
  EXPECT_LT(p(30.0), 1e-3);
  EXPECT_GT(p(20.0), 0.05);
  EXPECT_LE(p(10.0), 1.0);
  EXPECT_EQ(cycle_slip_probability(0.1, 10.0, 0.0), 0.0);
  // Longer intervals: more slips, never beyond 1.
  EXPECT_GT(cycle_slip_probability(0.3, 10.0, 10.0), cycle_slip_probability(0.3, 10.0, 1.0));
}

TEST(Carrier, ValidationNamesTheSetting) {
  CarrierConfig c;
  c.pll_bandwidth_hz = 0.0;
  try {
    validate(c);
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pll_bandwidth_hz"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(validate(CarrierConfig{}));
}

TEST(Carrier, FllRangeRateNoiseScalesWithTheWavelength) {
  const CarrierConfig c;
  const double g1 = kSpeedOfLight_m_s / 1602.0e6;
  EXPECT_EQ(fll_range_rate_sigma_m_s(40.0, c), fll_range_rate_sigma_m_s(40.0, c, kL1Wavelength_m));
  EXPECT_NEAR(fll_range_rate_sigma_m_s(40.0, c, g1) / fll_range_rate_sigma_m_s(40.0, c), 1575.42 / 1602.0, 1e-12);
}

}  // namespace
}  // namespace gnssemu::world

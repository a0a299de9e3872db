// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/signal/dll_jitter.hpp"

using namespace gnssemu;
using namespace gnssemu::signal;

// Expected values from a Python evaluation of the same formulas.
TEST(DllJitter, ThermalSigma) {
  const DllParams p;  // B_L 0.5 Hz, T 20 ms, d 0.5, EMLP
  EXPECT_NEAR(kCaChip_m, 293.0523, 1e-4);
  EXPECT_NEAR(dll_thermal_sigma_m(45.0, p), 0.583254, 1e-5);
  EXPECT_NEAR(dll_thermal_sigma_m(30.0, p), 3.383876, 1e-5);
  DllParams dp = p;
  dp.discriminator = DllDiscriminator::kDotProduct;
  EXPECT_NEAR(dll_thermal_sigma_m(45.0, dp), 0.583100, 1e-5);
  DllParams wide{1.0, 0.02, 1.0};
  EXPECT_NEAR(dll_thermal_sigma_m(35.0, wide), 3.742748, 1e-5);
  // Monotone in C/N0, finite at the clamps.
  EXPECT_GT(dll_thermal_sigma_m(20.0, p), dll_thermal_sigma_m(40.0, p));
  EXPECT_TRUE(std::isfinite(dll_thermal_sigma_m(-50.0, p)));
  EXPECT_TRUE(std::isfinite(dll_thermal_sigma_m(NAN, p)));
  EXPECT_EQ(dll_thermal_sigma_m(-50.0, p), dll_thermal_sigma_m(0.0, p));
}

TEST(DllJitter, Validation) {
  EXPECT_NO_THROW(validate(DllParams{}));
  EXPECT_THROW(validate(DllParams{0.0, 0.02, 0.5}), Error);
  EXPECT_THROW(validate(DllParams{0.5, 0.0, 0.5}), Error);
  EXPECT_THROW(validate(DllParams{0.5, 0.02, 1.5}), Error);
  EXPECT_THROW(validate(DllParams{0.5, 0.02, 0.0}), Error);
}


// SPDX-License-Identifier: Apache-2.0
// MeasurementNoise: the one place the world's code and range-rate noise
// versus C/N0 is decided (the fault stage adds the difference it makes).
#include <gtest/gtest.h>

#include "core/world/measurement/measurement_noise.hpp"

namespace gnssemu::world {
namespace {

TEST(MeasurementNoise, CodeNoiseFollowsTheConfiguredModel) {
  WorldConfig c;
  c.errors.thermal_model = ThermalModel::kDll;
  MeasurementNoise n = MeasurementNoise::of(c);
  EXPECT_DOUBLE_EQ(n.code_sigma_m(35.0), signal::dll_thermal_sigma_m(35.0, c.signal.dll));
  EXPECT_GT(n.code_sigma_m(25.0), n.code_sigma_m(45.0));
  c.errors.thermal_model = ThermalModel::kFixed;
  c.errors.thermal_sigma_m = 0.7;
  n = MeasurementNoise::of(c);
  EXPECT_EQ(n.code_sigma_m(25.0), 0.7);  // a jammer adds nothing to a fixed model
  EXPECT_EQ(n.code_sigma_m(45.0), 0.7);
}

TEST(MeasurementNoise, RangeRateNoiseFollowsTheDopplerModelEvenWithoutCarrier) {
  WorldConfig c;
  c.carrier.doppler_model = DopplerModel::kFll;
  c.carrier.enabled = false;  // the world still draws FLL noise: so must the fault stage
  MeasurementNoise n = MeasurementNoise::of(c);
  EXPECT_DOUBLE_EQ(n.range_rate_sigma_m_s(30.0), fll_range_rate_sigma_m_s(30.0, c.carrier));
  c.carrier.doppler_model = DopplerModel::kFixed;
  c.errors.doppler_sigma_m_s = 0.05;
  n = MeasurementNoise::of(c);
  EXPECT_EQ(n.range_rate_sigma_m_s(30.0), 0.05);
}

}  // namespace
}  // namespace gnssemu::world

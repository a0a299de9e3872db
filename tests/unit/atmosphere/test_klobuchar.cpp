// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/atmosphere/klobuchar.hpp"
#include "core/common/constants.hpp"

using namespace gnssemu;
using namespace gnssemu::atmosphere;

namespace {
const orbit::KlobucharParams kRtk = rtklib_default_klobuchar();
}  // namespace

// Reference atmosphere.md §1.1: 45N 0E az 0, RTKLIB default coefficients.
TEST(Klobuchar, ReferenceValuesDaytime) {
  const double tow = 14.0 * 3600.0;  // 14 h local time at lon 0 (Sunday)
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 45 * kDegToRad, 0, 0, 90 * kDegToRad, tow), 3.64, 0.005);
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 45 * kDegToRad, 0, 0, 30 * kDegToRad, tow), 6.25, 0.005);
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 45 * kDegToRad, 0, 0, 5 * kDegToRad, tow), 10.3, 0.05);
}

TEST(Klobuchar, ReferenceValuesNight) {
  const double tow = 2.0 * 3600.0;
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 45 * kDegToRad, 0, 0, 90 * kDegToRad, tow), 1.50, 0.005);
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 45 * kDegToRad, 0, 0, 30 * kDegToRad, tow), 2.65, 0.005);
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 45 * kDegToRad, 0, 0, 5 * kDegToRad, tow), 4.54, 0.005);
  // Night floor is 5 ns * c * F.
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 45 * kDegToRad, 0, 0, 90 * kDegToRad, tow),
              5e-9 * kSpeedOfLight_m_s * klobuchar_slant_factor(90 * kDegToRad), 1e-9);
}

// Independent evaluation: a hand-written Python transcription of IS-GPS-200
// Fig. 20-4 (pi = math.pi), run once; values pasted here.
TEST(Klobuchar, IndependentPythonEvaluation) {
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 45 * kDegToRad, 0, 0, 90 * kDegToRad, 14 * 3600.0), 3.6358, 1e-4);
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 45 * kDegToRad, 0, 0, 5 * kDegToRad, 14 * 3600.0), 10.3248, 1e-4);
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, -33.9 * kDegToRad, 151.2 * kDegToRad, 135 * kDegToRad, 20 * kDegToRad, 345600 + 3 * 3600.5),
              7.795749204031743, 1e-6);
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 89.9 * kDegToRad, -179.99 * kDegToRad, 270 * kDegToRad, 7 * kDegToRad, 100.0),
              4.339823191399475, 1e-6);
}

TEST(Klobuchar, SlantFactor) {
  EXPECT_NEAR(klobuchar_slant_factor(90 * kDegToRad), 1.0 + 16.0 * std::pow(0.03, 3), 1e-9);
  EXPECT_NEAR(klobuchar_slant_factor(0.0), 1.0 + 16.0 * std::pow(0.53, 3), 1e-12);  // 3.382
  EXPECT_NEAR(klobuchar_slant_factor(-0.2), klobuchar_slant_factor(0.0), 0.0);
  EXPECT_NEAR(klobuchar_delay_l1_m(kRtk, 0.3, 0.2, 1.0, 0.4, 50000.0),
              klobuchar_vertical_delay_l1_m(kRtk, 0.3, 0.2, 1.0, 0.4, 50000.0) * klobuchar_slant_factor(0.4), 1e-12);
}

TEST(Klobuchar, FrequencyScaling) {
  // L2 = 1227.60 MHz: (f1/f2)^2 = 1.6469.
  EXPECT_NEAR(iono_delay_at_freq_m(1.0, 1227.60e6), 1.646944, 1e-6);
  EXPECT_EQ(iono_delay_at_freq_m(1.0, 0.0), 0.0);
}

TEST(Klobuchar, ZeroCoefficientsGiveNightFloor) {
  orbit::KlobucharParams zero;
  EXPECT_NEAR(klobuchar_delay_l1_m(zero, 0.5, 0.5, 0.0, 90 * kDegToRad, 50400.0),
              5e-9 * kSpeedOfLight_m_s * klobuchar_slant_factor(90 * kDegToRad), 1e-12);
}

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/atmosphere/receiver_corrections.hpp"
#include "core/common/constants.hpp"

using namespace gnssemu;
using atmosphere::TropoCorrection;

// RTKLIB's tropmodel maps the Saastamoinen zenith delay with 1/cos z.
TEST(ReceiverTropoCosZ, ZenithDelayTimesCosecant) {
  const double lat = 78.93 * kDegToRad, h = 80.0, doy = 124.0;
  const double zenith = atmosphere::receiver_tropo_delay_m(lat, h, kPi / 2, doy, TropoCorrection::kSaastamoinenCosZ);
  EXPECT_NEAR(zenith, atmosphere::receiver_tropo_delay_m(lat, h, kPi / 2, doy, TropoCorrection::kSaastamoinenNiell),
              1e-3);  // both mappings are 1 at the zenith
  EXPECT_GT(zenith, 2.2);
  EXPECT_LT(zenith, 2.5);
  const double at30 = atmosphere::receiver_tropo_delay_m(lat, h, 30.0 * kDegToRad, doy,
                                                         TropoCorrection::kSaastamoinenCosZ);
  EXPECT_NEAR(at30, 2.0 * zenith, 1e-9);
  // Low elevations: 1/sin exceeds Niell (5.76 vs ~5.56 at 10 deg).
  const double el = 10.0 * kDegToRad;
  EXPECT_GT(atmosphere::receiver_tropo_delay_m(lat, h, el, doy, TropoCorrection::kSaastamoinenCosZ),
            atmosphere::receiver_tropo_delay_m(lat, h, el, doy, TropoCorrection::kSaastamoinenNiell) + 0.3);
  // Held at 1 degree: finite at and below the horizon.
  EXPECT_TRUE(std::isfinite(atmosphere::receiver_tropo_delay_m(lat, h, -0.1, doy, TropoCorrection::kSaastamoinenCosZ)));
}

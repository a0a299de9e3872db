// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/atmosphere/clouds_rain.hpp"
#include "core/atmosphere/shells.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"

using namespace gnssemu;
using namespace gnssemu::atmosphere;

TEST(Clouds, P840CoefficientAtL1) {
  // Reference §3.2: 2.32e-3 at 0 C, 1.71e-3 at 10 C, 1.33e-3 at 20 C.
  EXPECT_NEAR(cloud_specific_attenuation_coeff(kL1Freq_hz, 273.15), 2.32e-3, 0.01e-3);
  EXPECT_NEAR(cloud_specific_attenuation_coeff(kL1Freq_hz, 283.15), 1.71e-3, 0.01e-3);
  EXPECT_NEAR(cloud_specific_attenuation_coeff(kL1Freq_hz, 293.15), 1.33e-3, 0.01e-3);
  EXPECT_EQ(cloud_specific_attenuation_coeff(kL1Freq_hz, 0.0), 0.0);
}

TEST(Clouds, PresetsAndErrors) {
  EXPECT_NEAR(cloud_preset("thick_fog").liquid_water_g_m3, 0.5, 0.0);
  EXPECT_NEAR(cloud_preset("thunderstorm").thickness_m, cloud_preset("cumulonimbus").thickness_m, 0.0);
  try {
    cloud_preset("drizzle");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown cloud preset 'drizzle'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cumulus"), std::string::npos);
  }
  CloudsRainConfig c;
  c.layer_count = 1;
  c.layers[0] = {1000.0, -10.0, 0.5, 273.15};
  EXPECT_THROW(CloudsRain{c}, Error);
  c.layers[0] = {1000.0, 10.0, 0.5, 0.0};
  EXPECT_THROW(CloudsRain{c}, Error);
  c.layers[0] = {1000.0, 10.0, -0.5, 273.15};
  EXPECT_THROW(CloudsRain{c}, Error);
  c.layers[0] = cloud_preset("fog");
  c.rain.rate_mm_h = -1.0;
  EXPECT_THROW(CloudsRain{c}, Error);
  c.rain = {};
  c.layer_count = kMaxCloudLayers + 1;
  EXPECT_THROW(CloudsRain{c}, Error);
}

TEST(Clouds, SlantAttenuation) {
  CloudsRainConfig c;
  c.layer_count = 1;
  c.layers[0] = cloud_preset("cumulus");  // 1.0 g/m^3 over 1.5 km at 5 C
  const CloudsRain cr(c);
  const double k = cloud_specific_attenuation_coeff(kL1Freq_hz, 278.15);
  EXPECT_NEAR(cr.attenuation(0.0, 90 * kDegToRad).clouds_db, k * 1.0 * 1.5, 1e-9);
  // Above the cloud top nothing, inside the cloud the part above.
  EXPECT_EQ(cr.attenuation(3000.0, 90 * kDegToRad).clouds_db, 0.0);
  EXPECT_NEAR(cr.attenuation(2000.0, 90 * kDegToRad).clouds_db, k * 0.5, 1e-9);
  // Reference §3.2: 1 kg/m^2 column at 0 C -> 0.0023 dB zenith, 0.027 dB at 5 deg.
  CloudsRainConfig one;
  one.layer_count = 1;
  one.layers[0] = {2000.0, 1000.0, 1.0, 273.15};
  const CloudsRain heavy(one);
  EXPECT_NEAR(heavy.attenuation(0.0, 90 * kDegToRad).clouds_db, 0.00232, 0.00002);
  // At 5 deg the spherical path through 2-3 km is 8% shorter than the flat 1/sin(e) one.
  const double k0 = cloud_specific_attenuation_coeff(kL1Freq_hz, 273.15);
  EXPECT_NEAR(heavy.attenuation(0.0, 5 * kDegToRad).clouds_db, k0 * slant_path_in_shell_m(0.0, 5 * kDegToRad, 2000.0, 3000.0) * 1e-3,
              1e-12);
  EXPECT_NEAR(heavy.attenuation(0.0, 5 * kDegToRad).clouds_db, 0.027, 0.002);
  // Thunderstorm: still a tenth of a dB at most at 5 deg.
  CloudsRainConfig cb;
  cb.layer_count = 1;
  cb.layers[0] = cloud_preset("thunderstorm");
  const double a5 = CloudsRain(cb).attenuation(0.0, 5 * kDegToRad).clouds_db;
  EXPECT_GT(a5, 0.1);
  EXPECT_LT(a5, 1.0);
}

TEST(Rain, P838AtL1) {
  // Reference §3.3: 1.2e-3 dB/km at 25 mm/h, 4.6e-3 dB/km at 100 mm/h.
  EXPECT_NEAR(rain_specific_attenuation_db_km(25.0), 1.22e-3, 0.01e-3);
  EXPECT_NEAR(rain_specific_attenuation_db_km(100.0), 4.59e-3, 0.01e-3);
  EXPECT_EQ(rain_specific_attenuation_db_km(0.0), 0.0);
  CloudsRainConfig c;
  c.rain.rate_mm_h = 100.0;
  c.rain.rain_height_m = 5000.0;
  const CloudsRain cr(c);
  EXPECT_NEAR(cr.attenuation(0.0, 90 * kDegToRad).rain_db, 5.0 * 4.59e-3, 0.1e-3);  // ~0.02 dB
  EXPECT_NEAR(cr.attenuation(0.0, 30 * kDegToRad).rain_db, slant_path_in_shell_m(0.0, 30 * kDegToRad, 0.0, 5000.0) * 1e-3 *
                                                          rain_specific_attenuation_db_km(100.0),
              1e-12);
  EXPECT_EQ(cr.attenuation(6000.0, 30 * kDegToRad).rain_db, 0.0);  // aircraft above the rain
  EXPECT_GT(cr.attenuation(-400.0, 90 * kDegToRad).rain_db, cr.attenuation(0.0, 90 * kDegToRad).rain_db);
}

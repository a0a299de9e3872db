// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/atmosphere/troposphere.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"

using namespace gnssemu;
using namespace gnssemu::atmosphere;

// Reference atmosphere.md §2.2 table: 45N, DOY 28, h = 0.
TEST(Niell, ReferenceTable) {
  const double el[] = {90, 30, 15, 10, 5, 3};
  const double mh[] = {1.0000, 1.9928, 3.8015, 5.5558, 10.152, 14.699};
  const double mw[] = {1.0000, 1.9965, 3.8333, 5.6571, 10.751, 16.417};
  for (int i = 0; i < 6; ++i) {
    const NiellMapping m = niell_mapping(el[i] * kDegToRad, 45 * kDegToRad, 0.0, 28.0);
    const double tol_h = mh[i] < 10 ? 1e-4 : 1e-3;
    const double tol_w = mw[i] < 10 ? 1e-4 : 1e-3;
    EXPECT_NEAR(m.hydro, mh[i], tol_h) << el[i];
    EXPECT_NEAR(m.wet, mw[i], tol_w) << el[i];
  }
}

TEST(Niell, SeasonHemisphereAndHeight) {
  // Southern hemisphere is shifted by half a year.
  const NiellMapping n = niell_mapping(5 * kDegToRad, 45 * kDegToRad, 0.0, 28.0);
  const NiellMapping s = niell_mapping(5 * kDegToRad, -45 * kDegToRad, 0.0, 28.0 + 182.625);
  EXPECT_NEAR(n.hydro, s.hydro, 1e-12);
  // At 15 deg and below the amplitude is zero: no season.
  EXPECT_NEAR(niell_mapping(5 * kDegToRad, 10 * kDegToRad, 0.0, 1.0).hydro, niell_mapping(5 * kDegToRad, 10 * kDegToRad, 0.0, 200.0).hydro,
              1e-12);
  // Height correction: +1 km adds [1/sin e - m(a_ht, b_ht, c_ht)] (> 0), i.e. raises m_h.
  const double dh = niell_mapping(5 * kDegToRad, 45 * kDegToRad, 1000.0, 28.0).hydro - n.hydro;
  EXPECT_GT(dh, 0.01);
  EXPECT_LT(dh, 0.2);
  // Interpolation in latitude is linear between rows; beyond 75 deg held.
  EXPECT_NEAR(niell_mapping(5 * kDegToRad, 80 * kDegToRad, 0, 100).hydro, niell_mapping(5 * kDegToRad, 90 * kDegToRad, 0, 100).hydro, 1e-12);
  // Wet has neither season nor height term.
  EXPECT_NEAR(niell_mapping(5 * kDegToRad, 45 * kDegToRad, 3000.0, 200.0).wet, n.wet, 1e-12);
}

// Reference §2.1 ZHD at 45 deg.
TEST(Saastamoinen, ReferenceZhd) {
  const double h[] = {0.0, 1000.0, 2000.0, 3000.0};
  const double zhd[] = {2.307, 2.047, 1.811, 1.598};
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(saastamoinen_zhd_m(standard_atmosphere(h[i]).pressure_hpa, 45 * kDegToRad, h[i]), zhd[i], 0.001) << h[i];
}

TEST(Saastamoinen, StandardAtmosphere) {
  const Meteo m0 = standard_atmosphere(0.0);
  EXPECT_NEAR(m0.pressure_hpa, 1013.25, 1e-9);
  EXPECT_NEAR(m0.temperature_k, 288.15, 1e-9);
  // e at 15 deg C, RH 0.7: 6.108 * 0.7 * exp((17.15*288.15 - 4684)/(288.15 - 38.45)) = 12.004 hPa.
  EXPECT_NEAR(m0.water_vapour_hpa, 12.004, 0.001);
  // ISA 11 km: 226.3 hPa, 216.65 K; continuous across the tropopause.
  EXPECT_NEAR(standard_atmosphere(11000.0).pressure_hpa, 226.3, 0.2);
  EXPECT_NEAR(standard_atmosphere(11000.0).pressure_hpa, standard_atmosphere(11000.001).pressure_hpa, 1e-3);
  // ISA 20 km: 54.75 hPa.
  EXPECT_NEAR(standard_atmosphere(20000.0).pressure_hpa, 54.75, 0.3);
  // ZWD at sea level: 0.002277 * (1255 / 288.15 + 0.05) * 12.004 = 0.1204 m.
  EXPECT_NEAR(saastamoinen_zwd_m(m0.temperature_k, m0.water_vapour_hpa), 0.1204, 0.0001);
}

TEST(Troposphere, ExponentialZhdFitsSaastamoinen) {
  // Reference §2.1: a = 2.31 m, b = 1.2e-4 1/m within 2 cm up to 3 km.
  for (double h = 0.0; h <= 3000.0; h += 250.0)
    EXPECT_NEAR(exponential_zhd_m(h), saastamoinen_zhd_m(standard_atmosphere(h).pressure_hpa, 45 * kDegToRad, h), 0.02)
        << h;
}

TEST(Troposphere, WorldSlantDelay) {
  const Troposphere t(TroposphereConfig{});
  // Zenith at sea level: 2.31 + 0.10 m.
  EXPECT_NEAR(t.slant_delay_m(45 * kDegToRad, 0.0, 90 * kDegToRad, 28.0), 2.41, 1e-9);
  // Reference §4.2: about 23 m at 5 deg.
  const double d5 = t.slant_delay_m(45 * kDegToRad, 0.0, 5 * kDegToRad, 28.0);
  EXPECT_NEAR(d5, 2.31 * 10.152 + 0.10 * 10.751, 0.01);
  TroposphereConfig off;
  off.enabled = false;
  EXPECT_EQ(Troposphere(off).slant_delay_m(0.1, 0.0, 0.1, 1.0), 0.0);
  // Receiver's standard correction close to the world default at the zenith (differs by the wet part).
  EXPECT_NEAR(standard_troposphere_correction_m(45 * kDegToRad, 0.0, 90 * kDegToRad, 28.0), 2.307 + 0.1204, 0.001);
}

TEST(Troposphere, BadConfigThrows) {
  TroposphereConfig c;
  c.zhd_a_m = -1.0;
  EXPECT_THROW(Troposphere{c}, Error);
  c = {};
  c.zwd_scale_height_m = 0.0;
  EXPECT_THROW(Troposphere{c}, Error);
  c = {};
  c.rel_humidity = 1.5;
  EXPECT_THROW(Troposphere{c}, Error);
  c = {};
  c.zhd_b_per_m = NAN;
  EXPECT_THROW(Troposphere{c}, Error);
}

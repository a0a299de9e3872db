// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"

using namespace gnssemu;

TEST(Geodesy, EquatorAndPole) {
  const Ecef e = geo::ecef_from_lla({0.0, 0.0, 0.0});
  EXPECT_NEAR(e.x, kWgs84A_m, 1e-6);
  EXPECT_NEAR(e.y, 0.0, 1e-6);
  const Ecef p = geo::ecef_from_lla({kPi / 2, 0.0, 0.0});
  EXPECT_NEAR(p.z, 6356752.314245, 1e-5);  // WGS-84 semi-minor axis
}

TEST(Geodesy, RoundTripHardCases) {
  for (double lat : {-90.0, -45.0, 0.0, 78.93, 90.0}) {
    for (double lon : {-180.0, -0.5, 0.0, 11.87, 179.999, 180.0}) {
      for (double h : {-400.0, 0.0, 12000.0, 20200e3}) {
        const Lla in{lat * kDegToRad, lon * kDegToRad, h};
        const Lla out = geo::lla_from_ecef(geo::ecef_from_lla(in));
        EXPECT_NEAR(out.lat_rad, in.lat_rad, 1e-11) << lat << " " << lon << " " << h;
        EXPECT_NEAR(out.height_m, h, 1e-4);
        if (std::fabs(lat) < 90.0) {
          EXPECT_NEAR(std::remainder(out.lon_rad - in.lon_rad, 2 * kPi), 0.0, 1e-11);
        }
      }
    }
  }
}

TEST(Geodesy, LookAnglesZenithAndHorizon) {
  const Lla rx{45.0 * kDegToRad, 7.0 * kDegToRad, 100.0};
  const Ecef rx_e = geo::ecef_from_lla(rx);
  const Ecef up = geo::ecef_from_lla({rx.lat_rad, rx.lon_rad, 20000e3});
  const auto z = geo::look_angles(rx_e, up);
  EXPECT_NEAR(z.el_rad, kPi / 2, 1e-9);
  EXPECT_NEAR(z.range_m, 20000e3 - 100.0, 1e-3);
  // Due east along the local horizontal.
  const Vec3 east = geo::enu_to_ecef_vector(Enu(1000.0, 0.0, 0.0), rx.lat_rad, rx.lon_rad);
  const auto e = geo::look_angles(rx_e, rx, Ecef(rx_e + east));
  EXPECT_NEAR(e.az_rad, kPi / 2, 1e-12);
  EXPECT_NEAR(e.el_rad, 0.0, 1e-12);
  // los_unit_ecef agrees with look_angles.
  const Vec3 u = geo::los_unit_ecef(1.0, 0.5, rx.lat_rad, rx.lon_rad);
  const auto la = geo::look_angles(rx_e, rx, Ecef(rx_e + u * 1e6));
  EXPECT_NEAR(la.az_rad, 1.0, 1e-12);
  EXPECT_NEAR(la.el_rad, 0.5, 1e-12);
}

// SPDX-License-Identifier: Apache-2.0
#include "core/geo/geodesy.hpp"

#include <GeographicLib/Config.h>
#include <GeographicLib/Geocentric.hpp>
#include <cmath>

#include "core/common/constants.hpp"

namespace gnssemu::geo {

namespace {
const GeographicLib::Geocentric& wgs84() {
  // Function-local static: constructed once, immutable (no global state to reset).
  static const GeographicLib::Geocentric g(kWgs84A_m, kWgs84F);
  return g;
}
}  // namespace

Ecef ecef_from_lla(const Lla& lla) noexcept {
  Ecef e;
  wgs84().Forward(lla.lat_rad * kRadToDeg, lla.lon_rad * kRadToDeg, lla.height_m, e.x, e.y, e.z);
  return e;
}

Lla lla_from_ecef(const Ecef& ecef) noexcept {
  double lat_deg = 0, lon_deg = 0, h = 0;
  wgs84().Reverse(ecef.x, ecef.y, ecef.z, lat_deg, lon_deg, h);
  return {lat_deg * kDegToRad, lon_deg * kDegToRad, h};
}

Enu ecef_to_enu_vector(const Vec3& v, double lat, double lon) noexcept {
  const double sl = std::sin(lat), cl = std::cos(lat), so = std::sin(lon), co = std::cos(lon);
  return Enu(-so * v.x + co * v.y,                          //
             -sl * co * v.x - sl * so * v.y + cl * v.z,     //
             cl * co * v.x + cl * so * v.y + sl * v.z);
}

Vec3 enu_to_ecef_vector(const Enu& v, double lat, double lon) noexcept {
  const double sl = std::sin(lat), cl = std::cos(lat), so = std::sin(lon), co = std::cos(lon);
  return {-so * v.x - sl * co * v.y + cl * co * v.z,  //
          co * v.x - sl * so * v.y + cl * so * v.z,   //
          cl * v.y + sl * v.z};
}

LookAngles look_angles(const Ecef& rx, const Lla& rx_lla, const Ecef& target) noexcept {
  const Vec3 d = target - rx;
  LookAngles la;
  la.range_m = d.norm();
  if (!(la.range_m > 0.0)) return la;
  const Enu enu = ecef_to_enu_vector(d, rx_lla.lat_rad, rx_lla.lon_rad);
  const double horiz = std::hypot(enu.x, enu.y);
  la.el_rad = std::atan2(enu.z, horiz);
  double az = std::atan2(enu.x, enu.y);
  if (az < 0.0) az += 2.0 * kPi;
  if (az >= 2.0 * kPi) az -= 2.0 * kPi;
  la.az_rad = az;
  return la;
}

LookAngles look_angles(const Ecef& rx, const Ecef& target) noexcept {
  return look_angles(rx, lla_from_ecef(rx), target);
}

std::string geographiclib_version() { return GEOGRAPHICLIB_VERSION_STRING; }

Vec3 los_unit_ecef(double az_rad, double el_rad, double lat_rad, double lon_rad) noexcept {
  const double ce = std::cos(el_rad);
  return enu_to_ecef_vector(Enu(ce * std::sin(az_rad), ce * std::cos(az_rad), std::sin(el_rad)), lat_rad, lon_rad);
}

}  // namespace gnssemu::geo

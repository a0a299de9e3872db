// SPDX-License-Identifier: Apache-2.0
#pragma once
// WGS-84 geodetic <-> ECEF conversions and satellite look angles, through
// GeographicLib::Geocentric (the only geodesy implementation in the project).
#include <cmath>
#include <string>

#include "core/common/vec3.hpp"

namespace gnssemu::geo {

/// ECEF position (m) of a geodetic point (lat/lon rad, height above ellipsoid m).
Ecef ecef_from_lla(const Lla& lla) noexcept;
/// Geodetic point of an ECEF position (m). Exact (GeographicLib, Vermeille).
Lla lla_from_ecef(const Ecef& ecef) noexcept;

/// Rotation of an ECEF vector into east/north/up at (lat_rad, lon_rad).
Enu ecef_to_enu_vector(const Vec3& ecef_vec, double lat_rad, double lon_rad) noexcept;
/// Rotation of an ENU vector into ECEF at (lat_rad, lon_rad).
Vec3 enu_to_ecef_vector(const Enu& enu_vec, double lat_rad, double lon_rad) noexcept;
/// The local east, north and up unit vectors (ECEF) at (lat_rad, lon_rad):
/// the rows of the ECEF -> ENU rotation.
struct EnuAxes {
  Vec3 e, n, u;
};
inline EnuAxes enu_axes(double lat_rad, double lon_rad) noexcept {
  const double sl = std::sin(lat_rad), cl = std::cos(lat_rad);
  const double so = std::sin(lon_rad), co = std::cos(lon_rad);
  return {{-so, co, 0.0}, {-sl * co, -sl * so, cl}, {cl * co, cl * so, sl}};
}
/// Local vertical (ellipsoid normal, up) at lla as an ECEF unit vector.
inline Vec3 up_unit_ecef(const Lla& lla) noexcept { return enu_axes(lla.lat_rad, lla.lon_rad).u; }

/// Azimuth (rad, [0, 2pi), clockwise from true north), elevation (rad,
/// [-pi/2, pi/2]) and geometric range (m) from a receiver to a target.
struct LookAngles {
  double az_rad = 0.0;
  double el_rad = 0.0;
  double range_m = 0.0;
};

/// Look angles from a receiver at rx (ECEF m, with its geodetic lat/lon) to target (ECEF m).
LookAngles look_angles(const Ecef& rx, const Lla& rx_lla, const Ecef& target) noexcept;
/// Same, computing the receiver's geodetic position itself.
LookAngles look_angles(const Ecef& rx, const Ecef& target) noexcept;

/// GeographicLib version string, e.g. "2.1.2" (for `gnssemu version`).
std::string geographiclib_version();

/// Line-of-sight unit vector (ECEF) of an azimuth/elevation at (lat_rad, lon_rad).
Vec3 los_unit_ecef(double az_rad, double el_rad, double lat_rad, double lon_rad) noexcept;

}  // namespace gnssemu::geo

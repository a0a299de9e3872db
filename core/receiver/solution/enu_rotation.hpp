// SPDX-License-Identifier: Apache-2.0
#pragma once
// geo::ecef_to_enu_vector() for many vectors at one place: the sines and
// cosines of its latitude and longitude computed once, the rotation with
// the same arithmetic (the same bits).
#include <cmath>

#include "core/common/vec3.hpp"

namespace gnssemu::receiver {

struct EnuRotation {
  double sl, cl, so, co;
  EnuRotation(double lat_rad, double lon_rad) noexcept
      : sl(std::sin(lat_rad)), cl(std::cos(lat_rad)), so(std::sin(lon_rad)), co(std::cos(lon_rad)) {}
  Enu operator()(const Vec3& v) const noexcept {
    return Enu(-so * v.x + co * v.y,                       //
               -sl * co * v.x - sl * so * v.y + cl * v.z,  //
               cl * co * v.x + cl * so * v.y + sl * v.z);
  }
};

}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
#include "core/geo/local_frame.hpp"

#include "core/geo/geodesy.hpp"

namespace gnssemu::geo {

LocalFrame::LocalFrame(const Lla& origin) noexcept : origin_(origin), origin_ecef_(ecef_from_lla(origin)) {}

Enu LocalFrame::to_enu(const Ecef& p) const noexcept { return vector_to_enu(p - origin_ecef_); }

Ecef LocalFrame::to_ecef(const Enu& p) const noexcept { return Ecef(origin_ecef_ + vector_to_ecef(p)); }

Lla LocalFrame::to_lla(const Enu& p) const noexcept { return lla_from_ecef(to_ecef(p)); }

Enu LocalFrame::from_lla(const Lla& lla) const noexcept { return to_enu(ecef_from_lla(lla)); }

Enu LocalFrame::vector_to_enu(const Vec3& v) const noexcept {
  return ecef_to_enu_vector(v, origin_.lat_rad, origin_.lon_rad);
}

Vec3 LocalFrame::vector_to_ecef(const Enu& v) const noexcept {
  return enu_to_ecef_vector(v, origin_.lat_rad, origin_.lon_rad);
}

}  // namespace gnssemu::geo

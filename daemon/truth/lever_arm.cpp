// SPDX-License-Identifier: Apache-2.0
#include "daemon/truth/lever_arm.hpp"

#include <cmath>

#include "core/geo/geodesy.hpp"

namespace gnssemu::daemon {

Vec3 body_to_ned(const Attitude& a, const Vec3& b) noexcept {
  // Tait-Bryan z-y'-x'' (yaw, pitch, roll): R = Rz(yaw) Ry(pitch) Rx(roll).
  const double cr = std::cos(a.roll_rad), sr = std::sin(a.roll_rad);
  const double cp = std::cos(a.pitch_rad), sp = std::sin(a.pitch_rad);
  const double cy = std::cos(a.yaw_rad), sy = std::sin(a.yaw_rad);
  return {cp * cy * b.x + (sr * sp * cy - cr * sy) * b.y + (cr * sp * cy + sr * sy) * b.z,
          cp * sy * b.x + (sr * sp * sy + cr * cy) * b.y + (cr * sp * sy - sr * cy) * b.z,
          -sp * b.x + sr * cp * b.y + cr * cp * b.z};
}

Attitude lever_attitude(const std::optional<Attitude>& att, const world::Truth& vehicle) noexcept {
  if (att) return *att;
  Attitude level;
  const Lla lla = geo::lla_from_ecef(vehicle.pos_m);
  const Enu v = geo::ecef_to_enu_vector(vehicle.vel_m_s, lla.lat_rad, lla.lon_rad);
  if (std::hypot(v.x, v.y) >= kMinHeadingSpeed_m_s) level.yaw_rad = std::atan2(v.x, v.y);
  return level;
}

world::Truth antenna_truth(const world::Truth& vehicle, const Vec3& lever_body_m,
                           const std::optional<Attitude>& att) noexcept {
  if (!vehicle.valid || lever_body_m == Vec3{}) return vehicle;
  const Vec3 ned = body_to_ned(lever_attitude(att, vehicle), lever_body_m);
  const Lla lla = geo::lla_from_ecef(vehicle.pos_m);
  const geo::EnuAxes ax = geo::enu_axes(lla.lat_rad, lla.lon_rad);
  world::Truth out = vehicle;
  out.pos_m = Ecef(vehicle.pos_m + ax.n * ned.x + ax.e * ned.y - ax.u * ned.z);
  return out;
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#pragma once
// LocalFrame: the simulator's level frame — east/north/up metres from a
// configured geodetic origin (the "game-level" frame of CARLA, Unreal, Gazebo).
#include "core/common/vec3.hpp"

namespace gnssemu::geo {

class LocalFrame {
public:
  /// origin: geodetic origin (lat/lon rad, ellipsoidal height m).
  explicit LocalFrame(const Lla& origin) noexcept;

  const Lla& origin() const noexcept { return origin_; }
  const Ecef& origin_ecef() const noexcept { return origin_ecef_; }

  /// ENU position (m) of an ECEF position (m). Exact (no flat-Earth approximation).
  Enu to_enu(const Ecef& p) const noexcept;
  /// ECEF position (m) of an ENU position (m).
  Ecef to_ecef(const Enu& p) const noexcept;
  /// Geodetic point of an ENU position.
  Lla to_lla(const Enu& p) const noexcept;
  /// ENU position of a geodetic point.
  Enu from_lla(const Lla& lla) const noexcept;
  /// Rotate a vector (e.g. velocity m/s) between frames at the origin.
  Enu vector_to_enu(const Vec3& ecef_vec) const noexcept;
  Vec3 vector_to_ecef(const Enu& enu_vec) const noexcept;

private:
  Lla origin_;
  Ecef origin_ecef_;
};

}  // namespace gnssemu::geo

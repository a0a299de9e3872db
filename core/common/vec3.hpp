// SPDX-License-Identifier: Apache-2.0
#pragma once
// Small 3-vector and frame-tagged positions. Frames are distinct types so an
// ENU vector cannot be passed where an ECEF one is expected.
#include <cmath>

namespace gnssemu {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;

  constexpr Vec3() = default;
  constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  constexpr bool operator==(const Vec3&) const = default;

  constexpr double dot(const Vec3& o) const { return x * o.x + y * o.y + z * o.z; }
  constexpr Vec3 cross(const Vec3& o) const {
    return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x};
  }
  double norm() const { return std::sqrt(dot(*this)); }
  bool finite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
};

constexpr Vec3 operator*(double s, const Vec3& v) { return v * s; }

/// A Vec3 tagged with its frame. Arithmetic falls back to Vec3 (explicit re-tag).
template <class Tag>
struct FrameVec : Vec3 {
  constexpr FrameVec() = default;
  constexpr FrameVec(double x_, double y_, double z_) : Vec3(x_, y_, z_) {}
  constexpr explicit FrameVec(const Vec3& v) : Vec3(v) {}
};

struct EcefTag {};
struct EnuTag {};

/// Earth-centred, Earth-fixed (WGS-84) coordinates, metres (or m/s for velocities).
using Ecef = FrameVec<EcefTag>;
/// Local east/north/up coordinates, metres (or m/s), relative to a LocalFrame origin.
using Enu = FrameVec<EnuTag>;

/// Geodetic WGS-84 position. lat_rad in [-pi/2, pi/2], lon_rad in (-pi, pi],
/// height_m above the ellipsoid.
struct Lla {
  double lat_rad = 0.0;
  double lon_rad = 0.0;
  double height_m = 0.0;
};

}  // namespace gnssemu

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Small meshes built in code for the scene tests.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/common/constants.hpp"
#include "core/scene/mesh.hpp"

namespace gnssemu::scene::test {

/// Axis-aligned rectangle (two triangles) through four corners in order.
inline void add_quad(MeshBuilder& b, const Vec3& a, const Vec3& c1, const Vec3& c2, const Vec3& c3) {
  const uint32_t v0 = b.vertex_count();
  for (const Vec3& p : {a, c1, c2, c3}) b.add_vertex(p.x, p.y, p.z);
  const uint32_t q[4] = {v0, v0 + 1, v0 + 2, v0 + 3};
  b.add_face(q, 4, 0);
}

/// Vertical wall in the plane y = y_m, x in [x0, x1], z in [z0, z1].
inline void add_wall_y(MeshBuilder& b, double y_m, double x0, double x1, double z0, double z1) {
  add_quad(b, {x0, y_m, z0}, {x1, y_m, z0}, {x1, y_m, z1}, {x0, y_m, z1});
}

/// Closed box [x0,x1] x [y0,y1] x [z0,z1] (12 triangles, shared edges).
inline void add_box(MeshBuilder& b, const Vec3& lo, const Vec3& hi) {
  const uint32_t v0 = b.vertex_count();
  for (int i = 0; i < 8; ++i) {
    b.add_vertex((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
  }
  const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    const uint32_t q[4] = {v0 + f[0], v0 + f[1], v0 + f[2], v0 + f[3]};
    b.add_face(q, 4, 0);
  }
}

/// Unit ENU vector towards azimuth az_deg (from north, clockwise) and elevation el_deg.
inline Enu direction(double az_deg, double el_deg) {
  const double az = az_deg * kDegToRad, el = el_deg * kDegToRad;
  return Enu(std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el));
}

/// A fresh temporary file with the given content (binary-safe).
inline std::string temp_file(const std::string& name, const std::string& content) {
  const auto dir = std::filesystem::temp_directory_path() / "gnssemu_scene_test";
  std::filesystem::create_directories(dir);
  const auto p = dir / name;
  std::ofstream(p, std::ios::binary | std::ios::trunc) << content;
  return p.string();
}

}  // namespace gnssemu::scene::test

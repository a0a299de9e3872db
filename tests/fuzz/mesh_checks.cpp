// SPDX-License-Identifier: Apache-2.0
#include "mesh_checks.hpp"

#include <cmath>

#include "core/common/error.hpp"
#include "fuzz_support.hpp"

namespace gnssemu::fuzz {

scene::Mesh load_scene_mesh(const std::string& path, const scene::Placement& placement) {
  return scene::load_mesh(path, placement);
}

void load_and_check_mesh(const std::string& path, MeshLoader load) {
  scene::Mesh m;
  try {
    m = load(path, scene::Placement{});
  } catch (const Error& e) {
    expect_names_file(e, path);
    return;
  }
  expect(!m.triangles.empty(), "a mesh without triangles is an error");
  for (const Vec3& v : m.vertices_m) {
    expect(v.finite(), "vertex finite");
    expect(std::abs(v.x) <= scene::MeshBuilder::kMaxCoordinate_m && std::abs(v.y) <= scene::MeshBuilder::kMaxCoordinate_m &&
               std::abs(v.z) <= scene::MeshBuilder::kMaxCoordinate_m,
           "vertex within kMaxCoordinate_m");
  }
  expect(m.material.size() == m.triangles.size(), "one material per triangle");
  expect(!m.material_names.empty() && m.material_names[0].empty(), "material 0 is none");
  for (const auto& t : m.triangles) {
    for (const uint32_t i : t) expect(i < m.vertices_m.size(), "triangle indexes an existing vertex");
    expect(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "triangle has three distinct vertices");
  }
  for (const uint16_t k : m.material) expect(k < m.material_names.size(), "material index in range");
  expect(m.stats.triangles == static_cast<int>(m.triangles.size()), "stats count the triangles kept");
  expect(m.stats.skipped() == 0 || !m.stats.first_problem.empty(), "a skipped element is reported");
}

}  // namespace gnssemu::fuzz

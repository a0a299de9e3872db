// SPDX-License-Identifier: Apache-2.0
#include "core/scene/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/common/error.hpp"

namespace gnssemu::scene {

namespace {

// Twice the area relative to the squared edge lengths below which a triangle
// counts as degenerate (collinear within float32 resolution).
constexpr double kMinRelativeArea = 1e-9;

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

std::string skip_report(const MeshStats& s) {
  if (s.skipped() == 0) return {};
  return "mesh: " + std::to_string(s.skipped()) + " bad elements skipped (" + std::to_string(s.skipped_bad_index) +
         " bad index, " + std::to_string(s.skipped_nonfinite) + " NaN/inf, " + std::to_string(s.skipped_degenerate) +
         " degenerate); first: " + s.first_problem;
}

MeshBuilder::MeshBuilder(std::string file, const Placement& placement)
    : file_(std::move(file)),
      placement_(placement),
      cos_yaw_(std::cos(placement.yaw_rad)),
      sin_yaw_(std::sin(placement.yaw_rad)) {
  mesh_.material_names.emplace_back();
}

void MeshBuilder::add_vertex(double x, double y, double z, int line) {
  const bool ok = std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
  if (placement_.y_up) {
    const double y_model = y;
    y = -z;
    z = y_model;
  }
  x *= placement_.scale;
  y *= placement_.scale;
  z *= placement_.scale;
  const Vec3 p(cos_yaw_ * x - sin_yaw_ * y + placement_.offset_m.x, sin_yaw_ * x + cos_yaw_ * y + placement_.offset_m.y,
               z + placement_.offset_m.z);
  if (ok && p.finite() &&
      (std::fabs(p.x) > kMaxCoordinate_m || std::fabs(p.y) > kMaxCoordinate_m || std::fabs(p.z) > kMaxCoordinate_m)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "vertex at (%.6g, %.6g, %.6g) m after placement is beyond 1e6 m of the origin", p.x,
                  p.y, p.z);
    throw Error(file_, line,
                std::string(buf) + " (Embree stores float32); model the scene in a local frame near [origin]");
  }
  vertices_.push_back(ok ? p : Vec3());
  finite_.push_back(ok && p.finite());
}

void MeshBuilder::set_material(const std::string& name) {
  auto& names = mesh_.material_names;
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) {
    current_material_ = static_cast<uint16_t>(it - names.begin());
    return;
  }
  if (names.size() >= 65535) throw Error(file_, 0, "more than 65534 materials");
  names.push_back(name);
  current_material_ = static_cast<uint16_t>(names.size() - 1);
}

void MeshBuilder::skip(int& counter, int line, const std::string& why) {
  ++counter;
  if (mesh_.stats.first_problem.empty()) mesh_.stats.first_problem = file_ + ":" + std::to_string(line) + ": " + why;
}

void MeshBuilder::add_face(const uint32_t* idx, int n, int line) {
  ++mesh_.stats.faces_read;
  for (int k = 1; k + 1 < n; ++k) {
    const std::array<uint32_t, 3> tri{idx[0], idx[k], idx[k + 1]};
    bool bad = false, nonfinite = false;
    for (const uint32_t i : tri) {
      if (i >= vertices_.size()) {
        bad = true;
      } else if (!finite_[i]) {
        nonfinite = true;
      }
    }
    if (bad) {
      skip(mesh_.stats.skipped_bad_index, line, "face refers to a vertex that does not exist; triangle skipped");
      continue;
    }
    if (nonfinite) {
      skip(mesh_.stats.skipped_nonfinite, line, "face uses a NaN/inf vertex; triangle skipped");
      continue;
    }
    const Vec3 e1 = vertices_[tri[1]] - vertices_[tri[0]];
    const Vec3 e2 = vertices_[tri[2]] - vertices_[tri[0]];
    const double area2 = e1.cross(e2).norm();
    if (!(area2 > kMinRelativeArea * (e1.dot(e1) + e2.dot(e2)))) {
      skip(mesh_.stats.skipped_degenerate, line, "degenerate triangle (zero area); skipped");
      continue;
    }
    mesh_.triangles.push_back(tri);
    mesh_.material.push_back(current_material_);
  }
  if (n < 3) skip(mesh_.stats.skipped_degenerate, line, "face with fewer than 3 vertices; skipped");
}

void MeshBuilder::add_face_checked(const int64_t* idx, int n, int line) {
  constexpr int kMaxPolygon = 256;
  std::array<uint32_t, kMaxPolygon> u{};
  if (n > kMaxPolygon) throw Error(file_, line, "polygon with more than 256 vertices");
  for (int i = 0; i < n; ++i) {
    u[static_cast<std::size_t>(i)] =
        idx[i] < 0 || idx[i] >= static_cast<int64_t>(vertices_.size()) ? UINT32_MAX : static_cast<uint32_t>(idx[i]);
  }
  add_face(u.data(), n, line);
}

Mesh MeshBuilder::finish() && {
  // Keep only vertices (finite ones stay; non-finite are zeroed and unused).
  mesh_.vertices_m = std::move(vertices_);
  mesh_.stats.triangles = static_cast<int>(mesh_.triangles.size());
  return std::move(mesh_);
}

Mesh load_mesh(const std::string& path, const Placement& placement, FootprintReader read_footprints) {
  if (!(placement.scale > 0.0) || !std::isfinite(placement.scale)) throw Error(path, 0, "placement scale must be > 0");
  if (!placement.offset_m.finite() || !std::isfinite(placement.yaw_rad)) {
    throw Error(path, 0, "placement offset and yaw must be finite");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path, 0, "mesh file not found");
  const std::string ext = lower_extension(path);
  Mesh m;
  if (ext == ".obj") {
    m = read_obj(path, placement);
  } else if (ext == ".ply") {
    m = read_ply(path, placement);
  } else if (ext == ".toml") {
    if (read_footprints == nullptr) throw Error(path, 0, "footprint files (.toml) need a footprint reader");
    m = read_footprints(path, placement);
  } else {
    throw Error(path, 0, "unknown mesh format '" + ext + "' (expected .obj, .ply or .toml footprints)");
  }
  if (m.triangles.empty()) {
    throw Error(path, 0,
                "no triangles in this mesh (" + std::to_string(m.vertices_m.size()) + " vertices, " +
                    std::to_string(m.stats.faces_read) + " faces read" +
                    (m.stats.skipped() > 0 ? ", " + std::to_string(m.stats.skipped()) +
                                                 " skipped; first: " + m.stats.first_problem
                                           : "") +
                    "): not a " + (ext == ".toml" ? "footprint file" : ext == ".ply" ? "PLY mesh" : "Wavefront OBJ mesh") +
                    ", or nothing usable in it");
  }
  return m;
}

}  // namespace gnssemu::scene

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Triangle mesh in the local ENU frame of the configured origin, and the
// readers that produce it (Wavefront OBJ, PLY ascii/binary; building
// footprints are extruded by footprints.hpp from a file read above core).
// Bad input: a gnssemu::Error naming file:line, or the element skipped and
// counted in MeshStats (never a crash, never a NaN vertex in the mesh).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/common/range.hpp"
#include "core/common/vec3.hpp"

namespace gnssemu::scene {

/// What the reader dropped. A skipped triangle never reaches the scene.
struct MeshStats {
  int faces_read = 0;            ///< faces (polygons) in the file
  int triangles = 0;             ///< triangles kept
  int skipped_bad_index = 0;     ///< triangles referring to a missing vertex
  int skipped_nonfinite = 0;     ///< triangles using a NaN/inf vertex
  int skipped_degenerate = 0;    ///< triangles of zero area (repeated or collinear vertices)
  std::string first_problem;     ///< "file:line: reason" of the first skipped element, or ""
  int skipped() const noexcept { return skipped_bad_index + skipped_nonfinite + skipped_degenerate; }
};

/// One line for users: "mesh: N bad elements skipped (a bad index, b
/// NaN/inf, c degenerate); first: file:line: reason", or "" when nothing was skipped.
std::string skip_report(const MeshStats& s);

/// Model-to-ENU placement: p_enu = offset_m + Rz(yaw_rad) * (scale * axes(p_model)).
struct Placement {
  Enu offset_m;            ///< model origin in local ENU, m
  double yaw_rad = 0.0;    ///< rotation about up, counter-clockwise seen from above (east towards north), rad
  double scale = 1.0;      ///< model units to metres (> 0)
  bool y_up = false;       ///< model is Y-up (Blender/glTF export): (x, y, z) -> (x, -z, y) before yaw
};

struct Mesh {
  std::vector<Vec3> vertices_m;                  ///< local ENU, m
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<uint16_t> material;                ///< per triangle, index into material_names
  std::vector<std::string> material_names;       ///< [0] is "" (no material given)
  MeshStats stats;
};

/// Incremental builder used by the readers: checks indices, finiteness and
/// area after placement, and counts what it skips.
class MeshBuilder {
public:
  /// Largest |e|, |n|, |u| of a placed vertex, m: Embree stores float32, whose
  /// resolution at 1000 km is 6 cm (and 0.5 m at ECEF magnitudes).
  static constexpr double kMaxCoordinate_m = 1.0e6;

  MeshBuilder(std::string file, const Placement& placement);

  /// Adds a model-frame vertex; a non-finite one is kept as a marker so
  /// faces using it are skipped (not an error). Throws gnssemu::Error
  /// (file:line) when the placed vertex is farther than kMaxCoordinate_m
  /// from the origin in any axis. line: source line for messages.
  void add_vertex(double x, double y, double z, int line = 0);
  uint32_t vertex_count() const noexcept { return static_cast<uint32_t>(vertices_.size()); }
  /// Sets the material of the faces that follow; "" = none.
  void set_material(const std::string& name);
  /// Adds a polygon (fan-triangulated) of 0-based indices; line for messages.
  void add_face(const uint32_t* idx, int n, int line);
  /// Adds a polygon by indices that may be out of range (counted as bad).
  void add_face_checked(const int64_t* idx, int n, int line);

  Mesh finish() &&;

private:
  void skip(int& counter, int line, const std::string& why);

  std::string file_;
  Placement placement_;
  double cos_yaw_, sin_yaw_;
  std::vector<Vec3> vertices_;
  std::vector<bool> finite_;
  Mesh mesh_;
  uint16_t current_material_ = 0;
};

/// Valid values of Placement's fields as a configuration gives them (yaw in
/// degrees; each offset component within MeshBuilder::kMaxCoordinate_m).
/// load_mesh itself requires a finite placement with scale > 0.
struct PlacementRanges {
  static constexpr Range yaw_deg{-360.0, 360.0, "deg"};
  static constexpr Range scale{0.0, 1.0e6, "", true};
  static constexpr Range offset_m{-MeshBuilder::kMaxCoordinate_m, MeshBuilder::kMaxCoordinate_m, "m"};
};

/// Reads a building footprint file (.toml, docs/scene.md) placed by
/// placement. Its text format is parsed above core (config::read_footprints);
/// the geometry is FootprintBuilder's.
using FootprintReader = Mesh (*)(const std::string& path, const Placement& placement);

/// Reads a mesh by extension: .obj, .ply, and .toml footprints through
/// read_footprints (without one, a .toml file is an error). Throws
/// gnssemu::Error (file:line: reason) on a missing file, unreadable syntax,
/// or a file that gives no triangle at all (e.g. not a mesh).
Mesh load_mesh(const std::string& path, const Placement& placement = {}, FootprintReader read_footprints = nullptr);

/// Wavefront OBJ: v, f (v, v/t, v//n, v/t/n, negative = relative), usemtl;
/// other statements ignored. Polygons are fan-triangulated.
Mesh read_obj(const std::string& path, const Placement& placement = {});

/// PLY 1.0 (ascii, binary_little_endian, binary_big_endian): element vertex
/// with x, y, z, element face with a list of vertex indices; other elements
/// and properties skipped.
Mesh read_ply(const std::string& path, const Placement& placement = {});

}  // namespace gnssemu::scene

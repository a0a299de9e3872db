// SPDX-License-Identifier: Apache-2.0
#pragma once
// Scene: the building mesh in an Embree BVH (float32, local ENU of the
// configured origin). Immutable after construction; queries are const,
// noexcept, allocation-free and safe from several threads. No Embree types
// leak out of this header.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/common/range.hpp"
#include "core/common/vec3.hpp"
#include "core/scene/mesh.hpp"

namespace gnssemu::scene {

/// One ray: origin (ENU m), unit direction, and the search interval (m).
struct Ray {
  Vec3 org_m;
  Vec3 dir;
  double tnear_m = 0.0;
  double tfar_m = 1.0e30;
};

/// Nearest hit of a ray. prim < 0: no hit.
struct Hit {
  int32_t prim = -1;     ///< triangle index in the mesh
  double t_m = 0.0;      ///< distance along the ray, m
};

class Scene {
public:
  /// Builds the BVH of mesh (robust/watertight triangle tests).
  /// Throws gnssemu::Error if Embree cannot be initialised.
  explicit Scene(const Mesh& mesh);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  std::size_t triangle_count() const noexcept { return normals_.size(); }
  /// True if every triangle is vertical or horizontal (extruded footprints,
  /// OSM cities): reflections then keep |sin(elevation)| of a ray, which
  /// the propagator exploits (docs/scene.md).
  bool vertical_horizontal() const noexcept { return vertical_horizontal_; }
  bool empty() const noexcept { return normals_.empty(); }

  /// True if anything lies on the ray within [tnear, tfar].
  bool occluded(const Ray& r) const noexcept;
  /// Nearest hit within [tnear, tfar].
  Hit intersect(const Ray& r) const noexcept;
  /// Batched queries (Embree ray streams, coherent flag): hits[i] for rays[i].
  void intersect(std::span<const Ray> rays, std::span<Hit> hits) const noexcept;

  /// Unit geometric normal of triangle prim (right-hand winding), ENU.
  const Vec3& normal(int32_t prim) const noexcept { return normals_[static_cast<std::size_t>(prim)]; }
  /// Plane offset of triangle prim: normal . p = offset for p on the plane, m.
  double plane_offset_m(int32_t prim) const noexcept { return offsets_[static_cast<std::size_t>(prim)]; }
  /// Power loss of one reflection on triangle prim, dB.
  double reflection_loss_db(int32_t prim) const noexcept {
    return loss_db_[material_[static_cast<std::size_t>(prim)]];
  }
  /// Material names (index 0 = none) and their loss per reflection (dB).
  const std::vector<std::string>& material_names() const noexcept { return material_names_; }
  /// Sets the loss of one reflection for a material (dB >= 0); unknown names are ignored.
  /// Setup only (not thread-safe with queries). Returns false if the name is not in the mesh.
  bool set_material_loss_db(const std::string& name, double loss_db);
  /// Sets the loss for every material (default 3 dB: half the power per bounce).
  void set_default_loss_db(double loss_db);

  /// Axis-aligned bounds of the mesh, ENU m (zero when empty).
  const Vec3& bounds_min_m() const noexcept { return lo_; }
  const Vec3& bounds_max_m() const noexcept { return hi_; }

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<Vec3> normals_;
  std::vector<double> offsets_;
  std::vector<uint16_t> material_;
  std::vector<std::string> material_names_;
  std::vector<double> loss_db_;
  Vec3 lo_, hi_;
  bool vertical_horizontal_ = true;
};

/// Valid loss of one reflection as a configuration gives it.
struct SceneRanges {
  static constexpr Range reflection_loss_db{0.0, 100.0, "dB"};
};

}  // namespace gnssemu::scene

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Building footprints extruded into a closed mesh (docs/scene.md): the
// geometry of the footprint format. Its text (TOML) is parsed above core
// (config/footprint_file), which calls these in file order, so each problem
// is reported where the file has it.
#include <string>
#include <vector>

#include "core/scene/mesh.hpp"

namespace gnssemu::scene {

/// One corner of a footprint in the model frame, m.
struct FootprintPoint {
  double e_m = 0.0;
  double n_m = 0.0;
};

/// Adds ground planes and buildings to a mesh. Errors: gnssemu::Error
/// naming the footprint file and line.
class FootprintBuilder {
public:
  /// file: the footprint file, for messages; placement: model -> local ENU.
  FootprintBuilder(std::string file, const Placement& placement);

  /// Square ground plane of half side half_size_m (m, > 0) at height_m (m),
  /// one quad; line: its table's line.
  void add_ground(double half_size_m, double height_m, const std::string& material, int line);

  /// The outline of a footprint: repeated points (consecutive, or closing
  /// the ring) dropped, then at least 3 distinct points, simple and of
  /// non-zero area, returned counter-clockwise. Throws
  /// "where.footprint: reason" at footprint_line.
  std::vector<FootprintPoint> outline(std::vector<FootprintPoint> points, int footprint_line,
                                      const std::string& where) const;

  /// Walls, roof (ear clipping) and floor of a counter-clockwise outline
  /// from base_m to base_m + height_m (m, height_m > 0). Vertices carry
  /// footprint_line, faces line (the building's table).
  void add_building(const std::vector<FootprintPoint>& outline, double base_m, double height_m,
                    const std::string& material, int footprint_line, int line, const std::string& where);

  Mesh finish() &&;

private:
  std::string file_;
  MeshBuilder builder_;
};

}  // namespace gnssemu::scene

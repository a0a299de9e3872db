// SPDX-License-Identifier: Apache-2.0
#pragma once
// Building footprint files (TOML, docs/scene.md): the text format of the
// footprints core/scene extrudes, and the mesh loader that knows every mesh
// format (OBJ, PLY, footprints).
#include <string>

#include "core/scene/mesh.hpp"

namespace gnssemu::config {

/// Extruded buildings of a footprint file, placed by placement:
///   [[building]] footprint = [[e, n], ...] (m, >= 3 points), height_m, base_m (0), material ("")
///   [ground] half_size_m, height_m (0), material ("")  -- optional square ground plane
/// Each building is closed (walls, roof, floor). Throws gnssemu::Error
/// naming path:line.
scene::Mesh read_footprints(const std::string& path, const scene::Placement& placement = {});

/// scene::load_mesh with footprint files: .obj, .ply or .toml by extension.
scene::Mesh load_mesh(const std::string& path, const scene::Placement& placement = {});

}  // namespace gnssemu::config

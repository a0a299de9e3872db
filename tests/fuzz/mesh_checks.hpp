// SPDX-License-Identifier: Apache-2.0
#pragma once
// The promises of every mesh reader (core/scene/mesh.hpp), for the OBJ, PLY
// and footprint fuzz targets.
#include <string>

#include "core/scene/mesh.hpp"

namespace gnssemu::fuzz {

/// A mesh reader by extension: scene::load_mesh (OBJ, PLY) or
/// config::load_mesh (footprint files too).
using MeshLoader = scene::Mesh (*)(const std::string& path, const scene::Placement& placement);

/// scene::load_mesh without a footprint reader, as a MeshLoader.
scene::Mesh load_scene_mesh(const std::string& path, const scene::Placement& placement);

/// Read path with load. Oracles:
/// errors are gnssemu::Error naming the file; a mesh has finite vertices
/// within MeshBuilder::kMaxCoordinate_m, triangles that index existing
/// vertices, one material per triangle, and stats that agree with it.
void load_and_check_mesh(const std::string& path, MeshLoader load);

}  // namespace gnssemu::fuzz

#pragma once
// The promises of every mesh reader (core/scene/mesh.hpp), for the OBJ, PLY
// and footprint fuzz targets.
#include <string>

#include "core/scene/mesh.hpp"

namespace gnssemu::fuzz {

/// Read path (a .obj, .ply or .toml file) with scene::load_mesh. Oracles:
/// errors are gnssemu::Error naming the file; a mesh has finite vertices
/// within MeshBuilder::kMaxCoordinate_m, triangles that index existing
/// vertices, one material per triangle, and stats that agree with it.
void load_and_check_mesh(const std::string& path);

}  // namespace gnssemu::fuzz

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Procedural city for benchmarks: a Manhattan grid of blocks, each split into
// 2 x 2 buildings of deterministic pseudo-random heights, with facades
// tessellated per floor and bay as real city meshes are. Streets run along
// x = k * pitch and y = k * pitch (k integer), so a receiver on a street
// centreline is outdoors.
#include <cstdint>

#include "core/scene/mesh.hpp"

namespace gnssemu::scene {

struct CityConfig {
  int blocks = 10;              ///< blocks per side (the city is blocks x blocks)
  double block_m = 80.0;        ///< block side, m
  double street_m = 20.0;       ///< street width, m (pitch = block_m + street_m)
  double min_height_m = 8.0;    ///< building heights uniform in [min, max], m
  double max_height_m = 60.0;
  double floor_m = 3.0;         ///< facade tessellation: storey height, m
  double bay_m = 8.0;           ///< facade tessellation: bay width, m
  bool ground = true;           ///< add a ground plane at z = 0
  uint64_t seed = 1;
};

/// The city mesh, centred on the ENU origin (materials "concrete", "glass").
Mesh make_city(const CityConfig& c);

}  // namespace gnssemu::scene

// SPDX-License-Identifier: Apache-2.0
#include "core/scene/procedural_city.hpp"

#include <algorithm>
#include <cmath>

namespace gnssemu::scene {

namespace {

uint64_t splitmix64(uint64_t& s) {
  uint64_t z = (s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double uniform(uint64_t& s) { return static_cast<double>(splitmix64(s) >> 11) * 0x1.0p-53; }

// One facade from (x0, y0) to (x1, y1), z in [0, h], tessellated into bays x floors.
void facade(MeshBuilder& b, double x0, double y0, double x1, double y1, double h, const CityConfig& c) {
  const double len = std::hypot(x1 - x0, y1 - y0);
  const int bays = std::max(1, static_cast<int>(std::ceil(len / c.bay_m)));
  const int floors = std::max(1, static_cast<int>(std::ceil(h / c.floor_m)));
  const uint32_t v0 = b.vertex_count();
  for (int j = 0; j <= floors; ++j) {
    const double z = h * j / floors;
    for (int i = 0; i <= bays; ++i) {
      const double f = static_cast<double>(i) / bays;
      b.add_vertex(x0 + f * (x1 - x0), y0 + f * (y1 - y0), z);
    }
  }
  const auto row = static_cast<uint32_t>(bays + 1);
  for (int j = 0; j < floors; ++j) {
    for (int i = 0; i < bays; ++i) {
      const uint32_t a = v0 + static_cast<uint32_t>(j) * row + static_cast<uint32_t>(i);
      const uint32_t q[4] = {a, a + 1, a + 1 + row, a + row};
      b.add_face(q, 4, 0);
    }
  }
}

void building(MeshBuilder& b, double x0, double y0, double x1, double y1, double h, const CityConfig& c) {
  facade(b, x0, y0, x1, y0, h, c);
  facade(b, x1, y0, x1, y1, h, c);
  facade(b, x1, y1, x0, y1, h, c);
  facade(b, x0, y1, x0, y0, h, c);
  const uint32_t v = b.vertex_count();
  b.add_vertex(x0, y0, h);
  b.add_vertex(x1, y0, h);
  b.add_vertex(x1, y1, h);
  b.add_vertex(x0, y1, h);
  const uint32_t roof[4] = {v, v + 1, v + 2, v + 3};
  b.add_face(roof, 4, 0);
}

}  // namespace

Mesh make_city(const CityConfig& c) {
  MeshBuilder b("procedural city", {});
  uint64_t rng = c.seed;
  const double pitch = c.block_m + c.street_m;
  const double half = 0.5 * c.blocks * pitch;
  if (c.ground) {
    b.set_material("concrete");
    const double g = half + pitch;
    const uint32_t v = b.vertex_count();
    b.add_vertex(-g, -g, 0.0);
    b.add_vertex(g, -g, 0.0);
    b.add_vertex(g, g, 0.0);
    b.add_vertex(-g, g, 0.0);
    const uint32_t q[4] = {v, v + 1, v + 2, v + 3};
    b.add_face(q, 4, 0);
  }
  const double gap = 2.0;  // passage between the buildings of a block, m
  const double part = 0.5 * (c.block_m - gap);
  for (int by = 0; by < c.blocks; ++by) {
    for (int bx = 0; bx < c.blocks; ++bx) {
      const double ox = -half + bx * pitch + 0.5 * c.street_m;
      const double oy = -half + by * pitch + 0.5 * c.street_m;
      for (int k = 0; k < 4; ++k) {
        const double x0 = ox + (k & 1) * (part + gap), y0 = oy + (k >> 1) * (part + gap);
        const double h = c.min_height_m + (c.max_height_m - c.min_height_m) * uniform(rng);
        b.set_material(uniform(rng) < 0.3 ? "glass" : "concrete");
        building(b, x0, y0, x0 + part, y0 + part, h, c);
      }
    }
  }
  return std::move(b).finish();
}

}  // namespace gnssemu::scene

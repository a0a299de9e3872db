// SPDX-License-Identifier: Apache-2.0
// Extruded building footprints: a canyon sketched without a modeller.
#include "core/scene/footprints.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/common/error.hpp"

namespace gnssemu::scene {

namespace {

using P2 = FootprintPoint;

double signed_area(const std::vector<P2>& p) {
  double a = 0.0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += p[j].e_m * p[i].n_m - p[i].e_m * p[j].n_m;
  return 0.5 * a;
}

double cross(const P2& a, const P2& b, const P2& c) {
  return (b.e_m - a.e_m) * (c.n_m - a.n_m) - (b.n_m - a.n_m) * (c.e_m - a.e_m);
}

bool inside(const P2& p, const P2& a, const P2& b, const P2& c) {
  return cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0;
}

bool segments_cross(const P2& a, const P2& b, const P2& c, const P2& d) {
  const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
  return ((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0)) && d1 != 0.0 && d2 != 0.0 && d3 != 0.0 &&
         d4 != 0.0;
}

bool simple(const std::vector<P2>& p) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segments_cross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return false;
    }
  }
  return true;
}

// Ear clipping of a counter-clockwise simple polygon; indices into poly.
// Returns false if the polygon is not simple enough to clip.
bool triangulate(const std::vector<P2>& poly, std::vector<std::array<uint32_t, 3>>& out) {
  std::vector<uint32_t> v(poly.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<uint32_t>(i);
  std::size_t guard = 0;
  while (v.size() > 3) {
    if (++guard > 4 * poly.size() * poly.size()) return false;
    bool clipped = false;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const uint32_t a = v[(i + v.size() - 1) % v.size()], b = v[i], c = v[(i + 1) % v.size()];
      if (cross(poly[a], poly[b], poly[c]) <= 0.0) continue;  // reflex or flat
      bool ear = true;
      for (const uint32_t k : v) {
        if (k != a && k != b && k != c && inside(poly[k], poly[a], poly[b], poly[c])) {
          ear = false;
          break;
        }
      }
      if (!ear) continue;
      out.push_back({a, b, c});
      v.erase(v.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
      break;
    }
    if (!clipped) return false;
  }
  out.push_back({v[0], v[1], v[2]});
  return true;
}

}  // namespace

FootprintBuilder::FootprintBuilder(std::string file, const Placement& placement)
    : file_(std::move(file)), builder_(file_, placement) {}

void FootprintBuilder::add_ground(double half_size_m, double height_m, const std::string& material, int line) {
  const double h = half_size_m;
  const double z = height_m;
  builder_.set_material(material);
  const uint32_t v0 = builder_.vertex_count();
  builder_.add_vertex(-h, -h, z, line);
  builder_.add_vertex(h, -h, z, line);
  builder_.add_vertex(h, h, z, line);
  builder_.add_vertex(-h, h, z, line);
  const uint32_t quad[4] = {v0, v0 + 1, v0 + 2, v0 + 3};
  builder_.add_face(quad, 4, line);
}

std::vector<FootprintPoint> FootprintBuilder::outline(std::vector<FootprintPoint> poly, int footprint_line,
                                                      const std::string& where) const {
  // A repeated point (consecutive, or the closing one) adds no edge: drop it
  // rather than call the polygon self-intersecting.
  const auto same = [](const P2& a, const P2& c) { return a.e_m == c.e_m && a.n_m == c.n_m; };
  poly.erase(std::unique(poly.begin(), poly.end(), same), poly.end());
  if (poly.size() > 1 && same(poly.front(), poly.back())) poly.pop_back();
  if (poly.size() < 3) throw Error(file_, footprint_line, where + ".footprint: needs at least 3 distinct points");
  const double area = signed_area(poly);
  if (!simple(poly)) throw Error(file_, footprint_line, where + ".footprint: self-intersecting polygon");
  if (!(std::fabs(area) > 1e-6)) throw Error(file_, footprint_line, where + ".footprint: zero area");
  if (area < 0.0) std::reverse(poly.begin(), poly.end());
  return poly;
}

void FootprintBuilder::add_building(const std::vector<FootprintPoint>& poly, double base_m, double height_m,
                                    const std::string& material, int footprint_line, int line,
                                    const std::string& where) {
  builder_.set_material(material);
  std::vector<std::array<uint32_t, 3>> tris;
  if (!triangulate(poly, tris)) throw Error(file_, footprint_line, where + ".footprint: self-intersecting polygon");
  const uint32_t v0 = builder_.vertex_count();
  const auto m = static_cast<uint32_t>(poly.size());
  for (const P2& p : poly) builder_.add_vertex(p.e_m, p.n_m, base_m, footprint_line);
  for (const P2& p : poly) builder_.add_vertex(p.e_m, p.n_m, base_m + height_m, footprint_line);
  for (uint32_t i = 0; i < m; ++i) {
    const uint32_t j = (i + 1) % m;
    const uint32_t quad[4] = {v0 + i, v0 + j, v0 + m + j, v0 + m + i};  // outward for CCW footprints
    builder_.add_face(quad, 4, line);
  }
  for (const auto& tr : tris) {
    const uint32_t roof[3] = {v0 + m + tr[0], v0 + m + tr[1], v0 + m + tr[2]};
    const uint32_t floor[3] = {v0 + tr[0], v0 + tr[2], v0 + tr[1]};
    builder_.add_face(roof, 3, line);
    builder_.add_face(floor, 3, line);
  }
}

Mesh FootprintBuilder::finish() && { return std::move(builder_).finish(); }

}  // namespace gnssemu::scene

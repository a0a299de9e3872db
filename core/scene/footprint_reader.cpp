// Extruded building footprints from TOML: a canyon sketched without a modeller.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/common/error.hpp"
#include "core/scene/mesh.hpp"

namespace gnssemu::scene {

namespace {

struct P2 {
  double e, n;
};

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

double signed_area(const std::vector<P2>& p) {
  double a = 0.0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += p[j].e * p[i].n - p[i].e * p[j].n;
  return 0.5 * a;
}

double cross(const P2& a, const P2& b, const P2& c) { return (b.e - a.e) * (c.n - a.n) - (b.n - a.n) * (c.e - a.e); }

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

double number(const toml::table& t, const char* key, double def, const std::string& path, const std::string& where,
              bool required) {
  const toml::node* n = t.get(key);
  if (n == nullptr) {
    if (required) throw Error(path, line_of(t), where + ": missing " + key);
    return def;
  }
  const auto v = n->value<double>();
  if (!v || !std::isfinite(*v)) throw Error(path, line_of(*n), where + "." + key + ": expected a finite number");
  return *v;
}

std::string text(const toml::table& t, const char* key, const std::string& path, const std::string& where) {
  const toml::node* n = t.get(key);
  if (n == nullptr) return {};
  const auto* s = n->as_string();
  if (s == nullptr) throw Error(path, line_of(*n), where + "." + key + ": expected a string");
  return s->get();
}

void check_keys(const toml::table& t, std::initializer_list<std::string_view> known, const std::string& path,
                const std::string& where) {
  for (const auto& [k, v] : t) {
    bool ok = false;
    for (const std::string_view kk : known) ok = ok || k.str() == kk;
    if (!ok) throw Error(path, line_of(v), where + ": unknown key '" + std::string(k.str()) + "'");
  }
}

void add_building(MeshBuilder& b, const toml::table& t, const std::string& path, const std::string& where) {
  check_keys(t, {"footprint", "height_m", "base_m", "material"}, path, where);
  const toml::node* fp = t.get("footprint");
  if (fp == nullptr || !fp->is_array()) throw Error(path, line_of(t), where + ": footprint = [[e, n], ...] is required");
  std::vector<P2> poly;
  for (const toml::node& pt : *fp->as_array()) {
    const auto* a = pt.as_array();
    if (a == nullptr || a->size() != 2) throw Error(path, line_of(pt), where + ".footprint: each point is [e_m, n_m]");
    const auto e = a->get(0)->value<double>(), n = a->get(1)->value<double>();
    if (!e || !n || !std::isfinite(*e) || !std::isfinite(*n)) {
      throw Error(path, line_of(pt), where + ".footprint: point coordinates must be finite numbers");
    }
    poly.push_back({*e, *n});
  }
  // A repeated point (consecutive, or the closing one) adds no edge: drop it
  // rather than call the polygon self-intersecting.
  poly.erase(std::unique(poly.begin(), poly.end(), [](const P2& a, const P2& c) { return a.e == c.e && a.n == c.n; }),
             poly.end());
  if (poly.size() > 1 && poly.front().e == poly.back().e && poly.front().n == poly.back().n) poly.pop_back();
  if (poly.size() < 3) throw Error(path, line_of(*fp), where + ".footprint: needs at least 3 distinct points");
  const double area = signed_area(poly);
  if (!simple(poly)) throw Error(path, line_of(*fp), where + ".footprint: self-intersecting polygon");
  if (!(std::fabs(area) > 1e-6)) throw Error(path, line_of(*fp), where + ".footprint: zero area");
  if (area < 0.0) std::reverse(poly.begin(), poly.end());
  const double base = number(t, "base_m", 0.0, path, where, false);
  const double height = number(t, "height_m", 0.0, path, where, true);
  if (!(height > 0.0)) throw Error(path, line_of(*t.get("height_m")), where + ".height_m: must be > 0");
  b.set_material(text(t, "material", path, where));
  std::vector<std::array<uint32_t, 3>> tris;
  if (!triangulate(poly, tris)) throw Error(path, line_of(*fp), where + ".footprint: self-intersecting polygon");
  const uint32_t v0 = b.vertex_count();
  const auto m = static_cast<uint32_t>(poly.size());
  const int line = line_of(t);
  for (const P2& p : poly) b.add_vertex(p.e, p.n, base, line_of(*fp));
  for (const P2& p : poly) b.add_vertex(p.e, p.n, base + height, line_of(*fp));
  for (uint32_t i = 0; i < m; ++i) {
    const uint32_t j = (i + 1) % m;
    const uint32_t quad[4] = {v0 + i, v0 + j, v0 + m + j, v0 + m + i};  // outward for CCW footprints
    b.add_face(quad, 4, line);
  }
  for (const auto& tr : tris) {
    const uint32_t roof[3] = {v0 + m + tr[0], v0 + m + tr[1], v0 + m + tr[2]};
    const uint32_t floor[3] = {v0 + tr[0], v0 + tr[2], v0 + tr[1]};
    b.add_face(roof, 3, line);
    b.add_face(floor, 3, line);
  }
}

}  // namespace

Mesh read_footprints(const std::string& path, const Placement& placement) {
  toml::table doc;
  try {
    doc = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw Error(path, static_cast<int>(e.source().begin.line), "TOML syntax error: " + std::string(e.description()));
  }
  check_keys(doc, {"building", "ground"}, path, "footprints");
  MeshBuilder b(path, placement);
  if (const toml::node* g = doc.get("ground")) {
    const auto* t = g->as_table();
    if (t == nullptr) throw Error(path, line_of(*g), "ground: expected a table [ground]");
    check_keys(*t, {"half_size_m", "height_m", "material"}, path, "ground");
    const double h = number(*t, "half_size_m", 0.0, path, "ground", true);
    if (!(h > 0.0)) throw Error(path, line_of(*t->get("half_size_m")), "ground.half_size_m: must be > 0");
    const double z = number(*t, "height_m", 0.0, path, "ground", false);
    b.set_material(text(*t, "material", path, "ground"));
    const uint32_t v0 = b.vertex_count();
    const int line = line_of(*t);
    b.add_vertex(-h, -h, z, line);
    b.add_vertex(h, -h, z, line);
    b.add_vertex(h, h, z, line);
    b.add_vertex(-h, h, z, line);
    const uint32_t quad[4] = {v0, v0 + 1, v0 + 2, v0 + 3};
    b.add_face(quad, 4, line_of(*t));
  }
  if (const toml::node* arr = doc.get("building")) {
    const auto* a = arr->as_array();
    if (a == nullptr) throw Error(path, line_of(*arr), "building: expected [[building]] tables");
    int i = 0;
    for (const toml::node& n : *a) {
      const auto* t = n.as_table();
      const std::string where = "building[" + std::to_string(i++) + "]";
      if (t == nullptr) throw Error(path, line_of(n), where + ": expected a table");
      add_building(b, *t, path, where);
    }
  }
  return std::move(b).finish();
}

}  // namespace gnssemu::scene

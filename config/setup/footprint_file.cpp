// SPDX-License-Identifier: Apache-2.0
#include "config/setup/footprint_file.hpp"

#include <cmath>
#include <initializer_list>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "config/toml/toml_reader.hpp"
#include "core/common/error.hpp"
#include "core/scene/footprints.hpp"

namespace gnssemu::config {

namespace {

using detail::line_of;

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

void add_ground(scene::FootprintBuilder& b, const toml::node& g, const std::string& path) {
  const auto* t = g.as_table();
  if (t == nullptr) throw Error(path, line_of(g), "ground: expected a table [ground]");
  check_keys(*t, {"half_size_m", "height_m", "material"}, path, "ground");
  const double h = number(*t, "half_size_m", 0.0, path, "ground", true);
  if (!(h > 0.0)) throw Error(path, line_of(*t->get("half_size_m")), "ground.half_size_m: must be > 0");
  const double z = number(*t, "height_m", 0.0, path, "ground", false);
  b.add_ground(h, z, text(*t, "material", path, "ground"), line_of(*t));
}

void add_building(scene::FootprintBuilder& b, const toml::table& t, const std::string& path, const std::string& where) {
  check_keys(t, {"footprint", "height_m", "base_m", "material"}, path, where);
  const toml::node* fp = t.get("footprint");
  if (fp == nullptr || !fp->is_array()) throw Error(path, line_of(t), where + ": footprint = [[e, n], ...] is required");
  std::vector<scene::FootprintPoint> points;
  for (const toml::node& pt : *fp->as_array()) {
    const auto* a = pt.as_array();
    if (a == nullptr || a->size() != 2) throw Error(path, line_of(pt), where + ".footprint: each point is [e_m, n_m]");
    const auto e = a->get(0)->value<double>(), n = a->get(1)->value<double>();
    if (!e || !n || !std::isfinite(*e) || !std::isfinite(*n)) {
      throw Error(path, line_of(pt), where + ".footprint: point coordinates must be finite numbers");
    }
    points.push_back({*e, *n});
  }
  const std::vector<scene::FootprintPoint> outline = b.outline(std::move(points), line_of(*fp), where);
  const double base = number(t, "base_m", 0.0, path, where, false);
  const double height = number(t, "height_m", 0.0, path, where, true);
  if (!(height > 0.0)) throw Error(path, line_of(*t.get("height_m")), where + ".height_m: must be > 0");
  b.add_building(outline, base, height, text(t, "material", path, where), line_of(*fp), line_of(t), where);
}

}  // namespace

scene::Mesh read_footprints(const std::string& path, const scene::Placement& placement) {
  toml::table doc;
  try {
    doc = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw Error(path, static_cast<int>(e.source().begin.line), "TOML syntax error: " + std::string(e.description()));
  }
  check_keys(doc, {"building", "ground"}, path, "footprints");
  scene::FootprintBuilder b(path, placement);
  if (const toml::node* g = doc.get("ground")) add_ground(b, *g, path);
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

scene::Mesh load_mesh(const std::string& path, const scene::Placement& placement) {
  return scene::load_mesh(path, placement, read_footprints);
}

}  // namespace gnssemu::config

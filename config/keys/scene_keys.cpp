// SPDX-License-Identifier: Apache-2.0
// [scene]: the buildings' mesh, its placement, the search effort and the
// reflection losses (docs/scene.md). Ranges: core/scene's.
#include "config/keys/config_keys.hpp"

namespace gnssemu::config::detail {

namespace {

using scene::Placement;
using scene::SearchConfig;
using Pr = scene::PlacementRanges;
using Sr = scene::SearchRanges;

// dB per reflection, every material and each named one.
constexpr Range kReflectionLoss = scene::SceneRanges::reflection_loss_db;

constexpr Choice<bool> kUpAxes[] = {{"z", false}, {"y", true}};

void read_offset(TableReader& t, const Field<SceneConfig>& f, SceneConfig& s) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) return;
  const std::string name = t.full_name(f.key);
  const auto* a = n->as_array();
  if (a == nullptr || a->size() != 3) t.fail(*n, name + ": expected [east_m, north_m, up_m]");
  double v[3];
  for (std::size_t i = 0; i < 3; ++i) {
    const auto x = a->get(i)->value<double>();
    if (!x || !Pr::offset_m.contains(*x)) {
      t.fail(*a->get(i), name + ": components must be finite numbers within 1000 km");
    }
    v[i] = *x;
  }
  s.placement.offset_m = Enu(v[0], v[1], v[2]);
}

void write_offset(TomlWriter& w, const Field<SceneConfig>& f, const SceneConfig& s) {
  const Enu& o = s.placement.offset_m;
  std::string v = "[";
  v += number_text(o.x) + ", " + number_text(o.y) + ", " + number_text(o.z) + "]";
  w.key(f.key, v, f.note);
}

constexpr Field<SceneConfig> offset_field() {
  Field<SceneConfig> row = custom<SceneConfig>("offset_m", Pr::offset_m.unit, "",
                                             "model origin in the local ENU frame of `[origin]`", read_offset,
                                             write_offset);
  row.note = "model origin in local ENU";
  row.doc_range_of = [] { return "[east, north, up], each in " + range_text(Pr::offset_m); };
  return row;
}

// name = dB per material of the mesh; the line is kept for load_scene's
// message about a name the mesh does not have.
void read_material_loss(TableReader& t, const Field<SceneConfig>& f, SceneConfig& s) {
  if (std::optional<TableReader> m = t.table(f.key, false)) {
    for (const auto& [k, v] : *t.find(f.key)->as_table()) {
      const std::string key(k.str());
      s.material_loss_db.push_back({key, m->number(key, std::nullopt, kReflectionLoss), line_of(v)});
    }
    m->finish();
  }
}

void write_material_loss(TomlWriter& w, const Field<SceneConfig>& f, const SceneConfig& s) {
  if (s.material_loss_db.empty()) return;
  const std::string outer = w.table();
  w.set_table(sub_table(w, f.key));
  w.header({});
  for (const SceneConfig::MaterialLoss& m : s.material_loss_db) w.key(string_text(m.name), number_text(m.loss_db));
  w.set_table(outer);
}

constexpr Field<SceneConfig> material_loss_field() {
  Field<SceneConfig> row = custom<SceneConfig>(
      "material_loss_db", kReflectionLoss.unit, "",
      "`[scene.material_loss_db]`: `name = dB` per material name of the mesh (OBJ `usemtl`, footprint `material`); "
      "a name the mesh does not have is an error naming this file and line, listing the mesh's materials",
      read_material_loss, write_material_loss);
  row.doc_default = "none";
  row.doc_range_of = [] { return "table of " + range_text(kReflectionLoss); };
  row.open_keys = true;
  return row;
}

constexpr Field<SceneConfig> kSceneFields[] = {
    existing_file<&SceneConfig::mesh_file>("mesh", "`.obj`, `.ply` (ascii/binary) or footprint `.toml`; relative to "
                                                   "this config file"),
    offset_field(),
    angle<&SceneConfig::placement, &Placement::yaw_rad>("yaw_deg", Pr::yaw_deg,
                                                        "rotation about up, counter-clockwise seen from above")
        .with_note("counter-clockwise from east"),
    number<&SceneConfig::placement, &Placement::scale>("scale", Pr::scale, "model units to metres"),
    either<kUpAxes, &SceneConfig::placement, &Placement::y_up>("up_axis", "`\"y\"` for Y-up exports"),
    integer<&SceneConfig::search, &SearchConfig::rays>("rays", Sr::rays,
                                                       "hemisphere search rays (scenes with slanted faces)"),
    integer<&SceneConfig::search, &SearchConfig::azimuth_rays>(
        "azimuth_rays", Sr::azimuth_rays, "cone rays per blocked satellite (vertical/horizontal scenes); 0 = always "
                                          "hemisphere")
        .with_note("per blocked satellite, vertical/horizontal scenes"),
    integer<&SceneConfig::search, &SearchConfig::max_bounces>("max_bounces", Sr::max_bounces,
                                                              "reflections per path at most"),
    number<&SceneConfig::search, &SearchConfig::match_factor>("match_factor", Sr::match_factor,
                                                              "candidate tolerance in ray spacings"),
    number<&SceneConfig::search, &SearchConfig::reuse_distance_m>(
        "reuse_distance_m", Sr::reuse_distance_m,
        "reuse a satellite's path within this distance of its last search (0 and angle 0: off)"),
    angle<&SceneConfig::search, &SearchConfig::reuse_angle_rad>("reuse_angle_deg", Sr::reuse_angle_deg,
                                                                "… and while its direction turned less than this"),
    angle<&SceneConfig::search, &SearchConfig::min_arrival_el_rad>(
        "min_arrival_elevation_deg", Sr::min_arrival_elevation_deg,
        "reflected arrivals from below are rejected (antenna)"),
    number<&SceneConfig::search, &SearchConfig::max_loss_db>("max_loss_db", Sr::max_loss_db,
                                                             "paths with more reflection loss are not received"),
    number<&SceneConfig::reflection_loss_db>("reflection_loss_db", kReflectionLoss,
                                             "loss per reflection, every material"),
    material_loss_field(),
};

}  // namespace

constexpr Section<SceneConfig> kSceneKeys{kSceneFields};

}  // namespace gnssemu::config::detail

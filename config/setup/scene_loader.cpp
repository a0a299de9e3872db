// SPDX-License-Identifier: Apache-2.0
#include "config/setup/scene_loader.hpp"

#include "config/setup/footprint_file.hpp"
#include "core/common/error.hpp"

namespace gnssemu::config {

std::unique_ptr<scene::Scene> load_scene(const Config& c, scene::MeshStats* stats) {
  if (!c.scene) return nullptr;
  const SceneConfig& s = *c.scene;
  const scene::Mesh mesh = config::load_mesh(s.mesh_file, s.placement);
  if (stats != nullptr) *stats = mesh.stats;
  auto out = std::make_unique<scene::Scene>(mesh);
  out->set_default_loss_db(s.reflection_loss_db);
  for (const SceneConfig::MaterialLoss& m : s.material_loss_db) {
    if (!out->set_material_loss_db(m.name, m.loss_db)) {
      std::string known;
      for (const std::string& n : out->material_names()) {
        if (!n.empty()) known += (known.empty() ? "" : ", ") + n;
      }
      throw Error(c.source, m.line,
                  "scene.material_loss_db." + m.name + ": no such material in " + s.mesh_file +
                      (known.empty() ? " (it has none)" : " (it has: " + known + ")"));
    }
  }
  return out;
}

}  // namespace gnssemu::config

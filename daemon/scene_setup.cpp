// SPDX-License-Identifier: Apache-2.0
#include "daemon/scene_setup.hpp"

#include <spdlog/spdlog.h>

#include "config/setup/scene_loader.hpp"
#include "core/scene/mesh.hpp"

namespace gnssemu::daemon {

std::unique_ptr<scene::Scene> load_scene_logged(const config::Config& cfg) {
  scene::MeshStats stats;
  std::unique_ptr<scene::Scene> s = config::load_scene(cfg, &stats);
  if (const std::string w = scene::skip_report(stats); !w.empty()) spdlog::warn("scene {}", w);
  return s;
}

}  // namespace gnssemu::daemon

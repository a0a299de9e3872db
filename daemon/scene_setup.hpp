// SPDX-License-Identifier: Apache-2.0
#pragma once
// The daemon's scene: loaded once at start-up, what the mesh reader skipped
// logged as a warning (count by reason and the first file:line).
#include <memory>

#include "config/config.hpp"
#include "core/scene/scene.hpp"

namespace gnssemu::daemon {

/// config::load_scene(cfg) plus spdlog::warn("scene mesh: N bad elements
/// skipped (...); first: file:line: reason") when the reader skipped
/// anything. nullptr without [scene]. Throws what load_scene throws.
std::unique_ptr<scene::Scene> load_scene_logged(const config::Config& cfg);

}  // namespace gnssemu::daemon

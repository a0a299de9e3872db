// SPDX-License-Identifier: Apache-2.0
#pragma once
// Load the configured scene (the pipeline's world takes it through
// make_pipeline, config/setup/pipeline_setup.hpp).
#include <memory>

#include "config/config.hpp"
#include "core/scene/scene.hpp"

namespace gnssemu::config {

/// The mesh of c.scene placed in the ENU frame of c.origin, with the
/// configured reflection losses; nullptr when c has no [scene]. stats (if
/// given) receives what the mesh reader skipped. Throws gnssemu::Error
/// (mesh file:line, or config file:line for an unknown material name).
std::unique_ptr<scene::Scene> load_scene(const Config& c, scene::MeshStats* stats = nullptr);

}  // namespace gnssemu::config

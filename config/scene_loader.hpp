#pragma once
// Load the configured scene and give it to a receiver: the one place batch
// and the daemon set up the scene stage from a Config.
#include <memory>

#include "config/config.hpp"
#include "core/receiver/receiver.hpp"
#include "core/scene/scene.hpp"

namespace gnssemu::config {

/// The mesh of c.scene placed in the ENU frame of c.origin, with the
/// configured reflection losses; nullptr when c has no [scene]. stats (if
/// given) receives what the mesh reader skipped. Throws gnssemu::Error
/// (mesh file:line, or config file:line for an unknown material name).
std::unique_ptr<scene::Scene> load_scene(const Config& c, scene::MeshStats* stats = nullptr);

/// Attaches scene (from load_scene(c)) to rx with c's origin and search
/// settings; does nothing when scene is null.
void attach_scene(receiver::Receiver& rx, const Config& c, const scene::Scene* scene);

}  // namespace gnssemu::config

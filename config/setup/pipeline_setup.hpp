// SPDX-License-Identifier: Apache-2.0
#pragma once
// The emulated receiver of a Config: the one assembly path of the daemon,
// `gnssemu batch` and every other caller that starts from a configuration.
#include <memory>

#include "config/config.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/scene/scene.hpp"

namespace gnssemu::config {

/// The world and receiver settings of c.
pipeline::PipelineConfig pipeline_config(const Config& c);

/// The receiver of c in its world: c's settings, the ephemerides of store,
/// what the nav file's header broadcasts (pipeline::broadcast_of(nav)), and
/// scene (from load_scene(c); may be null) at c's origin with c's search
/// settings. store and scene must outlive the result. Throws gnssemu::Error
/// on an invalid setting.
std::unique_ptr<pipeline::Pipeline> make_pipeline(const Config& c, const orbit::EphemerisStore& store,
                                                  const pipeline::Broadcast& broadcast, const scene::Scene* scene);

}  // namespace gnssemu::config

// SPDX-License-Identifier: Apache-2.0
#include "config/setup/pipeline_setup.hpp"

namespace gnssemu::config {

pipeline::PipelineConfig pipeline_config(const Config& c) { return pipeline::PipelineConfig{c.world, c.receiver}; }

std::unique_ptr<pipeline::Pipeline> make_pipeline(const Config& c, const orbit::EphemerisStore& store,
                                                  const pipeline::Broadcast& broadcast, const scene::Scene* scene) {
  world::SceneSetup buildings;
  if (scene != nullptr && c.scene) buildings = world::SceneSetup{scene, c.origin, c.scene->search};
  return std::make_unique<pipeline::Pipeline>(store, pipeline_config(c), broadcast, buildings);
}

}  // namespace gnssemu::config

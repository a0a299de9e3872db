// SPDX-License-Identifier: Apache-2.0
#include "core/pipeline/pipeline.hpp"

namespace gnssemu::pipeline {

Broadcast broadcast_of(const orbit::NavData& nav) { return Broadcast{nav.klobuchar, nav.leap_seconds}; }

namespace {

/// The world a receiver needs: the bands it tracks.
world::WorldConfig world_for(const PipelineConfig& c) {
  world::WorldConfig w = c.world;
  w.bands = c.receiver.bands;
  return w;
}

}  // namespace

Pipeline::Pipeline(const orbit::EphemerisStore& store, const PipelineConfig& config, const Broadcast& broadcast,
                   const world::SceneSetup& scene)
    : world_(store, world_for(config)), receiver_(config.receiver, config.world.seed) {
  world_.set_klobuchar_shape(broadcast.klobuchar);
  receiver_.set_klobuchar(broadcast.klobuchar);
  if (broadcast.leap_seconds) receiver_.set_leap_seconds(*broadcast.leap_seconds);
  if (scene.scene != nullptr) world_.attach_scene(scene);
  fault_context_.seed = config.world.seed;
  fault_context_.link = config.world.signal.link;
  fault_context_.noise = world::MeasurementNoise::of(config.world);
}

void Pipeline::set_faults(std::span<const faults::FaultEvent> events) {
  faults_ = std::make_unique<faults::FaultStage>(fault_context_, events);
}

void Pipeline::adopt_faults(std::unique_ptr<faults::FaultStage> stage) {
  if (stage) stage->set_context(fault_context_);
  faults_ = std::move(stage);
}

}  // namespace gnssemu::pipeline

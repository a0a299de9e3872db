// SPDX-License-Identifier: Apache-2.0
#pragma once
// Pipeline: the emulated receiver in its world, as every caller runs it —
// vehicle truth in, the receiver's Fix out. The world makes the observables
// at the antenna, the fault stage (when there is one) edits them, and the
// receiver processes them. The one place these are put together, with
// what the navigation message broadcasts and the optional buildings.
#include <memory>
#include <optional>
#include <span>

#include "core/faults/fault_stage.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/receiver/receiver.hpp"
#include "core/world/world.hpp"

namespace gnssemu::pipeline {

struct PipelineConfig {
  world::WorldConfig world;
  receiver::ReceiverConfig receiver;
};

/// What the navigation message broadcasts besides the ephemerides (a nav
/// file's header).
struct Broadcast {
  /// Klobuchar coefficients: the receiver's ionospheric correction, and the
  /// shape of the world's Klobuchar-shaped ionosphere unless its config gives
  /// one. Invalid: RTKLIB's default coefficients for both.
  orbit::KlobucharParams klobuchar;
  std::optional<int> leap_seconds = std::nullopt;  ///< GPS - UTC; none: the built-in table
};

/// The header part of a nav file.
Broadcast broadcast_of(const orbit::NavData& nav);

class Pipeline {
public:
  /// store (and scene.scene) must outlive the pipeline. Setup only
  /// (allocates); throws gnssemu::Error on an invalid config or broadcast.
  Pipeline(const orbit::EphemerisStore& store, const PipelineConfig& config, const Broadcast& broadcast = {},
           const world::SceneSetup& scene = {});

  /// One epoch at receive time t (GPS): the world at the receiver's mask,
  /// the faults, then the receiver. Never throws, never allocates.
  const receiver::Fix& step(const time::GpsTime& t, const world::Truth& truth) noexcept {
    world_.set_tracked_systems(receiver_.systems());
    return finish(t, truth, world_.step(t, truth, receiver_.config().elevation_mask_rad));
  }

  /// The same at the epoch of a sky shared by several pipelines (a fleet,
  /// several antennas on a vehicle): the caller updates it once for
  /// sky.t() with every antenna, then steps each pipeline with it.
  const receiver::Fix& step(const world::SharedSky& sky, const world::Truth& truth) noexcept {
    world_.set_tracked_systems(receiver_.systems());
    return finish(sky.t(), truth, world_.step(sky, truth, receiver_.config().elevation_mask_rad));
  }

  /// Put a fault stage between world and receiver with these events (start
  /// times from the first epoch; none: an empty stage that inject() fills
  /// later). Setup only (allocates); throws gnssemu::Error on a bad event.
  void set_faults(std::span<const faults::FaultEvent> events);
  /// Hand the fault stage (its events, time line and spoofer state) to
  /// another pipeline: the faults are in the world around the receiver, so a
  /// receiver restart (a reset, a reload) keeps them. nullptr without one.
  std::unique_ptr<faults::FaultStage> take_faults() noexcept { return std::move(faults_); }
  /// Take over a stage from take_faults(), now with this pipeline's noise
  /// models and seed (nullptr: no stage). Setup only.
  void adopt_faults(std::unique_ptr<faults::FaultStage> stage);
  /// The fault stage, or nullptr without one.
  faults::FaultStage* faults() noexcept { return faults_.get(); }
  const faults::FaultStage* faults() const noexcept { return faults_.get(); }

  const receiver::Fix& last_fix() const noexcept { return receiver_.last_fix(); }
  /// The receiver's corrections changed between epochs: Receiver::on_corrections
  /// with the observables of the last epoch. Never allocates.
  bool on_corrections() noexcept { return receiver_.on_corrections(faults_ ? obs_ : world_.observables()); }
  world::World& world() noexcept { return world_; }
  const world::World& world() const noexcept { return world_; }
  receiver::Receiver& receiver() noexcept { return receiver_; }
  const receiver::Receiver& receiver() const noexcept { return receiver_; }

private:
  /// The fault stage (if any), then the receiver, on the world's observables o.
  const receiver::Fix& finish(const time::GpsTime& t, const world::Truth& truth, const world::Observables& o) noexcept {
    if (!faults_) return receiver_.step(t, o);
    obs_ = o;  // the world's own stay untouched
    faults_->apply(t, truth, obs_);
    return receiver_.step(t, obs_);
  }

  world::World world_;
  receiver::Receiver receiver_;
  faults::FaultContext fault_context_;
  std::unique_ptr<faults::FaultStage> faults_;
  world::Observables obs_;  ///< the faulted copy of the world's observables
};

}  // namespace gnssemu::pipeline

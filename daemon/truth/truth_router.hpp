// SPDX-License-Identifier: Apache-2.0
#pragma once
// TruthRouter: the tracks of all vehicles heard on the truth input, their
// sim->GPS clock maps, and the choice of the vehicle that drives the receiver
// (the configured one, else the first seen). Pure: the caller passes clocks.
#include <optional>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "daemon/truth/time_mapping.hpp"
#include "daemon/truth/truth_packet.hpp"
#include "daemon/truth/vehicle_track.hpp"

namespace gnssemu::daemon {

class TruthRouter {
public:
  static constexpr std::size_t kMaxVehicles = 16;

  /// driving_vehicle: id to follow; empty: the first vehicle seen.
  TruthRouter(const TrackParams& params, config::TimeMode mode, std::string driving_vehicle = {});

  struct Ingest {
    bool accepted = false;
    DropReason reason = DropReason::kCount;  ///< when !accepted
    bool new_vehicle = false;
    bool driving = false;           ///< sample belongs to the driving vehicle
    bool reanchored = false;        ///< sim->GPS anchor (re)set by this sample
    bool restarted = false;         ///< the vehicle's history was restarted
    VehicleTrack::Step step;        ///< from the vehicle's previous sample (step.jump(): a jump)
    time::GpsTime stamp;            ///< GPS stamp given to the sample
  };

  /// Add a parsed sample. clock_gps: realtime — the epoch clock at arrival;
  /// lockstep — GPS time of the next epoch (anchors a new sim clock there).
  /// now_s: monotonic time, s.
  Ingest ingest(const TruthSample& sample, const time::GpsTime& clock_gps, double now_s);

  /// Truth of the driving vehicle at GPS time t (invalid when none or timed out).
  world::Truth truth_at(const time::GpsTime& t, double now_s) const noexcept;

  /// Whether any sample of the driving vehicle was ever accepted (after this,
  /// the demo never drives the receiver again).
  bool has_driver() const noexcept { return driver_ >= 0; }
  /// Driving vehicle's last packet within the timeout.
  bool driver_fresh(double now_s) const noexcept;
  /// Seconds since the driving vehicle's last accepted packet; NaN when none.
  double driver_age_s(double now_s) const noexcept;
  /// Newest stamp of the driving vehicle, if any sample is held.
  std::optional<time::GpsTime> driver_newest() const noexcept;
  const std::string& driver_id() const noexcept { return driving_id_; }

  /// New timeouts ([truth] reloaded); the tracks are kept.
  void set_params(const TrackParams& params) noexcept { params_ = params; }
  /// Follow vehicle id from now on (empty: the first vehicle heard next, or
  /// the one already driving). The tracks are kept: a vehicle already heard
  /// drives at once.
  void set_driving_vehicle(const std::string& id);
  /// The configured vehicle (set_driving_vehicle or the constructor), "" none.
  const std::string& wanted_vehicle() const noexcept { return wanted_; }

  /// The epoch clock jumped back (coverage wrap): drop samples, re-anchor clocks.
  void on_clock_jump() noexcept;

  std::size_t vehicle_count() const noexcept { return vehicles_.size(); }
  const TrackParams& params() const noexcept { return params_; }

private:
  struct Vehicle {
    std::string id;
    VehicleTrack track;
    SimClockMap clock;
  };

  TrackParams params_;
  config::TimeMode mode_;
  std::string driving_id_;
  std::string wanted_;  ///< configured vehicle, "" the first heard
  std::vector<Vehicle> vehicles_;
  int driver_ = -1;
};

}  // namespace gnssemu::daemon

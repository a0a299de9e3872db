// SPDX-License-Identifier: Apache-2.0
#pragma once
// FleetRouter: the truth input's routing to the daemon's vehicles. One UDP
// socket feeds all of them; a packet's "vehicle" picks one, which keeps its
// own TruthRouter (track, sim clock map, timeout) and the attitude of its
// newest packet (for the lever arms). An id that names no configured vehicle
// is refused (DropReason::kUnknownVehicle) and nothing is kept of it, so a
// flood of ids costs no memory. The single-vehicle form is one entry that
// takes every id, its TruthRouter choosing the driver as it always did.
// Pure: the caller passes clocks.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "config/config.hpp"
#include "daemon/truth/truth_packet.hpp"
#include "daemon/truth/truth_router.hpp"

namespace gnssemu::daemon {

class FleetRouter {
public:
  /// ids: the vehicles in config order, each a packet's vehicle id; {""}:
  /// the single-vehicle form (any id), driving: its [truth] vehicle ("" the
  /// first heard). Setup only (allocates).
  FleetRouter(const TrackParams& params, config::TimeMode mode, const std::vector<std::string>& ids,
              const std::string& driving = {});

  struct Routed {
    std::optional<std::size_t> vehicle;  ///< none: no configured vehicle has the id
    TruthRouter::Ingest in;              ///< the vehicle's router's answer (reason kUnknownVehicle when none)
  };
  /// Route a parsed sample (clock_gps and now_s as TruthRouter::ingest).
  Routed ingest(const TruthSample& sample, const time::GpsTime& clock_gps, double now_s);

  /// The vehicle a packet with id goes to; none: unknown. O(log n).
  std::optional<std::size_t> find(std::string_view id) const noexcept;
  std::size_t size() const noexcept { return routers_.size(); }
  /// The single-vehicle form (one entry, any id).
  bool single() const noexcept { return single_; }
  const std::string& id(std::size_t v) const noexcept { return ids_[v]; }
  TruthRouter& router(std::size_t v) noexcept { return routers_[v]; }
  const TruthRouter& router(std::size_t v) const noexcept { return routers_[v]; }
  /// The attitude of vehicle v's newest accepted packet that had one.
  const std::optional<Attitude>& attitude(std::size_t v) const noexcept { return attitude_[v]; }

  /// Some vehicle's driver sent within its timeout.
  bool any_fresh(double now_s) const noexcept;
  /// Lockstep: the GPS time every driven vehicle has reached — the oldest
  /// newest stamp among the vehicles whose driver is fresh (a vehicle that
  /// stopped holds the others back only until its timeout). None: no fresh one.
  std::optional<time::GpsTime> reached(double now_s) const noexcept;

  /// New timeouts for every vehicle ([truth] reloaded); the tracks are kept.
  void set_params(const TrackParams& params) noexcept;

  /// The vehicles become ids (a reload of the fleet form): a vehicle in both
  /// keeps its router (track, clock map, driver) and attitude, a new one
  /// starts empty, a missing one is gone (its packets kUnknownVehicle).
  /// Returns, per old index, its new index (none: removed). Setup only.
  std::vector<std::optional<std::size_t>> reshape(const std::vector<std::string>& ids);

private:
  TrackParams params_;
  config::TimeMode mode_;
  bool single_;
  std::vector<std::string> ids_;
  std::vector<TruthRouter> routers_;
  std::vector<std::optional<Attitude>> attitude_;
  std::vector<std::pair<std::string, std::size_t>> by_id_;  ///< sorted by id
};

}  // namespace gnssemu::daemon

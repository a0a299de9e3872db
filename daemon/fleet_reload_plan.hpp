// SPDX-License-Identifier: Apache-2.0
#pragma once
// FleetReloadPlan: what a SIGHUP reload does to a fleet's vehicles
// (docs/daemon.md §Reload). Vehicles match by id: one only in the loaded
// file is added, one only in the running configuration is removed, one whose
// receivers are the same in both is kept (untouched), the others changed.
// A changed vehicle's receivers match by name and follow ReloadPlan, each on
// its own receiver configuration (config::receiver_config) with the running
// top level, so [origin], [time] ... are the top level's plan, said once.
// A lever arm applies live; receivers added to or removed from a vehicle
// need a restart.
#include <cstddef>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "daemon/reload_plan.hpp"

namespace gnssemu::daemon {

struct ReceiverReload {
  std::string name;
  std::size_t running = 0;  ///< its index in the running vehicle's receivers
  std::size_t loaded = 0;   ///< and in the loaded one's
  bool lever_arm = false;   ///< the lever arm changed (applied live)
  ReloadPlan plan;          ///< need_restart without what the top level's plan says
};

struct VehicleReload {
  std::string id;
  std::size_t running = 0;  ///< index in resolve_vehicles(running); added: unused
  std::size_t loaded = 0;   ///< index in resolve_vehicles(loaded); removed: unused
  std::vector<ReceiverReload> receivers;  ///< changed: the receivers in both, running order
  std::vector<std::string> need_restart;  ///< changed: receivers added or removed

  /// Something of the changed vehicle applies live.
  bool applies() const noexcept;
  /// "gps1: receiver models (receiver restarted), output a reopened; gps2: lever arm".
  std::string describe_live() const;
  /// "gps1: output a protocols/messages/baud; receivers added or removed (gps1 -> gps1, gps2)".
  std::string describe_restart() const;
};

struct FleetReloadPlan {
  std::vector<VehicleReload> added;    ///< loaded order
  std::vector<VehicleReload> removed;  ///< running order
  std::vector<VehicleReload> kept;     ///< unchanged, running order
  std::vector<VehicleReload> changed;  ///< running order

  /// Ids of each list, for tests and the log: "a, b"; "none" when empty.
  static std::string ids(const std::vector<VehicleReload>& list);
};

/// Compares the vehicles of two configurations of the fleet form ([[vehicle]]
/// or [fleet]); top_restart: the top level's ReloadPlan::need_restart, left
/// out of each receiver's.
FleetReloadPlan plan_fleet_reload(const config::Config& running, const config::Config& loaded,
                                  const std::vector<std::string>& top_restart);

}  // namespace gnssemu::daemon

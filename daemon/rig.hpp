// SPDX-License-Identifier: Apache-2.0
#pragma once
// One emulated receiver of the daemon: its pipeline in the shared world, its
// u-blox device, the port channels wired to the device's outputs, its
// status and its view of the faults, keyed by vehicle and receiver name.
// The Daemon holds a list of them; a file of the single-vehicle form is a
// list of one.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "config/setup/device_setup.hpp"
#include "core/common/vec3.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/world/truth.hpp"
#include "daemon/fault_log.hpp"
#include "daemon/ports/port_channel.hpp"
#include "daemon/status/status_producer.hpp"
#include "daemon/status/status_setup.hpp"

namespace gnssemu::daemon {

struct Rig {
  /// rx_cfg: this receiver's configuration (the top level with its merged
  /// [receiver] settings and its outputs); vehicle_idx: its vehicle in the
  /// daemon's list; lever_arm: antenna in the body frame (forward, right,
  /// down), m; nav_systems: the systems the nav data hold (orbit::systems_of).
  Rig(std::string vehicle_id, std::string receiver_name, std::size_t vehicle_idx, const config::Config& rx_cfg,
      const Vec3& lever_arm, SystemSet nav_systems)
      : vehicle(std::move(vehicle_id)),
        name(std::move(receiver_name)),
        vehicle_index(vehicle_idx),
        cfg(rx_cfg),
        lever_arm_m(lever_arm),
        device(config::device_setup(rx_cfg, nav_systems)),
        status(status_settings(rx_cfg)) {}

  /// "ego/gps1": how logs and ctl name the receiver.
  std::string label() const { return vehicle + "/" + name; }

  std::string vehicle;  ///< the truth packets' vehicle id; "" = any (single-vehicle form)
  std::string name;     ///< the receiver's name on its vehicle
  std::size_t vehicle_index;
  config::Config cfg;   ///< its settings and outputs (cfg.outputs: channel i's port)
  Vec3 lever_arm_m;
  std::unique_ptr<pipeline::Pipeline> receiver;  ///< the emulated receiver in its world
  protocol::ubx::Device device;                  ///< every output is one of its UART1s
  std::vector<std::unique_ptr<PortChannel>> channels;
  std::vector<std::string> out_summary;  ///< per channel: what it sent when last logged ("NMEA+UBX")

  StatusProducer status;                 ///< its /api/status and ctl status
  std::vector<FaultStatus> faults_view;  ///< the fault list as its status shows it
  double fault_status_s = -1.0;          ///< run time the fault list was last built, s
  FaultLog fault_log;                    ///< fault starts and ends, for the log

  world::Truth truth;         ///< at its antenna, this epoch
  int last_fix_type = -1;
  bool last_truth_valid = false;
  int last_num_used = 0;
  int last_num_tracked = 0;
};

}  // namespace gnssemu::daemon

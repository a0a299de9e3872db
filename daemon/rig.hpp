// SPDX-License-Identifier: Apache-2.0
#pragma once
// One emulated receiver of the daemon: its pipeline in the world, its u-blox
// device and the port channels wired to the device's outputs, keyed by
// vehicle and receiver name. The Daemon holds a list of them; a file of the
// single-vehicle form is a list of one.
#include <memory>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "config/device_setup.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/protocol/ubx/ubx_device.hpp"
#include "daemon/ports/port_channel.hpp"

namespace gnssemu::daemon {

struct Rig {
  /// cfg: the configuration whose [receiver] and outputs this rig runs;
  /// nav_systems: the systems the nav data hold (orbit::systems_of).
  Rig(std::string vehicle_id, std::string receiver_name, const config::Config& cfg, SystemSet nav_systems)
      : vehicle(std::move(vehicle_id)), name(std::move(receiver_name)), device(config::device_setup(cfg, nav_systems)) {}

  std::string vehicle;  ///< the truth packets' vehicle id; "" = any (single-vehicle form)
  std::string name;     ///< the receiver's name on its vehicle
  std::unique_ptr<pipeline::Pipeline> receiver;  ///< the emulated receiver in its world
  protocol::ubx::Device device;                  ///< every output is one of its UART1s
  std::vector<std::unique_ptr<PortChannel>> channels;
  std::vector<std::string> out_summary;  ///< per channel: what it sent when last logged ("NMEA+UBX")
};

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#pragma once
// ReloadPlan: what a SIGHUP reload changes (docs/daemon.md §Reload). Applied
// live: [log] level, [truth] allow / vehicle / timeout_s /
// max_extrapolation_s, [demo]; the receiver's models ([receiver],
// [atmosphere], [signal], [scene]: the receiver restarts on the new ones and
// reacquires, as after a reset); an output whose transport alone changed
// (pty path, serial device, tcp/udp address, file) is reopened, the others
// stay open. Needs a restart (logged, the running value kept): [origin],
// [nav], [time], rate_hz, [truth] bind/port, outputs added or removed, and
// an output's protocols, messages or baud (the emulated chip's stored
// configuration, which hosts may have changed since), and its name; a
// change between the single-vehicle form and [[vehicle]]/[fleet]. A fleet's
// vehicles: FleetReloadPlan, which applies this plan per receiver.
#include <cstddef>
#include <string>
#include <vector>

#include "config/config.hpp"

namespace gnssemu::daemon {

struct ReloadPlan {
  bool log_level = false;
  bool truth = false;      ///< allow, vehicle, timeout_s, max_extrapolation_s
  bool demo = false;
  bool receiver = false;   ///< receiver or world models: rebuild the pipeline
  bool scene = false;      ///< [scene] (also rebuilds the pipeline)
  std::vector<std::size_t> reopen;        ///< outputs whose transport changed
  std::vector<std::string> need_restart;  ///< what changed but applies only at a restart

  /// Something is applied live.
  bool applies() const noexcept { return log_level || truth || demo || receiver || scene || !reopen.empty(); }
  /// "log level, truth, output gps0 reopened" for the log; "nothing" when empty.
  std::string describe(const config::Config& now) const;
};

/// Compares the running configuration with the one just loaded.
ReloadPlan plan_reload(const config::Config& running, const config::Config& loaded);

/// The [truth] settings a reload applies while running (allow-list, vehicle,
/// timeouts): copied from loaded into running. Bind address and port need a restart.
inline void take_live_truth(config::TruthInputConfig& running, const config::TruthInputConfig& loaded) {
  running.allow = loaded.allow;
  running.vehicle = loaded.vehicle;
  running.timeout_s = loaded.timeout_s;
  running.max_extrapolation_s = loaded.max_extrapolation_s;
}

}  // namespace gnssemu::daemon

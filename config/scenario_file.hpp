// SPDX-License-Identifier: Apache-2.0
#pragma once
// Scenario files (TOML, docs/faults.md): a list of [[event]] tables, each
//   start_s (s after the first epoch, or after "now" when injected),
//   duration_s (optional; default: to the end), type (jammer, spoofer,
//   outage, sky_block, satellite, port), the type's string key (kind, mode,
//   antenna, fault) and its parameters, each a number or a [from, to] ramp
//   over the event.
// The same text drives gnssemu batch --scenario, gnssemud --scenario and
// injection on the control socket. gnssemud's events may name a target
// (target = "v3" for a vehicle's receivers, "v3/gps2" for one of them).
#include <string>
#include <string_view>
#include <vector>

#include "core/faults/fault_event.hpp"

namespace gnssemu::config {

/// An event and the receivers it acts on.
struct ScenarioEvent {
  faults::FaultEvent event;
  /// "" every receiver; "v3" every receiver of vehicle v3; "v3/gps2" that
  /// one (ids and names as in docs/configuration.md §Vehicles).
  std::string target;
};

/// Whether target (a ScenarioEvent's, not "") names rig receiver of vehicle.
bool target_matches(std::string_view target, std::string_view vehicle, std::string_view receiver) noexcept;

/// Events of a scenario file, in file order. Throws gnssemu::Error naming
/// path:line for a syntax error, an unknown type or key, a value out of
/// range or a missing parameter; and for a target (one receiver runs here).
std::vector<faults::FaultEvent> read_scenario(const std::string& path);

/// The same from text; name is what errors call it ("control socket").
std::vector<faults::FaultEvent> parse_scenario(std::string_view text, const std::string& name);

/// The same with targets (gnssemud: a fleet's receivers). Throws as
/// read_scenario, and for a target that is not "id" or "id/name".
std::vector<ScenarioEvent> read_targeted_scenario(const std::string& path);
std::vector<ScenarioEvent> parse_targeted_scenario(std::string_view text, const std::string& name);

}  // namespace gnssemu::config

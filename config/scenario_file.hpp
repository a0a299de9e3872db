// SPDX-License-Identifier: Apache-2.0
#pragma once
// Scenario files (TOML, docs/faults.md): a list of [[event]] tables, each
//   start_s (s after the first epoch, or after "now" when injected),
//   duration_s (optional; default: to the end), type (jammer, spoofer,
//   outage, sky_block, satellite, port), the type's string key (kind, mode,
//   antenna, fault) and its parameters, each a number or a [from, to] ramp
//   over the event.
// The same text drives gnssemu batch --scenario, gnssemud --scenario and
// injection on the control socket.
#include <string>
#include <string_view>
#include <vector>

#include "core/faults/fault_event.hpp"

namespace gnssemu::config {

/// Events of a scenario file, in file order. Throws gnssemu::Error naming
/// path:line for a syntax error, an unknown type or key, a value out of
/// range or a missing parameter.
std::vector<faults::FaultEvent> read_scenario(const std::string& path);

/// The same from text; name is what errors call it ("control socket").
std::vector<faults::FaultEvent> parse_scenario(std::string_view text, const std::string& name);

}  // namespace gnssemu::config

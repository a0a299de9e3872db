// SPDX-License-Identifier: Apache-2.0
#pragma once
// The control socket's commands (docs/daemon.md §Control socket). One JSON
// object per line in, one per line out:
//   {"cmd":"status"}                                  -> {"ok":true,"cmd":"status","status":{...}}
//   {"cmd":"inject","scenario":"<TOML>","source":"f"} -> {"ok":true,"cmd":"inject","injected":[...],"faults":N}
//   {"cmd":"clear"}                                   -> {"ok":true,"cmd":"clear","cleared":N}
// Each may carry "target": "v3" (a vehicle's receivers) or "v3/gps2" (one);
// without it a command acts on every receiver.
// Anything else -> {"ok":false,"error":"..."}, and nothing changes.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace gnssemu::daemon {

/// What the commands act on (the daemon).
class ControlTarget {
public:
  virtual ~ControlTarget() = default;
  /// Append the status of the receivers target names ("" every one) as
  /// one JSON object (the status page's /api/status). Throws gnssemu::Error
  /// for a target that names no receiver.
  virtual void write_status(std::string& out, std::string_view target) = 0;
  /// Add the events of a scenario text (start times from now) to the
  /// receivers target names ("" those each event's own target names, else
  /// every one); returns one line per event added. Throws gnssemu::Error
  /// naming source:line, and then adds nothing.
  virtual std::vector<std::string> inject(std::string_view scenario, const std::string& source,
                                          std::string_view target) = 0;
  /// Remove every fault of the receivers target names ("" every one);
  /// returns how many there were. Throws gnssemu::Error for an unknown target.
  virtual std::size_t clear(std::string_view target) = 0;
  /// Faults held now (active or pending).
  virtual std::size_t fault_count() const = 0;
};

/// The reply line (no newline) to one request line. Never throws.
std::string handle_control_request(std::string_view request, ControlTarget& target) noexcept;

}  // namespace gnssemu::daemon

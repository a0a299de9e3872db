// SPDX-License-Identifier: Apache-2.0
#pragma once
// The control socket's commands (docs/daemon.md §Control socket). One JSON
// object per line in, one per line out:
//   {"cmd":"status"}                                  -> {"ok":true,"cmd":"status","status":{...}}
//   {"cmd":"inject","scenario":"<TOML>","source":"f"} -> {"ok":true,"cmd":"inject","injected":[...],"faults":N}
//   {"cmd":"clear"}                                   -> {"ok":true,"cmd":"clear","cleared":N}
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
  /// Append the status as one JSON object (the status page's /api/status).
  virtual void write_status(std::string& out) = 0;
  /// Add the events of a scenario text (start times from now); returns one
  /// line per event added. Throws gnssemu::Error naming source:line, and
  /// then adds nothing.
  virtual std::vector<std::string> inject(std::string_view scenario, const std::string& source) = 0;
  /// Remove every fault; returns how many there were.
  virtual std::size_t clear() = 0;
  /// Faults held now (active or pending).
  virtual std::size_t fault_count() const = 0;
};

/// The reply line (no newline) to one request line. Never throws.
std::string handle_control_request(std::string_view request, ControlTarget& target) noexcept;

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#pragma once
// FaultLog: when a fault event starts or ends (docs/daemon.md §Logs). The
// daemon hands it the fault stage's status after every epoch and logs one
// line per change: signal faults and port events alike, never per epoch.
// Plain class: no I/O; update() and end_all() allocate nothing.
#include <array>
#include <cstddef>
#include <span>
#include <string>

#include "core/faults/fault_event.hpp"
#include "core/faults/fault_stage.hpp"

namespace gnssemu::daemon {

/// One event's change: it became active, or it stopped being active.
struct FaultTransition {
  std::size_t index = 0;  ///< in the status list it was seen in
  bool started = false;   ///< true: became active; false: ended
};

class FaultLog {
public:
  static constexpr std::size_t kMaxEvents = faults::FaultStage::kMaxEvents;

  /// Compare the stage's status after an epoch (FaultStage::status()) with
  /// the last one: the events that became active and those that ended, in
  /// list order. An entry whose event is another than before (the list was
  /// replaced without end_all) counts as a new event. Entries past
  /// kMaxEvents are ignored. No allocation.
  std::span<const FaultTransition> update(std::span<const faults::FaultStatus> status) noexcept;
  /// Every event active at the last update ends now (the list is about to
  /// be cleared or replaced; describe them from the status still held):
  /// their transitions; the next update starts from nothing active.
  std::span<const FaultTransition> end_all() noexcept;

private:
  std::array<const faults::FaultEvent*, kMaxEvents> event_{};  ///< identity of entry i at the last update
  std::array<bool, kMaxEvents> active_{};
  std::size_t n_ = 0;
  std::array<FaultTransition, kMaxEvents> out_{};
};

/// One line naming an event for the log: its type, string key and every
/// given parameter, a ramp as from→to ("jammer kind=cw js_db=20→50"), its
/// duration when it has one ("for 20.0 s") and, for a port event, the
/// output it acts on by name ("on gps0", "on every output"). output_names:
/// the [[output]] names in order. Allocates (transitions only).
std::string fault_log_text(const faults::FaultEvent& e, std::span<const std::string> output_names);

}  // namespace gnssemu::daemon

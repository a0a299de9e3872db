// SPDX-License-Identifier: Apache-2.0
#pragma once
// DelayLine: a port's epochs and replies held back by a latency link fault
// (docs/faults.md), released in the order they were sent: nothing leaves
// before what was sent before it, so a latency that ramps down bunches
// epochs up instead of reordering them, and a reply waits behind the epochs
// already on the line.
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gnssemu::daemon {

class DelayLine {
public:
  /// One held epoch or reply: its bytes, where each message ends, when it is due.
  struct Entry {
    double due_s = 0.0;               ///< monotonic clock, s
    std::string bytes;
    std::vector<std::size_t> ends;    ///< empty for a reply (sent whole)
    bool reply = false;               ///< a reply to source, not an epoch for every reader
    int source = 0;                   ///< the input source (tcp client) a reply goes to
  };

  /// Hold bytes (message ends in ends) until due_s, or until the epoch held
  /// before it is due if that is later. Allocates only when more epochs are
  /// held at once than ever before (each slot keeps its capacity).
  void push(double due_s, std::string_view bytes, std::span<const std::size_t> ends);
  /// Hold a reply to source until due_s, or behind what is held before it.
  void push_reply(double due_s, int source, std::string_view bytes);

  bool empty() const noexcept { return count_ == 0; }
  std::size_t size() const noexcept { return count_; }
  /// When the oldest held epoch is due, s; +infinity when nothing is held.
  double next_due_s() const noexcept {
    return empty() ? std::numeric_limits<double>::infinity() : slots_[head_].due_s;
  }
  /// The oldest held epoch (not empty()).
  const Entry& front() const noexcept { return slots_[head_]; }
  /// Release the oldest held epoch (not empty()).
  void pop() noexcept;
  /// Forget every held epoch.
  void clear() noexcept { head_ = count_ = 0; }

private:
  /// The next free slot, due at due_s or when the entry before it is.
  Entry& next_slot(double due_s);
  std::vector<Entry> slots_;  ///< a ring: count_ entries from head_
  std::size_t head_ = 0;
  std::size_t count_ = 0;
  double last_due_s_ = -std::numeric_limits<double>::infinity();
};

}  // namespace gnssemu::daemon

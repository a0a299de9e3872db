// SPDX-License-Identifier: Apache-2.0
#pragma once
// Per-reason drop counters with a log rate limit: the first drop of a reason
// is logged at once, later ones at most once per interval per reason as a
// summary of how many there were (take_due, polled by a timer so a burst is
// reported within an interval even when no further packet arrives), and
// the per-reason totals at exit. Pure (caller passes time).
#include <array>
#include <cstdint>
#include <string>

#include "daemon/truth/truth_packet.hpp"

namespace gnssemu::daemon {

using DropCounts = std::array<uint64_t, kDropReasonCount>;

class DropStats {
public:
  /// interval_s: minimum spacing of log lines per reason, s (> 0).
  explicit DropStats(double interval_s = 5.0) noexcept;

  /// Count one drop at monotonic time now_s (s). Returns the number of drops
  /// the caller should report in a log line now (this one plus those
  /// suppressed since the last line), or 0 when a line is not due.
  uint64_t record(DropReason reason, double now_s) noexcept;

  /// The suppressed drops of every reason whose last line is interval_s or
  /// more before now_s (s), taken: the caller logs them as one summary.
  /// All zero when none is due.
  DropCounts take_due(double now_s) noexcept;

  uint64_t count(DropReason reason) const noexcept;
  uint64_t total() const noexcept;
  const DropCounts& totals() const noexcept { return total_; }
  double interval_s() const noexcept { return interval_s_; }

private:
  double interval_s_;
  DropCounts total_{};
  DropCounts pending_{};
  std::array<double, kDropReasonCount> last_log_s_{};
  std::array<bool, kDropReasonCount> logged_{};
};

/// "malformed_json 4999, bad_magic 3" (reasons with a count, in enum order); "" when all are 0.
std::string drop_counts_text(const DropCounts& counts);
/// Sum of counts.
uint64_t drop_counts_sum(const DropCounts& counts) noexcept;

}  // namespace gnssemu::daemon

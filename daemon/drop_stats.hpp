#pragma once
// Per-reason drop counters with a log rate limit: at most one line per reason
// per interval, carrying how many drops it stands for. Pure (caller passes time).
#include <array>
#include <cstdint>

#include "daemon/truth_packet.hpp"

namespace gnssemu::daemon {

class DropStats {
public:
  /// interval_s: minimum spacing of log lines per reason, s (> 0).
  explicit DropStats(double interval_s = 5.0) noexcept;

  /// Count one drop at monotonic time now_s (s). Returns the number of drops
  /// the caller should report in a log line now (this one plus those
  /// suppressed since the last line), or 0 when a line is not due.
  uint64_t record(DropReason reason, double now_s) noexcept;

  uint64_t count(DropReason reason) const noexcept;
  uint64_t total() const noexcept;

private:
  double interval_s_;
  std::array<uint64_t, kDropReasonCount> total_{};
  std::array<uint64_t, kDropReasonCount> pending_{};
  std::array<double, kDropReasonCount> last_log_s_{};
  std::array<bool, kDropReasonCount> logged_{};
};

}  // namespace gnssemu::daemon

#include "daemon/drop_stats.hpp"

namespace gnssemu::daemon {

DropStats::DropStats(double interval_s) noexcept : interval_s_(interval_s) {}

uint64_t DropStats::record(DropReason reason, double now_s) noexcept {
  const auto i = static_cast<std::size_t>(reason);
  if (i >= kDropReasonCount) return 0;
  ++total_[i];
  ++pending_[i];
  if (logged_[i] && now_s - last_log_s_[i] < interval_s_) return 0;
  logged_[i] = true;
  last_log_s_[i] = now_s;
  const uint64_t n = pending_[i];
  pending_[i] = 0;
  return n;
}

uint64_t DropStats::count(DropReason reason) const noexcept {
  const auto i = static_cast<std::size_t>(reason);
  return i < kDropReasonCount ? total_[i] : 0;
}

uint64_t DropStats::total() const noexcept {
  uint64_t n = 0;
  for (uint64_t c : total_) n += c;
  return n;
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#include "daemon/truth/drop_stats.hpp"

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

DropCounts DropStats::take_due(double now_s) noexcept {
  DropCounts due{};
  for (std::size_t i = 0; i < kDropReasonCount; ++i) {
    if (pending_[i] == 0 || now_s - last_log_s_[i] < interval_s_) continue;
    due[i] = pending_[i];
    pending_[i] = 0;
    last_log_s_[i] = now_s;
  }
  return due;
}

uint64_t DropStats::count(DropReason reason) const noexcept {
  const auto i = static_cast<std::size_t>(reason);
  return i < kDropReasonCount ? total_[i] : 0;
}

uint64_t DropStats::total() const noexcept { return drop_counts_sum(total_); }

std::string drop_counts_text(const DropCounts& counts) {
  std::string out;
  for (std::size_t i = 0; i < kDropReasonCount; ++i) {
    if (counts[i] == 0) continue;
    if (!out.empty()) out += ", ";
    out += drop_reason_name(static_cast<DropReason>(i));
    out += ' ';
    out += std::to_string(counts[i]);
  }
  return out;
}

uint64_t drop_counts_sum(const DropCounts& counts) noexcept {
  uint64_t n = 0;
  for (uint64_t c : counts) n += c;
  return n;
}

}  // namespace gnssemu::daemon

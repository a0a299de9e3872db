// SPDX-License-Identifier: Apache-2.0
#include "daemon/ports/tx_budget.hpp"

#include <algorithm>

namespace gnssemu::daemon {

void TxBudget::advance(double now_s) noexcept {
  if (!started_) {
    started_ = true;
    last_s_ = now_s;
    return;
  }
  const double dt = now_s - last_s_;
  if (dt > 0.0) {
    level_bytes_ = std::max(0.0, level_bytes_ - dt * line_bytes_per_s());
    last_s_ = now_s;
  }
}

bool TxBudget::admit(std::size_t n, double now_s) noexcept {
  if (!limited()) return true;
  advance(now_s);
  if (level_bytes_ + static_cast<double>(n) > static_cast<double>(capacity_bytes_)) return false;
  level_bytes_ += static_cast<double>(n);
  return true;
}

void TxBudget::set_baud(uint32_t baud_bps, double now_s) noexcept {
  advance(now_s);
  baud_bps_ = baud_bps;
  if (!limited()) level_bytes_ = 0.0;
}

}  // namespace gnssemu::daemon

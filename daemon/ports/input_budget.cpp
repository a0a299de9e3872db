// SPDX-License-Identifier: Apache-2.0
#include "daemon/ports/input_budget.hpp"

#include <algorithm>

namespace gnssemu::daemon {

namespace {
// A read's worth the bucket refills to before the next read (the ports read 1 kB at a time).
constexpr double kReadBytes = 1024.0;
}  // namespace

double InputBudget::spend(std::size_t n, double now_s) noexcept {
  if (!started_) {
    started_ = true;
    last_s_ = now_s;
  }
  const double dt = now_s - last_s_;
  if (dt > 0.0) {
    level_ = std::min(burst_, level_ + dt * rate_);
    last_s_ = now_s;
  }
  level_ -= static_cast<double>(n);
  if (level_ > 0.0) return 0.0;
  return (std::min(kReadBytes, burst_) - level_) / rate_;
}

}  // namespace gnssemu::daemon

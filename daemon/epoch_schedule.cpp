// SPDX-License-Identifier: Apache-2.0
#include "daemon/epoch_schedule.hpp"

#include <cmath>

namespace gnssemu::daemon {

int64_t epoch_deadline_ns(int64_t index, double rate_hz) noexcept {
  return std::llround(static_cast<double>(index) * 1e9 / rate_hz);
}

double epoch_offset_s(int64_t index, double rate_hz) noexcept {
  return static_cast<double>(index) / rate_hz;
}

ScheduleStep next_epoch(int64_t index, double rate_hz, int64_t now_ns) noexcept {
  ScheduleStep s{index + 1, 0};
  if (now_ns > epoch_deadline_ns(index + 2, rate_hz)) {
    // Newest epoch whose deadline has passed.
    int64_t due = static_cast<int64_t>(std::floor(static_cast<double>(now_ns) * rate_hz / 1e9));
    while (epoch_deadline_ns(due + 1, rate_hz) <= now_ns) ++due;
    while (due > index + 1 && epoch_deadline_ns(due, rate_hz) > now_ns) --due;
    s.next_index = due;
    s.skipped = due - (index + 1);
  }
  return s;
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Epoch deadline arithmetic on absolute times: epoch k is due at
// t0 + k / rate_hz, so timer jitter never accumulates into drift. Pure.
#include <cstdint>

namespace gnssemu::daemon {

/// Deadline of epoch index (>= 0) after t0, ns, for rate_hz (> 0).
int64_t epoch_deadline_ns(int64_t index, double rate_hz) noexcept;
/// Time of epoch index after the first one, s.
double epoch_offset_s(int64_t index, double rate_hz) noexcept;

struct ScheduleStep {
  int64_t next_index = 0;  ///< epoch to serve next
  int64_t skipped = 0;     ///< epochs skipped because the loop was late
};

/// Having served epoch index, choose the next one at monotonic time now_ns
/// (ns since t0). Normally index + 1; when now_ns is more than one period past
/// that epoch's deadline, skip to the newest epoch already due and count the
/// ones jumped over.
ScheduleStep next_epoch(int64_t index, double rate_hz, int64_t now_ns) noexcept;

}  // namespace gnssemu::daemon

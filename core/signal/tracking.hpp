// SPDX-License-Identifier: Apache-2.0
#pragma once
// Acquisition and tracking thresholds with hysteresis: a satellite is
// acquired once C/N0 >= acquire_dbhz and kept until C/N0 < lose_dbhz.
// Defaults are engineering values (reference atmosphere.md §4.1 ⚠; MITRE
// quotes 28.7 dB-Hz at the correlator for aviation acquisition).
#include <optional>

#include "core/common/range.hpp"
#include "core/common/violation.hpp"

namespace gnssemu::signal {

struct TrackingThresholds {
  double acquire_dbhz = 30.0;  ///< C/N0 needed to acquire, dB-Hz
  double lose_dbhz = 25.0;     ///< below this, lock is lost, dB-Hz (<= acquire_dbhz)
};

/// Valid values of TrackingThresholds' fields.
struct TrackingRanges {
  static constexpr Range acquire_dbhz{0.0, 60.0, "dB-Hz"};
  static constexpr Range lose_dbhz{0.0, 60.0, "dB-Hz"};
};

/// Hysteresis: lose_dbhz <= acquire_dbhz.
std::optional<Violation> check_hysteresis(const TrackingThresholds& t);

/// Throws gnssemu::Error unless both are in range and lose <= acquire.
void validate(const TrackingThresholds& t);

/// Next tracking state from the current one and this epoch's C/N0 (dB-Hz).
/// NaN C/N0 counts as no signal.
constexpr bool next_tracked(bool tracked, double cn0_dbhz, const TrackingThresholds& t) noexcept {
  return tracked ? cn0_dbhz >= t.lose_dbhz : cn0_dbhz >= t.acquire_dbhz;
}

/// Per-satellite tracking state with the time spent locked.
class TrackingState {
public:
  /// Advance by dt_s (s, >= 0) with this epoch's C/N0; returns tracked().
  bool update(double cn0_dbhz, double dt_s, const TrackingThresholds& t) noexcept {
    const bool now = next_tracked(tracked_, cn0_dbhz, t);
    lock_time_s_ = now && tracked_ ? lock_time_s_ + (dt_s > 0.0 ? dt_s : 0.0) : 0.0;
    tracked_ = now;
    return tracked_;
  }
  bool tracked() const noexcept { return tracked_; }
  /// Continuous lock time since acquisition, s.
  double lock_time_s() const noexcept { return lock_time_s_; }
  void reset() noexcept { tracked_ = false; lock_time_s_ = 0.0; }

private:
  bool tracked_ = false;
  double lock_time_s_ = 0.0;
};

}  // namespace gnssemu::signal

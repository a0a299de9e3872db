// SPDX-License-Identifier: Apache-2.0
#pragma once
// Mapping between the clocks the daemon juggles: wall time elapsed since
// start, GPS time of epochs (the clock runs on from its start, for days on
// end), and each simulator's sim_time_s. Pure functions and small value types.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/orbit/ephemeris.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::daemon {

/// The nav data's own first day: first toe + 1 h (every satellite has had
/// time to appear). GpsTime{} for an empty list.
time::GpsTime first_toe_plus_hour(const std::vector<orbit::Ephemeris>& ephemerides);

/// Start of the epoch clock for time.use_wall_clock_date: a u-blox receiver's
/// epochs sit on whole multiples of the measurement period in GPS time, so
/// the clock starts at the next whole GPS second after now.
struct WholeSecondStart {
  time::GpsTime start;  ///< now rounded up to a whole GPS second
  double wait_s = 0.0;  ///< start - now, s, in [0, 1)
};
WholeSecondStart whole_second_start(const time::GpsTime& now) noexcept;

/// GPS time of the first epoch: start when configured; else, with
/// wall_clock, now rounded up to a whole GPS second (today's date); else the
/// nav data's first toe + 1 h.
time::GpsTime run_start(const std::optional<time::GpsTime>& start, bool wall_clock,
                        const std::vector<orbit::Ephemeris>& ephemerides, const time::GpsTime& now);

/// Maps a simulator's sim_time_s to GPS time: gps = anchor_gps + (sim - anchor_sim).
/// Anchored on the first packet at its arrival time; re-anchored when the
/// mapped time drifts from the arrival time by more than threshold_s
/// (a simulator running slower or faster than real time, or restarted).
class SimClockMap {
public:
  explicit SimClockMap(double threshold_s = 0.2) noexcept : threshold_s_(threshold_s) {}

  struct Mapped {
    time::GpsTime t;
    bool reanchored = false;  ///< true when this call set a new anchor (also on the first call)
  };
  /// sim_time_s: packet's simulation time, s; arrival: its arrival, GPS time.
  Mapped map(double sim_time_s, const time::GpsTime& arrival) noexcept;
  /// Forget the anchor (next map() anchors anew).
  void reset() noexcept { anchored_ = false; }
  bool anchored() const noexcept { return anchored_; }
  /// Lockstep: fix the anchor so that sim_time_s maps to gps exactly.
  void anchor(double sim_time_s, const time::GpsTime& gps) noexcept;
  /// GPS time of sim_time_s under the current anchor (anchored() must be true).
  time::GpsTime to_gps(double sim_time_s) const noexcept { return anchor_gps_ + (sim_time_s - anchor_sim_s_); }

private:
  double threshold_s_;
  bool anchored_ = false;
  double anchor_sim_s_ = 0.0;
  time::GpsTime anchor_gps_;
};

}  // namespace gnssemu::daemon

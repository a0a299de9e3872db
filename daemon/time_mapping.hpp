#pragma once
// Mapping between the clocks the daemon juggles: wall time elapsed since
// start, GPS time of epochs (inside the nav file's coverage), and each
// simulator's sim_time_s. Pure functions and small value types.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/orbit/ephemeris.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::daemon {

/// GPS-time span the realtime clock runs over.
struct Coverage {
  time::GpsTime start;  ///< GPS time of elapsed 0
  double span_s = 0.0;  ///< wrap back to start after this long (s); <= 0: never wrap
};

/// Default coverage of a nav file: from the first toe + 1 h (every satellite
/// has had time to appear) to the last toe. Empty list -> span 0.
Coverage default_coverage(const std::vector<orbit::Ephemeris>& ephemerides);

/// Coverage starting at a configured start: runs to the last toe when that is
/// later than start + 1 h, else never wraps.
Coverage coverage_from(const time::GpsTime& start, const std::vector<orbit::Ephemeris>& ephemerides);

/// Start of the epoch clock for time.use_wall_clock_date: a u-blox receiver's
/// epochs sit on whole multiples of the measurement period in GPS time, so
/// the clock starts at the next whole GPS second after now.
struct WholeSecondStart {
  time::GpsTime start;  ///< now rounded up to a whole GPS second
  double wait_s = 0.0;  ///< start - now, s, in [0, 1)
};
WholeSecondStart whole_second_start(const time::GpsTime& now) noexcept;

struct EpochTime {
  time::GpsTime t;     ///< GPS time
  int64_t wraps = 0;   ///< how often the clock has wrapped back to coverage.start
};

/// GPS time elapsed_s (s, >= 0) after coverage.start, wrapping back to the
/// start every span_s.
EpochTime realtime_gps_time(const Coverage& coverage, double elapsed_s) noexcept;

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

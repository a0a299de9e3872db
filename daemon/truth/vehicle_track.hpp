// SPDX-License-Identifier: Apache-2.0
#pragma once
// VehicleTrack: what the truth input knows of one vehicle — its recent
// samples (world::TruthTrack, live rule: brief extrapolation, then hold),
// the ordering of its simulation time, and when its last packet arrived:
// "no truth" once packets stop for longer than the timeout (a receiver that
// lost its antenna, never a frozen position). Fixed memory; no allocation.
#include <cstddef>
#include <optional>

#include "core/common/vec3.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/truth.hpp"
#include "core/world/truth_track.hpp"

namespace gnssemu::daemon {

struct TrackParams {
  double timeout_s = 2.0;            ///< no packet for longer than this (s, monotonic) -> invalid truth
  double max_extrapolation_s = 0.5;  ///< extrapolate at most this far (s) past the newest sample
};

class VehicleTrack {
public:
  /// Highest truth rate handled, Hz (docs/truth-protocol.md).
  static constexpr double kMaxRateHz = 1000.0;
  /// Samples kept: at least 1 s at kMaxRateHz (a few epochs back at 10 Hz
  /// and the whole extrapolation span); ~80 kB per vehicle, allocated once.
  static constexpr std::size_t kHistory = 1024;
  static_assert(static_cast<double>(kHistory) >= kMaxRateHz * 1.0);
  /// Packets without velocity less than this apart (s) get a velocity from the
  /// position difference over at least this baseline, not over the last
  /// segment: at 1 kHz a 1 ms difference turns 1 mm of position noise into
  /// 1 m/s. Slower senders (>= 20 Hz spacing) keep the segment velocity.
  static constexpr double kVelocityBaselineS = 0.05;

  /// A step between consecutive samples this long (m) or more at this speed
  /// (m/s) or more is a jump, not motion: faster than any orbit (7.8 km/s)
  /// and too long for a sender's noise. Kept as sent (the receivers lose
  /// lock and reacquire, as a real one carried off would); the caller logs it.
  static constexpr double kJumpMinStepM = 1000.0;
  static constexpr double kJumpMinSpeedMS = 10000.0;
  /// The step the last accepted add() made from the sample before it.
  struct Step {
    double distance_m = 0.0;  ///< 0: the first sample, or the history restarted
    double dt_s = 0.0;        ///< GPS stamp difference, s
    bool jump() const noexcept { return distance_m >= kJumpMinStepM && distance_m >= kJumpMinSpeedMS * dt_s; }
  };

  enum class AddResult {
    kAdded,
    kSimTimeBackwards,  ///< sim_time_s not increasing: dropped
    kRestarted,         ///< stamp not after the newest one (clock re-anchored): history restarted
  };

  VehicleTrack() : track_(kHistory) {}

  /// Add a sample with simulation time sim_time_s (s), GPS stamp t, ECEF
  /// position (m) and optional velocity (m/s), received at arrival_s
  /// (monotonic s, the clock later passed as now_s).
  AddResult add(double sim_time_s, const time::GpsTime& t, const Ecef& pos_m,
                const std::optional<Ecef>& vel_m_s, double arrival_s) noexcept;

  /// Forget the samples (keeps sim-time ordering and arrival time), e.g. when
  /// the epoch clock wraps back to the start of the nav file's coverage.
  void clear_samples() noexcept { track_.clear(); }
  /// Forget everything, as for a vehicle never seen (e.g. a simulator restarting its clock).
  void reset() noexcept {
    track_.clear();
    last_sim_time_s_.reset();
  }

  /// Truth at GPS time t, judged at monotonic time now_s (s): the live rule
  /// of world::TruthTrack with params.max_extrapolation_s; invalid when
  /// timed out.
  world::Truth truth_at(const time::GpsTime& t, double now_s, const TrackParams& params) const noexcept;

  /// A packet arrived within timeout_s of now_s.
  bool fresh(double now_s, const TrackParams& params) const noexcept;

  std::size_t size() const noexcept { return track_.size(); }
  /// k = 0 oldest ... size()-1 newest.
  const world::TruthSample& sample(std::size_t k) const noexcept { return track_.sample(k); }
  const world::TruthSample& newest() const noexcept { return track_.newest(); }
  double last_arrival_s() const noexcept { return last_arrival_s_; }
  const Step& last_step() const noexcept { return last_step_; }
  std::optional<double> last_sim_time_s() const noexcept { return last_sim_time_s_; }

private:
  world::TruthTrack track_;
  std::optional<double> last_sim_time_s_;
  double last_arrival_s_ = 0.0;
  Step last_step_;
};

}  // namespace gnssemu::daemon

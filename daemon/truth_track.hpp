#pragma once
// TruthTrack: the recent truth of one vehicle, and truth at any epoch time by
// linear interpolation, brief extrapolation beyond the newest sample, and
// "no truth" once packets stop for longer than the timeout (a receiver that
// lost its antenna, never a frozen position). Fixed memory; no allocation.
#include <array>
#include <cstddef>
#include <optional>

#include "core/common/vec3.hpp"
#include "core/world/truth.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::daemon {

struct TrackParams {
  double timeout_s = 2.0;            ///< no packet for longer than this (s, monotonic) -> invalid truth
  double max_extrapolation_s = 0.5;  ///< extrapolate at most this far (s) past the newest sample
};

class TruthTrack {
public:
  static constexpr std::size_t kHistory = 32;

  enum class AddResult {
    kAdded,
    kSimTimeBackwards,  ///< sim_time_s not increasing: dropped
    kRestarted,         ///< stamp not after the newest one (clock re-anchored): history restarted
  };

  struct Sample {
    time::GpsTime t;      ///< stamp, GPS time
    Ecef pos_m;           ///< ECEF m
    Ecef vel_m_s;         ///< ECEF m/s (valid when has_vel)
    bool has_vel = false;
  };

  /// Add a sample with simulation time sim_time_s (s), GPS stamp t, ECEF
  /// position (m) and optional velocity (m/s), received at arrival_s
  /// (monotonic s, the clock later passed as now_s).
  AddResult add(double sim_time_s, const time::GpsTime& t, const Ecef& pos_m,
                const std::optional<Ecef>& vel_m_s, double arrival_s) noexcept;

  /// Forget the samples (keeps sim-time ordering and arrival time), e.g. when
  /// the epoch clock wraps back to the start of the nav file's coverage.
  void clear_samples() noexcept { count_ = 0; }
  /// Forget everything, as for a vehicle never seen (e.g. a simulator restarting its clock).
  void reset() noexcept {
    count_ = 0;
    last_sim_time_s_.reset();
  }

  /// Truth at GPS time t, judged at monotonic time now_s (s). Invalid when
  /// empty, timed out, or t is more than max_extrapolation_s before the oldest sample.
  /// Past the newest sample, extrapolation stops at max_extrapolation_s; then
  /// the position is held there with zero velocity until the timeout.
  world::Truth truth_at(const time::GpsTime& t, double now_s, const TrackParams& params) const noexcept;

  /// A packet arrived within timeout_s of now_s.
  bool fresh(double now_s, const TrackParams& params) const noexcept;

  std::size_t size() const noexcept { return count_; }
  /// k = 0 oldest ... size()-1 newest.
  const Sample& sample(std::size_t k) const noexcept { return ring_[(head_ + k) % kHistory]; }
  const Sample& newest() const noexcept { return sample(count_ - 1); }
  double last_arrival_s() const noexcept { return last_arrival_s_; }
  std::optional<double> last_sim_time_s() const noexcept { return last_sim_time_s_; }

private:
  Ecef velocity_at_end(bool newest_end) const noexcept;

  std::array<Sample, kHistory> ring_{};
  std::size_t head_ = 0;
  std::size_t count_ = 0;
  std::optional<double> last_sim_time_s_;
  double last_arrival_s_ = 0.0;
};

}  // namespace gnssemu::daemon

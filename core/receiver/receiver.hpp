#pragma once
// Receiver: the emulated receiver's own processing of the world's
// observables at one epoch (DESIGN.md §1, steps 7-9): tracking with
// acquire / lose hysteresis and the channel limit, its own broadcast
// corrections, weighted least squares with fault exclusion, DOP, accuracy
// and fix state. It never sees the world's models or the truth. Pure and
// deterministic; no exceptions and no allocation on step() after construction.
#include <array>
#include <cstdint>

#include "core/orbit/nav_data.hpp"
#include "core/receiver/fix.hpp"
#include "core/receiver/receiver_config.hpp"
#include "core/receiver/solver.hpp"
#include "core/signal/tracking.hpp"
#include "core/world/observables.hpp"

namespace gnssemu::receiver {

class Receiver {
public:
  /// Throws gnssemu::Error on an invalid config.
  explicit Receiver(const ReceiverConfig& config);

  /// Process the observables of the epoch at receive time t (GPS). Without
  /// an antenna (obs.antenna_connected false) the epoch has no fix (time
  /// still advances, satellites drop out).
  const Fix& step(const time::GpsTime& t, const world::Observables& obs) noexcept;

  const Fix& last_fix() const noexcept { return fix_; }
  const ReceiverConfig& config() const noexcept { return config_; }

  /// GPS - UTC to report (e.g. the nav header's LEAP SECONDS); without it
  /// the built-in table (time::leap_seconds_at) is used.
  void set_leap_seconds(int leap_s) noexcept {
    leap_override_ = true;
    leap_s_ = leap_s;
  }

  /// Broadcast Klobuchar coefficients of the nav header (RINEX 2 ION
  /// ALPHA/BETA, RINEX 3 GPSA/GPSB) for the receiver's ionospheric
  /// correction; invalid: RTKLIB's default coefficients (the state after
  /// construction). Throws gnssemu::Error for non-finite values.
  void set_klobuchar(const orbit::KlobucharParams& p);

private:
  /// Acquisition / loss with hysteresis, then the channel limit (highest
  /// elevations first): tracked_.
  void tracking_stage(const world::Observables& obs, double dt_s) noexcept;
  /// fix_.sats from every satellite in view and the solver's measurements
  /// from the tracked ones.
  void measurement_stage(const world::Observables& obs) noexcept;
  void no_fix_epoch() noexcept;
  void fill_solution() noexcept;

  ReceiverConfig config_;
  Fix fix_;

  // Tracking.
  std::array<signal::TrackingState, kMaxGpsPrn> tracking_{};
  std::array<bool, kMaxGpsPrn> tracked_{};
  std::array<double, kMaxGpsPrn> el_rad_{};  ///< elevation per PRN this epoch (channel priority)
  bool started_ = false;
  time::GpsTime t_prev_;

  SpoofMonitor spoof_;

  // Solution.
  Solver solver_;
  SolverInput in_;
  SolverOutput out_;
  std::array<int, kMaxGpsPrn> meas_prn_{};  ///< PRN of each solver measurement
  bool time_valid_ = false;
  bool have_fix_ = false;
  time::GpsTime last_fix_t_;
  Ecef last_pos_m_, last_vel_m_s_;
  double last_clock_m_ = 0.0, last_drift_m_s_ = 0.0;
  bool have_3d_ = false;
  Ecef held_pos_m_;
  double held_height_m_ = 0.0;
  bool leap_override_ = false;
  int leap_s_ = 18;
};

}  // namespace gnssemu::receiver

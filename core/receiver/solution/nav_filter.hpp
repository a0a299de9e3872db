// SPDX-License-Identifier: Apache-2.0
#pragma once
// Navigation Kalman filter: ECEF position and velocity, clock bias and drift
// (8 states, constant-velocity motion with white acceleration, a two-state
// clock), updated one scalar measurement at a time with the receiver's
// pseudoranges and range rates. The motion noise comes from the dynamic
// model (dynamic_model.hpp), the clock noise from the oscillator's Allan
// parameters. Brown & Hwang, Introduction to Random Signals and Applied
// Kalman Filtering, 4th ed., ch. 9 (PV model, two-state clock). No allocation.
#include <array>
#include <cstdint>

#include "core/common/range.hpp"
#include "core/common/vec3.hpp"
#include "core/receiver/solution/dynamic_model.hpp"

namespace gnssemu::receiver {

/// The receiver's position processing.
enum class NavFilterType : std::uint8_t {
  kNone,    ///< snapshot weighted least squares on raw code every epoch
  kKalman,  ///< carrier-smoothed code and Doppler into the navigation filter
};

/// How the receiver's outputs flag a coasted (extrapolated) solution.
enum class CoastReport : std::uint8_t {
  /// Extrapolated but flagged "no fix": NAV-PVT fixType 0 with the
  /// extrapolated position, gnssFixOK 0; NMEA invalid. u-blox's documented
  /// behaviour for receivers without sensors (ANTARIS 4 System Integration
  /// Manual §4.6.5.2 "Dead Reckoning / extrapolating positioning"; the M8's
  /// CFG-NAV5 drLimit is reserved, fixType 1 is for its ADR/UDR products).
  kNoFix,
  /// Flagged as dead reckoning: fixType 1, GGA quality 6, mode E.
  kDeadReckoning,
};

struct NavFilterConfig {
  NavFilterType type = NavFilterType::kKalman;
  DynamicModel dynamic_model = DynamicModel::kPortable;  ///< CFG-NAV5 dynModel
  /// Carrier smoothing window of the code, s (>= 0; 0: raw code, as a u-blox
  /// M8 navigates: its NAV-SAT / NAV-SVINFO never flag a smoothed pseudorange).
  double smoothing_window_s = 0.0;
  /// Static hold (CFG-NAV5 staticHoldThresh): below this speed the reported
  /// position is frozen and the velocity reported 0, m/s (>= 0; 0 off).
  double static_hold_speed_m_s = 0.0;
  /// Static hold ends once the position moved this far from the held one,
  /// m (>= 0; 0: speed only; CFG-NAV5 staticHoldMaxDist).
  double static_hold_max_dist_m = 0.0;
  /// Random-walk position noise of the filter, m^2/s (>= 0): how much
  /// unmodelled change of the measured position (slowly drifting errors) it
  /// follows; with carrier-smoothed code it sets the epoch-to-epoch wander.
  double position_noise_m2_s = 0.02;
  /// Fewer than 3 usable satellites: the filter predicts (reporting a
  /// growing accuracy) for this long, then the fix is lost, s (>= 0).
  double coast_limit_s = 3.0;
  CoastReport coast_report = CoastReport::kNoFix;
  /// Oscillator: white frequency noise h0 (s) and random-walk frequency
  /// noise h-2 (1/s) of its Allan variance; a TCXO by default (Brown & Hwang,
  /// typical Allan coefficients of ch. 9).
  double clock_h0_s = 2.0e-19;
  double clock_h_minus2_per_s = 2.0e-20;
  /// A measurement whose innovation exceeds this many sigma is not used, (> 0).
  double innovation_gate_sigma = 5.0;
  /// The snapshot solution this far (m) beyond 5 sigma of the filter's
  /// prediction restarts the filter from it (the antenna was moved, or the
  /// filter went wrong).
  double reinit_margin_m = 30.0;
};

/// Valid values of NavFilterConfig's numbers.
struct NavFilterRanges {
  static constexpr Range smoothing_window_s{0.0, 3600.0, "s"};
  static constexpr Range static_hold_speed_m_s{0.0, 2.55, "m/s"};  ///< staticHoldThresh is U1 cm/s
  static constexpr Range static_hold_max_dist_m{0.0, 65535.0, "m"};
  static constexpr Range position_noise_m2_s{0.0, 100.0, "m^2/s"};
  static constexpr Range coast_limit_s{0.0, 600.0, "s"};
  static constexpr Range clock_h0_s{0.0, 1.0e-15, "s"};
  static constexpr Range clock_h_minus2_per_s{0.0, 1.0e-15, "1/s"};
  static constexpr Range innovation_gate_sigma{0.0, 100.0, "", true};
  static constexpr Range reinit_margin_m{0.0, 1.0e6, "m"};
};

/// Throws gnssemu::Error for a value out of its range.
void validate(const NavFilterConfig& c);

/// State order: x, y, z (m), vx, vy, vz (m/s), c x bias (m), c x drift (m/s).
inline constexpr int kNavStates = 8;
using NavVector = std::array<double, kNavStates>;
using NavMatrix = std::array<NavVector, kNavStates>;

class NavFilter {
public:
  /// Start at a solution: position and velocity (ECEF), clock (m, m/s), and
  /// the variances of each (m^2, m^2/s^2; per axis for position and velocity).
  void init(const Ecef& pos_m, const Ecef& vel_m_s, double clock_m, double drift_m_s, double pos_var_m2,
            double vel_var_m2_s2, double clock_var_m2, double drift_var_m2_s2) noexcept;
  void reset() noexcept { initialised_ = false; }
  bool initialised() const noexcept { return initialised_; }

  /// Propagate by dt_s (s, >= 0): white acceleration of PSD q_h / q_v
  /// (m^2/s^3) along the local horizontal / vertical at the current
  /// position, a position random walk of PSD q_pos (m^2/s) on every axis;
  /// clock with phase and frequency PSDs sf (m^2/s) and sg (m^2/s^3);
  /// zero_velocity: the velocity is held at 0.
  void predict(double dt_s, double q_h, double q_v, double q_pos, double sf, double sg, bool zero_velocity) noexcept;

  /// Scalar update z - h.x = innovation_m with variance r; returns false (and
  /// changes nothing) when |innovation| exceeds gate_sigma x sqrt(h P h' + r).
  bool update(const NavVector& h, double innovation, double r, double gate_sigma) noexcept;

  /// h P h': the variance of the linear combination h of the states.
  double variance_of(const NavVector& h) const noexcept;
  /// Add var_m2 to the variance of each position axis and of the clock bias
  /// (the prediction is in doubt).
  void widen_position(double var_m2) noexcept;

  /// Add a common offset to the clock bias (a millisecond clock step) and
  /// var_m2 to its variance.
  void shift_clock(double offset_m, double var_m2) noexcept;

  Ecef pos_m() const noexcept { return {x_[0], x_[1], x_[2]}; }
  Ecef vel_m_s() const noexcept { return {x_[3], x_[4], x_[5]}; }
  double clock_m() const noexcept { return x_[6]; }
  double drift_m_s() const noexcept { return x_[7]; }
  const NavMatrix& covariance() const noexcept { return p_; }
  /// Velocity set to 0 with variance var (the stationary model).
  void hold_velocity(double var_m2_s2) noexcept;

private:
  NavVector x_{};
  NavMatrix p_{};
  bool initialised_ = false;
};

/// Phase and frequency PSDs of a two-state clock model from Allan parameters
/// h0 and h-2, in range units: sf = c^2 h0 / 2 (m^2/s), sg = c^2 2 pi^2 h-2
/// (m^2/s^3) (Brown & Hwang, ch. 9).
double clock_phase_psd_m2_s(double h0_s) noexcept;
double clock_freq_psd_m2_s3(double h_minus2_per_s) noexcept;

}  // namespace gnssemu::receiver

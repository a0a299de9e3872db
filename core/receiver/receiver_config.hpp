#pragma once
// ReceiverConfig: error model and solver settings. All values SI.
#include <cstdint>

#include "core/common/constants.hpp"

namespace gnssemu::receiver {

/// First-order Gauss–Markov process: steady-state sigma and correlation time.
struct GaussMarkovConfig {
  double sigma_m = 0.0;     ///< steady-state 1-sigma, m (>= 0; 0 disables)
  double tau_s = 1800.0;    ///< correlation time, s (> 0)
};

struct ErrorModelConfig {
  double thermal_sigma_m = 0.3;                  ///< white pseudorange noise, m
  GaussMarkovConfig orbit_clock{1.2, 1800.0};    ///< broadcast orbit/clock residual per satellite
  double doppler_sigma_m_s = 0.03;               ///< white range-rate noise, m/s
};

struct ClockConfig {
  double bias_s = 1.0e-4;            ///< initial receiver clock bias, s
  double drift_s_s = 5.0e-8;         ///< initial clock drift, s/s (TCXO-like)
  double drift_noise_s_s_sqrt_s = 1.0e-10;  ///< drift random walk density, s/s/sqrt(s)
  /// |bias| above this makes the receiver step its clock by a whole multiple of
  /// it (millisecond jumps of unsteered receivers), s; 0 disables.
  double jump_threshold_s = 1.0e-3;
};

/// What the receiver's own solver assumes (it does not know the world model).
struct SolverConfig {
  /// Pseudorange 1-sigma model sigma^2 = a^2 + b^2 / sin^2(el), m (RTKLIB-style).
  double sigma_a_m = 1.2;
  double sigma_b_m = 0.3;
  double sigma_range_rate_m_s = 0.05;  ///< Doppler range-rate 1-sigma, m/s
  double height_hold_sigma_m = 1.0;    ///< 1-sigma of the held height in 2D fixes, m
  /// False-alarm probability of the chi-square test on post-fit residuals
  /// (fails -> no fix); 0 disables the test.
  double residual_test_pfa = 1.0e-3;
  int max_iterations = 15;             ///< Gauss–Newton iterations at most
};

struct ReceiverConfig {
  double elevation_mask_rad = 5.0 * kDegToRad;  ///< [0, pi/2)
  uint64_t seed = 1;                            ///< error-process seed (deterministic)
  ErrorModelConfig errors;
  ClockConfig clock;
  double nominal_cn0_dbhz = 45.0;  ///< placeholder C/N0 until the signal module (issue 3)
  double max_pdop = 20.0;          ///< above this the fix is reported as none
  int max_channels = 16;           ///< satellites tracked at most (highest first)
  SolverConfig solver;
};

}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
#pragma once
// World-side error processes: first-order Gauss–Markov residuals and the
// receiver's free-running clock. Pure functions of their inputs and a
// standard-normal draw supplied by the caller (random.hpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "core/common/constants.hpp"
#include "core/world/world_config.hpp"

namespace gnssemu::world {

/// The multipath residual scales as sigma_m / sin(el), el held at >= 5 deg
/// (WorldConfig::errors.multipath: sigma_m is the zenith value): that sine.
inline double multipath_sin_el(double el_rad) noexcept {
  constexpr double kMinEl_rad = 5.0 * kDegToRad;
  return std::sin(std::max(el_rad, kMinEl_rad));
}

/// Global RMS signal-in-space range error of each system's broadcast orbits
/// and clocks, m (Montenbruck, Steigenberger & Hauschild, "Multi-GNSS
/// signal-in-space range error assessment", Adv. Space Res. 61(12), 2018:
/// Galileo 0.2, GPS 0.6, BeiDou-2 1, GLONASS 2 m over 2017; QZSS and SBAS
/// taken as GPS). In the order of the system table.
inline constexpr std::array<double, kNumSystems> kSystemSisre_m{0.6, 2.0, 0.2, 1.0, 0.6, 0.6};

/// The orbit/clock residual process of a satellite of system sys. The
/// configured (GPS) sigma is what the station fits put into this process:
/// GPS's SISRE and the rest of the per-satellite residual the other terms do
/// not carry (code, unmodelled atmosphere). Only the SISRE share changes with
/// the system: sigma^2 = rest^2 + SISRE_sys^2 with rest^2 = sigma_gps^2 -
/// SISRE_gps^2 (a fitted sigma below GPS's SISRE is all SISRE and scales
/// with the ratio). Scaling the whole fitted sigma made GLONASS 4 m and
/// Galileo 0.4 m at the default 1.2 m, and the receiver's residual test,
/// which passes on real four-system days, failed every other simulated
/// epoch. The correlation time is kept.
inline GaussMarkovConfig orbit_clock_process(const GaussMarkovConfig& gps, GnssSystem sys) noexcept {
  const double sisre_gps_m = kSystemSisre_m[0];
  const double ratio = kSystemSisre_m[static_cast<std::size_t>(sys)] / sisre_gps_m;
  if (ratio == 1.0 || !(gps.sigma_m > 0.0)) return gps;
  const double sis_m = std::min(gps.sigma_m, sisre_gps_m);
  const double rest2 = gps.sigma_m * gps.sigma_m - sis_m * sis_m;
  return GaussMarkovConfig{std::sqrt(rest2 + sis_m * sis_m * ratio * ratio), gps.tau_s};
}

/// Stationary start of a Gauss–Markov process: sigma_m * w, w ~ N(0, 1).
inline double gauss_markov_init(const GaussMarkovConfig& cfg, double w) noexcept {
  return cfg.sigma_m > 0.0 ? cfg.sigma_m * w : 0.0;
}

/// One exact step of dx/dt = -x/tau + noise over dt_s seconds:
/// x_k = phi x_{k-1} + sigma sqrt(1 - phi^2) w, phi = exp(-dt/tau)
/// (exact discretisation, e.g. Brown & Hwang, Introduction to Random Signals
/// and Applied Kalman Filtering, 4th ed., §2.9). dt_s <= 0 holds the value.
inline double gauss_markov_step(double x, double dt_s, const GaussMarkovConfig& cfg, double w) noexcept {
  if (!(cfg.sigma_m > 0.0)) return 0.0;
  if (!(dt_s > 0.0)) return x;
  const double phi = std::exp(-dt_s / cfg.tau_s);
  return phi * x + cfg.sigma_m * std::sqrt(1.0 - phi * phi) * w;
}

/// Free-running receiver oscillator: drift is a random walk, bias its
/// integral; the receiver steps its clock by whole jump_threshold_s multiples
/// once |bias| exceeds it (as unsteered receivers do with 1 ms jumps).
class ReceiverClock {
public:
  explicit ReceiverClock(const ClockConfig& cfg) noexcept
      : cfg_(cfg), bias_s_(cfg.bias_s), drift_s_s_(cfg.drift_s_s) {}

  /// Advance by dt_s seconds (<= 0: no change); w ~ N(0, 1) drives the drift walk.
  void advance(double dt_s, double w) noexcept {
    if (!(dt_s > 0.0)) return;
    const double drift_new = drift_s_s_ + cfg_.drift_noise_s_s_sqrt_s * std::sqrt(dt_s) * w;
    bias_s_ += 0.5 * (drift_s_s_ + drift_new) * dt_s;  // trapezoid
    drift_s_s_ = drift_new;
    const double j = cfg_.jump_threshold_s;
    if (j > 0.0 && std::fabs(bias_s_) > j) bias_s_ -= j * std::trunc(bias_s_ / j);
  }

  double bias_s() const noexcept { return bias_s_; }
  double drift_s_s() const noexcept { return drift_s_s_; }

private:
  ClockConfig cfg_;
  double bias_s_;
  double drift_s_s_;
};

}  // namespace gnssemu::world

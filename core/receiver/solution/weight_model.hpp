// SPDX-License-Identifier: Apache-2.0
#pragma once
// The solver's pseudorange variance (weights 1 / sigma^2): the configured
// WeightModel plus the variance of what the receiver's broadcast corrections
// miss. Shared by receiver::Solver and `gnssemu spp`, which applies the
// corrections before the solver. Pure, no allocation.
#include "core/receiver/receiver_config.hpp"

namespace gnssemu::receiver {

/// sin(el) floor of the weight model (about 2.9 deg): keeps weights finite at
/// and below the horizon.
inline constexpr double kMinSinEl = 0.05;

/// The broadcast URA as RTKLIB weights it: the upper bound of the URA index
/// interval that contains ura_m (IS-GPS-200 20.3.3.3.1.1: 2.4, 3.4, 4.85,
/// 6.85, 9.65, 13.65, 24, 48, ... 6144 m), 6144 m above the table or for a
/// non-finite value, m. ura_m: the navigation file's SV accuracy, m.
double ura_bound_m(double ura_m) noexcept;

/// Variance of the measurement itself, m^2, = elevation_variance_m2 +
/// satellite_variance_m2: kElevationCn0 a^2 + b^2 / s^2 + c^2 10^(-C/N0 / 10);
/// kRtklib a^2 + b^2 / s + ura_bound_m(ura_m)^2 + code_bias^2. sin_el: sine of
/// the elevation (held at >= kMinSinEl).
double measurement_variance_m2(const SolverConfig& cfg, double sin_el, double cn0_dbhz, double ura_m) noexcept;

/// The elevation part: a^2 + b^2 / s^2 (kRtklib: a^2 + b^2 / s), s = sin_el
/// held at >= kMinSinEl, m^2. Inline: the solver evaluates it per satellite
/// and iteration.
inline double elevation_variance_m2(const SolverConfig& cfg, double sin_el) noexcept {
  const double s = sin_el > kMinSinEl ? sin_el : kMinSinEl;
  const double a2 = cfg.sigma_a_m * cfg.sigma_a_m, b2 = cfg.sigma_b_m * cfg.sigma_b_m;
  return cfg.weights == WeightModel::kRtklib ? a2 + b2 / s : a2 + b2 / (s * s);
}

/// The part fixed for a satellite over an epoch, m^2: kElevationCn0 the
/// C/N0 term c^2 10^(-C/N0 / 10) (0 when cn0_dbhz <= 0 or not finite; C/N0
/// held at <= 70 dB-Hz); kRtklib ura_bound_m(ura_m)^2 + code_bias_sigma_m^2.
/// ura_m: the ephemeris' SV accuracy, m.
double satellite_variance_m2(const SolverConfig& cfg, double cn0_dbhz, double ura_m) noexcept;

/// satellite_variance_m2 for a satellite of system sys: kRtklib takes the
/// broadcast accuracy as RTKLIB 2.4.3 does per system (ephemeris.c
/// var_uraeph, rinex.c sisa_index): Galileo's SISA on its index grid (0.01 m
/// steps to 0.5 m, 0.02 m to 1 m, 0.04 m to 2 m, 0.16 m to 6 m; beyond: 500 m,
/// "no accuracy prediction"), GLONASS a fixed 5 m (ERREPH_GLO), the others the
/// URA bound. kElevationCn0 is the same for every system.
double satellite_variance_m2(const SolverConfig& cfg, double cn0_dbhz, double ura_m, GnssSystem sys) noexcept;

/// The broadcast orbit-and-clock sigma RTKLIB 2.4.3 assigns to a satellite of
/// system sys with the navigation file's accuracy ura_m (see above), m.
double rtklib_ephemeris_sigma_m(GnssSystem sys, double ura_m) noexcept;

/// Variance of what the receiver's corrections miss, m^2 (RTKLIB's ERR_BRDCI
/// and ERR_SAAS forms): (iono_model_fraction x iono_m)^2 when the
/// ionospheric correction is on, (tropo_model_sigma_m / (sin el + 0.1))^2
/// when the tropospheric one is. iono_m: the Klobuchar delay removed, m;
/// sin_el: sine of the elevation (negative held at 0).
double correction_variance_m2(const SolverConfig& cfg, double iono_m, double sin_el) noexcept;

}  // namespace gnssemu::receiver

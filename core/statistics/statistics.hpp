// SPDX-License-Identifier: Apache-2.0
#pragma once
// Descriptive statistics of sample series for the offline tools (batch
// summaries, calibration against a real receiver): mean, RMS, spread,
// percentiles and the statistics of a position-error series. They allocate
// and are never on the per-epoch path.
#include <span>
#include <vector>

#include "core/common/vec3.hpp"

namespace gnssemu::statistics {

/// Arithmetic mean of v; NaN when v is empty.
double mean(std::span<const double> v) noexcept;
/// Root mean square sqrt(sum x^2 / n); NaN when v is empty.
double rms(std::span<const double> v) noexcept;
/// Largest |x|; NaN when v is empty.
double max_abs(std::span<const double> v) noexcept;
/// Population variance about mean_v: sum (x - mean_v)^2 / n; NaN when v is empty.
double variance(std::span<const double> v, double mean_v) noexcept;
/// Population standard deviation about mean_v: sqrt(variance); NaN when v is empty.
double std_dev(std::span<const double> v, double mean_v) noexcept;

/// Nearest-rank percentile: the ceil(p n)-th smallest of v (p in (0, 1]; the
/// rank is held in [1, n]); NaN when v is empty.
double percentile_nearest_rank(std::vector<double> v, double p);
/// percentile_nearest_rank of values already sorted ascending; no copy, no
/// allocation (the per-epoch status figures).
double percentile_nearest_rank_sorted(std::span<const double> sorted, double p) noexcept;
/// Quantile q in [0, 1] interpolated linearly between the order statistics
/// around q (n - 1) (Hyndman & Fan 1996, definition 7); NaN when v is empty.
double quantile_linear(std::vector<double> v, double q);

/// Statistics of a position-error series (fix minus truth, local ENU, m).
struct PositionErrorStats {
  int n = 0;  ///< finite samples used
  double mean_e_m = 0.0, mean_n_m = 0.0, mean_u_m = 0.0;
  double sigma_e_m = 0.0, sigma_n_m = 0.0, sigma_u_m = 0.0;  ///< population standard deviations, m
  double cep50_m = 0.0, cep95_m = 0.0;  ///< 50 % / 95 % quantiles (quantile_linear) of hypot(e, n), m
  /// Lag at which the mean autocorrelation of e, n, u (each about its mean)
  /// first falls below 1/e, s (linear interpolation between lags); the span
  /// of the series when it never does.
  double corr_time_s = 0.0;
};

/// errors: one sample per step_s seconds (s > 0) of a regular grid; a
/// missing epoch is a non-finite sample (left out of every sum). All zero
/// when no sample is finite.
PositionErrorStats position_error_stats(const std::vector<Enu>& errors, double step_s);

}  // namespace gnssemu::statistics

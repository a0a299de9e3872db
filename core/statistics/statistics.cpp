// SPDX-License-Identifier: Apache-2.0
#include "core/statistics/statistics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace gnssemu::statistics {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double component(const Enu& d, int c) noexcept { return c == 0 ? d.x : c == 1 ? d.y : d.z; }

/// Mean normalised autocorrelation of the three components at lag 1, 2, ...
/// until it falls below 1/e; pairs with a non-finite sample are skipped.
double correlation_time_s(const std::vector<Enu>& errors, const std::array<double, 3>& mean,
                          const std::array<double, 3>& var, double step_s) {
  const std::size_t n = errors.size();
  double prev = 1.0;
  for (std::size_t k = 1; k < n; ++k) {
    double rho = 0.0;
    for (int c = 0; c < 3; ++c) {
      double acc = 0.0;
      int cnt = 0;
      for (std::size_t i = 0; i + k < n; ++i) {
        const Enu& a = errors[i];
        const Enu& b = errors[i + k];
        if (!a.finite() || !b.finite()) continue;
        acc += (component(a, c) - mean[c]) * (component(b, c) - mean[c]);
        ++cnt;
      }
      rho += cnt > 0 && var[c] > 0.0 ? acc / cnt / var[c] / 3.0 : 0.0;
    }
    const double target = std::exp(-1.0);
    if (rho < target) {
      const double frac = (prev - target) / (prev - rho);
      return (static_cast<double>(k - 1) + frac) * step_s;
    }
    prev = rho;
  }
  return static_cast<double>(n) * step_s;
}

}  // namespace

double mean(std::span<const double> v) noexcept {
  if (v.empty()) return kNaN;
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double rms(std::span<const double> v) noexcept {
  if (v.empty()) return kNaN;
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

double max_abs(std::span<const double> v) noexcept {
  if (v.empty()) return kNaN;
  double m = 0.0;
  for (double x : v) m = std::max(m, std::fabs(x));
  return m;
}

double variance(std::span<const double> v, double mean_v) noexcept {
  if (v.empty()) return kNaN;
  double s = 0.0;
  for (double x : v) s += (x - mean_v) * (x - mean_v);
  return s / static_cast<double>(v.size());
}

double std_dev(std::span<const double> v, double mean_v) noexcept { return std::sqrt(variance(v, mean_v)); }

double percentile_nearest_rank(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return percentile_nearest_rank_sorted(v, p);
}

double percentile_nearest_rank_sorted(std::span<const double> sorted, double p) noexcept {
  if (sorted.empty()) return kNaN;
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

double quantile_linear(std::vector<double> v, double q) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  const double frac = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1.0 - frac) + v[i + 1] * frac : v[i];
}

PositionErrorStats position_error_stats(const std::vector<Enu>& errors, double step_s) {
  PositionErrorStats s;
  std::array<std::vector<double>, 3> comp;
  std::vector<double> h;
  for (const Enu& d : errors) {
    if (!d.finite()) continue;
    for (int c = 0; c < 3; ++c) comp[static_cast<std::size_t>(c)].push_back(component(d, c));
    h.push_back(std::hypot(d.x, d.y));
  }
  s.n = static_cast<int>(h.size());
  if (s.n == 0) return s;
  std::array<double, 3> m{}, var{};
  for (std::size_t c = 0; c < 3; ++c) {
    m[c] = mean(comp[c]);
    var[c] = variance(comp[c], m[c]);
  }
  s.mean_e_m = m[0], s.mean_n_m = m[1], s.mean_u_m = m[2];
  s.sigma_e_m = std::sqrt(var[0]), s.sigma_n_m = std::sqrt(var[1]), s.sigma_u_m = std::sqrt(var[2]);
  s.cep50_m = quantile_linear(h, 0.5);
  s.cep95_m = quantile_linear(h, 0.95);
  s.corr_time_s = correlation_time_s(errors, m, var, step_s);
  return s;
}

}  // namespace gnssemu::statistics

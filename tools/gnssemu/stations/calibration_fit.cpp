// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/stations/calibration_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/atmosphere/ionosphere.hpp"
#include "core/common/constants.hpp"
#include "core/world/measurement/error_processes.hpp"

namespace gnssemu::cli {

namespace {

double multipath_factor(double el_rad) { return 1.0 / world::multipath_sin_el(el_rad); }

constexpr double kCommonMaxLag_s = 12.0 * 3600.0;        // common-term autocovariance lags
constexpr double kCommonMaxTau_s = 2.0 * 86400.0;        // longest common-term time scale fitted
constexpr int kMinSatsCommon = 6;                        // 3 terms + clock + 2 degrees of freedom

/// Solve the n x n system a x = b (Gaussian elimination, partial pivoting).
template <std::size_t N>
bool solve_linear(std::array<std::array<double, N>, N> a, std::array<double, N> b, std::array<double, N>& x) {
  for (std::size_t c = 0; c < N; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < N; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    if (!(std::fabs(a[p][c]) > 1e-300)) return false;
    std::swap(a[c], a[p]);
    std::swap(b[c], b[p]);
    for (std::size_t r = 0; r < N; ++r) {
      if (r == c) continue;
      const double f = a[r][c] / a[c][c];
      for (std::size_t k = c; k < N; ++k) a[r][k] -= f * a[c][k];
      b[r] -= f * b[c];
    }
  }
  for (std::size_t i = 0; i < N; ++i) x[i] = b[i] / a[i][i];
  return true;
}

/// Regressors of one residual for fit_atmosphere_bias: alpha, beta, G_N, G_E.
std::array<double, 4> bias_regressors(const Residual& r) {
  return {r.klobuchar_m, r.nmf_wet, std::cos(r.az_rad), std::sin(r.az_rad)};
}

/// Regressors of the per-epoch common terms: a_t, G_N,t, G_E,t.
std::array<double, 3> common_regressors(const Residual& r) {
  return {r.klobuchar_m, std::cos(r.az_rad), std::sin(r.az_rad)};
}


}  // namespace

NoiseFit fit_gauss_markov(const std::vector<double>& acov, double step_s, double max_tau_s) {
  NoiseFit f;
  if (acov.empty()) return f;
  const double c0 = std::max(acov[0], 0.0);
  double best_cost = std::numeric_limits<double>::infinity(), best_a = 0.0, best_tau = 0.0;
  const double ratio = std::max(max_tau_s, 60.0) / 30.0;
  for (int g = 0; g <= 400; ++g) {
    const double tau = 30.0 * std::pow(ratio, g / 400.0);
    double sbb = 0.0, sbc = 0.0;
    for (std::size_t k = 1; k < acov.size(); ++k) {
      const double b = std::exp(-static_cast<double>(k) * step_s / tau);
      sbb += b * b;
      sbc += b * acov[k];
    }
    if (sbb <= 0.0) continue;
    const double a = std::clamp(sbc / sbb, 0.0, c0);
    double cost = 0.0;
    for (std::size_t k = 1; k < acov.size(); ++k) {
      const double d = acov[k] - a * std::exp(-static_cast<double>(k) * step_s / tau);
      cost += d * d;
    }
    if (cost < best_cost) best_cost = cost, best_a = a, best_tau = tau;
  }
  f.gm_sigma_m = std::sqrt(best_a);
  f.gm_tau_s = best_tau;
  f.white_sigma_m = std::sqrt(std::max(c0 - best_a, 0.0));
  return f;
}

std::vector<double> pooled_autocovariance(const std::vector<Residual>& res, int max_lag) {
  std::map<SatId, std::map<int, double>> by_sat;  // satellite -> grid -> value
  for (const Residual& r : res) by_sat[r.sat][r.grid] = r.value_m;
  std::vector<double> sum(static_cast<std::size_t>(max_lag + 1), 0.0);
  std::vector<double> cnt(sum.size(), 0.0);
  for (const auto& [sat, series] : by_sat) {
    for (const auto& [g, v] : series) {
      for (int k = 0; k <= max_lag; ++k) {
        const auto it = series.find(g + k);
        if (it == series.end()) continue;
        sum[static_cast<std::size_t>(k)] += v * it->second;
        cnt[static_cast<std::size_t>(k)] += 1.0;
      }
    }
  }
  std::vector<double> acov;
  for (std::size_t k = 0; k < sum.size() && cnt[k] > 0.0; ++k) acov.push_back(sum[k] / cnt[k]);
  return acov;
}

AtmosphereBiasFit fit_atmosphere_bias(const std::vector<Residual>& res, bool with_zwd) {
  constexpr std::size_t kN = 4;
  using Vec = std::array<double, kN>;
  std::array<Vec, kN> a{};
  Vec b{};
  for (std::size_t i = 0; i < res.size();) {
    std::size_t j = i;
    Vec mx{};
    double mr = 0.0;
    for (; j < res.size() && res[j].grid == res[i].grid; ++j) {
      const Vec x = bias_regressors(res[j]);
      for (std::size_t p = 0; p < kN; ++p) mx[p] += x[p];
      mr += res[j].value_m;
    }
    const double n = static_cast<double>(j - i);
    for (double& v : mx) v /= n;
    mr /= n;
    for (std::size_t k = i; k < j; ++k) {
      Vec u = bias_regressors(res[k]);
      for (std::size_t p = 0; p < kN; ++p) u[p] -= mx[p];
      const double y = res[k].value_m - mr;
      for (std::size_t p = 0; p < kN; ++p) {
        b[p] += u[p] * y;
        for (std::size_t q = 0; q < kN; ++q) a[p][q] += u[p] * u[q];
      }
    }
    i = j;
  }
  AtmosphereBiasFit f;
  f.correlation = a[0][1] / std::sqrt(a[0][0] * a[1][1]);
  if (!with_zwd) {  // beta fixed at 0
    for (std::size_t p = 0; p < kN; ++p) a[1][p] = a[p][1] = 0.0;
    a[1][1] = 1.0;
    b[1] = 0.0;
  }
  Vec x{};
  if (!solve_linear(a, b, x)) return f;
  f.klobuchar_alpha = x[0];
  f.zwd_beta_m = x[1];
  f.gradient_north_m = x[2];
  f.gradient_east_m = x[3];
  return f;
}

std::vector<CommonEpoch> remove_common_terms(std::vector<Residual>& res, const AtmosphereBiasFit& b) {
  using Vec = std::array<double, 3>;
  using Mat = std::array<Vec, 3>;
  std::vector<CommonEpoch> out;
  for (std::size_t i = 0; i < res.size();) {
    std::size_t j = i;
    for (; j < res.size() && res[j].grid == res[i].grid; ++j) {
      Residual& r = res[j];
      r.value_m -= b.klobuchar_alpha * r.klobuchar_m + b.zwd_beta_m * r.nmf_wet +
                   b.gradient_north_m * std::cos(r.az_rad) + b.gradient_east_m * std::sin(r.az_rad);
    }
    const double n = static_cast<double>(j - i);
    Vec mx{};
    double mr = 0.0;
    for (std::size_t k = i; k < j; ++k) {
      const Vec u = common_regressors(res[k]);
      for (std::size_t p = 0; p < 3; ++p) mx[p] += u[p] / n;
      mr += res[k].value_m / n;
    }
    Mat a{};
    for (std::size_t k = i; k < j; ++k) {
      Vec u = common_regressors(res[k]);
      for (std::size_t p = 0; p < 3; ++p) u[p] -= mx[p];
      for (std::size_t p = 0; p < 3; ++p)
        for (std::size_t q = 0; q < 3; ++q) a[p][q] += u[p] * u[q];
    }
    // Inverse by columns; an epoch whose satellites cannot separate the
    // terms (all at one elevation or one side of the sky) keeps its residuals.
    Mat inv{};
    bool ok = static_cast<int>(j - i) >= kMinSatsCommon;
    for (std::size_t c = 0; c < 3 && ok; ++c) {
      Vec e{}, col{};
      e[c] = 1.0;
      ok = solve_linear(a, e, col);
      for (std::size_t r = 0; r < 3; ++r) inv[r][c] = col[r];
    }
    // Conditioning: each term's variance factor at most 100 x its scale's.
    for (std::size_t p = 0; p < 3 && ok; ++p) ok = std::isfinite(inv[p][p]) && inv[p][p] * a[p][p] < 100.0;
    if (ok) {
      CommonEpoch e;
      e.grid = res[i].grid;
      e.first = i, e.last = j;
      for (std::size_t k = i; k < j; ++k) {
        Vec u = common_regressors(res[k]);
        for (std::size_t p = 0; p < 3; ++p) u[p] -= mx[p];
        Vec w{};
        for (std::size_t p = 0; p < 3; ++p) w[p] = inv[p][0] * u[0] + inv[p][1] * u[1] + inv[p][2] * u[2];
        e.weights.push_back(w);
        for (std::size_t p = 0; p < 3; ++p) e.value[p] += w[p] * (res[k].value_m - mr);
      }
      for (std::size_t k = i; k < j; ++k) {
        const Vec u = common_regressors(res[k]);
        res[k].value_m -= e.value[0] * u[0] + e.value[1] * u[1] + e.value[2] * u[2];
      }
      out.push_back(std::move(e));
    }
    double m = 0.0;
    for (std::size_t k = i; k < j; ++k) m += res[k].value_m;
    m /= n;
    const double removed = ok ? 4.0 : 1.0;  // the epoch's parameters (mean already counted in the clock)
    const double inflate = n > removed ? std::sqrt((n - 1.0) / (n - removed)) : 1.0;
    for (std::size_t k = i; k < j; ++k) res[k].value_m = (res[k].value_m - m) * inflate;
    i = j;
  }
  return out;
}

ProcessFit fit_processes(const std::vector<Residual>& res, const signal::LinkBudgetConfig& link,
                         const signal::DllParams& dll, double step_s) {
  constexpr std::size_t kTerms = 4;  // white, multipath, orbit/clock, iono
  using Vec = std::array<double, kTerms>;
  using Mat = std::array<Vec, kTerms>;
  const signal::LinkBudgetModel budget(link);
  signal::DllParams unit = dll;
  unit.loop_bandwidth_hz = 1.0;
  const double m_per_tecu = atmosphere::iono_m_per_tecu(link.freq_hz);
  struct Row {
    double value_m, white_m2, mp, iono;
  };
  std::map<SatId, std::map<int, Row>> by_sat;  // satellite -> grid -> regressors (grids of days never meet)
  for (const Residual& r : res) {
    const double s = signal::dll_thermal_sigma_m(budget.cn0_dbhz(r.range_m, r.el_rad, 0.0), unit);
    by_sat[r.sat][r.grid] =
        Row{r.value_m, s * s, multipath_factor(r.el_rad), m_per_tecu * atmosphere::iono_obliquity_factor(r.el_rad)};
  }
  // Lags: every step to 10 min, then sparser to 4 h (long lags are many and alike).
  std::vector<int> lags;
  const int k10 = static_cast<int>(std::lround(600.0 / step_s));
  const int kmax = static_cast<int>(std::lround(4.0 * 3600.0 / step_s));
  for (int k = 0; k <= kmax; k += k < k10 ? 1 : std::max(1, k10 / 4)) lags.push_back(k);
  std::vector<Mat> a(lags.size(), Mat{});
  std::vector<Vec> b(lags.size(), Vec{});
  ProcessFit f;
  for (const auto& [sat, series] : by_sat) {
    for (const auto& [g, r1] : series) {
      for (std::size_t li = 0; li < lags.size(); ++li) {
        const auto it = series.find(g + lags[li]);
        if (it == series.end()) continue;
        const Row& r2 = it->second;
        const Vec u{lags[li] == 0 ? r1.white_m2 : 0.0, r1.mp * r2.mp, 1.0, r1.iono * r2.iono};
        const double y = r1.value_m * r2.value_m;
        for (std::size_t i = 0; i < kTerms; ++i) {
          b[li][i] += u[i] * y;
          for (std::size_t j = 0; j < kTerms; ++j) a[li][i][j] += u[i] * u[j];
        }
        ++f.pairs;
      }
    }
  }
  double best = std::numeric_limits<double>::infinity();
  constexpr int kGrid = 22;  // 30 s x sqrt(2)^i: 30 s .. 12.9 h
  const auto tau_at = [](int i) { return 30.0 * std::pow(2.0, i / 2.0); };
  for (int i_mp = 0; i_mp < kGrid; ++i_mp) {
    for (int i_oc = i_mp + 2; i_oc < kGrid; ++i_oc) {
      for (int i_io = i_mp + 2; i_io < kGrid; ++i_io) {
        const Vec tau{0.0, tau_at(i_mp), tau_at(i_oc), tau_at(i_io)};
        Mat n{};
        Vec v{};
        for (std::size_t li = 0; li < lags.size(); ++li) {
          Vec d{1.0, 0.0, 0.0, 0.0};
          for (std::size_t t = 1; t < kTerms; ++t) d[t] = std::exp(-lags[li] * step_s / tau[t]);
          for (std::size_t p = 0; p < kTerms; ++p) {
            v[p] += d[p] * b[li][p];
            for (std::size_t q = 0; q < kTerms; ++q) n[p][q] += d[p] * d[q] * a[li][p][q];
          }
        }
        Vec x{};
        if (!solve_linear(n, v, x)) continue;
        if (*std::min_element(x.begin(), x.end()) < 0.0) continue;  // variances are >= 0
        double cost = 0.0;  // sum of squared misfit minus sum y^2 (constant)
        for (std::size_t p = 0; p < kTerms; ++p) cost -= x[p] * v[p];
        if (cost < best) {
          best = cost;
          f.dll_bandwidth_hz = x[0];
          f.multipath_sigma_m = std::sqrt(x[1]);
          f.multipath_tau_s = tau[1];
          f.orbit_clock_sigma_m = std::sqrt(x[2]);
          f.orbit_clock_tau_s = tau[2];
          f.iono_sigma_tecu = std::sqrt(x[3]);
          f.iono_tau_s = tau[3];
        }
      }
    }
  }
  return f;
}

void fit_common_processes(const std::vector<CommonEpoch>& epochs, const std::vector<Residual>& res,
                          const ProcessFit& p, double step_s, AtmosphereBiasFit& out) {
  if (epochs.size() < 10) return;
  const int max_lag = static_cast<int>(std::lround(kCommonMaxLag_s / step_s));
  std::map<int, const CommonEpoch*> by_grid;
  for (const CommonEpoch& e : epochs) by_grid[e.grid] = &e;
  const double m_per_tecu = atmosphere::iono_m_per_tecu(kL1Freq_hz);
  const auto slow_cov = [&](const Residual& a, const Residual& b, double lag_s) {
    const double mp = p.multipath_sigma_m * p.multipath_sigma_m * multipath_factor(a.el_rad) * multipath_factor(b.el_rad);
    const double io = p.iono_sigma_tecu * p.iono_sigma_tecu * m_per_tecu * m_per_tecu *
                      atmosphere::iono_obliquity_factor(a.el_rad) * atmosphere::iono_obliquity_factor(b.el_rad);
    const auto e = [&](double tau) { return tau > 0.0 ? std::exp(-lag_s / tau) : 0.0; };
    return mp * e(p.multipath_tau_s) + p.orbit_clock_sigma_m * p.orbit_clock_sigma_m * e(p.orbit_clock_tau_s) +
           io * e(p.iono_tau_s);
  };
  const std::size_t n_lags = static_cast<std::size_t>(max_lag + 1);
  // [0]: scale, [1]: gradient (N and E pooled).
  std::array<std::vector<double>, 2> acov{std::vector<double>(n_lags, 0.0), std::vector<double>(n_lags, 0.0)};
  std::array<std::vector<double>, 2> leak = acov;
  std::vector<double> cnt(n_lags, 0.0);
  std::array<int, kNumSats> index_of{};  // SatId::index() -> residual index in the later epoch, -1: absent
  for (const CommonEpoch& h : epochs) {
    index_of.fill(-1);
    for (std::size_t b = h.first; b < h.last; ++b) index_of[static_cast<std::size_t>(res[b].sat.index())] = static_cast<int>(b);
    for (int k = 0; k <= max_lag; ++k) {
      const auto it = by_grid.find(h.grid - k);
      if (it == by_grid.end()) continue;
      const CommonEpoch& g = *it->second;
      const std::size_t ks = static_cast<std::size_t>(k);
      acov[0][ks] += g.value[0] * h.value[0];
      acov[1][ks] += 0.5 * (g.value[1] * h.value[1] + g.value[2] * h.value[2]);
      double l0 = 0.0, l1 = 0.0;
      for (std::size_t a = g.first; a < g.last; ++a) {
        const int b = index_of[static_cast<std::size_t>(res[a].sat.index())];
        if (b < 0) continue;
        const auto& wa = g.weights[a - g.first];
        const auto& wb = h.weights[static_cast<std::size_t>(b) - h.first];
        const double c = slow_cov(res[a], res[static_cast<std::size_t>(b)], k * step_s);
        l0 += wa[0] * wb[0] * c;
        l1 += 0.5 * (wa[1] * wb[1] + wa[2] * wb[2]) * c;
      }
      leak[0][ks] += l0;
      leak[1][ks] += l1;
      cnt[ks] += 1.0;
    }
  }
  std::array<NoiseFit, 2> fit;
  for (std::size_t t = 0; t < 2; ++t) {
    std::vector<double> net;
    for (std::size_t k = 0; k < n_lags && cnt[k] > 0.0; ++k) net.push_back((acov[t][k] - leak[t][k]) / cnt[k]);
    fit[t] = fit_gauss_markov(net, step_s, kCommonMaxTau_s);
  }
  const double scale = 1.0 + out.klobuchar_alpha;  // relative to the world's ionosphere
  out.scale_sigma = scale > 0.0 ? fit[0].gm_sigma_m / scale : 0.0;
  out.scale_tau_s = fit[0].gm_tau_s;
  out.scale_leak = cnt[0] > 0.0 && scale > 0.0 ? std::sqrt(std::max(leak[0][0] / cnt[0], 0.0)) / scale : 0.0;
  out.gradient_sigma_m = fit[1].gm_sigma_m;
  out.gradient_tau_s = fit[1].gm_tau_s;
  out.gradient_leak_m = cnt[0] > 0.0 ? std::sqrt(std::max(leak[1][0] / cnt[0], 0.0)) : 0.0;
}

Cn0Fit fit_cn0(const std::vector<Residual>& res, const signal::LinkBudgetConfig& link) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, srange = 0;
  int n = 0;
  for (const Residual& r : res) {
    if (!std::isfinite(r.cn0_dbhz) || r.cn0_dbhz <= 0.0) continue;
    const double x = 1.0 - std::sin(r.el_rad);
    const double y = r.cn0_dbhz + signal::free_space_path_loss_db(r.range_m, link.freq_hz);
    sx += x, sy += y, sxx += x * x, sxy += x * y, srange += r.range_m;
    ++n;
  }
  Cn0Fit f;
  f.n = n;
  if (n < 10) return f;
  const double det = n * sxx - sx * sx;
  double slope = det > 0.0 ? (n * sxy - sx * sy) / det : 0.0;
  slope = std::min(slope, 0.0);  // the pattern falls towards the horizon
  const double c0 = (sy - slope * sx) / n;
  // const = EIRP + G_zenith - (kT + NF + rise) - implementation loss.
  const double noise = signal::thermal_noise_density_dbw_hz(link.noise_temperature_k) + link.noise_figure_db +
                       link.environment_noise_rise_db;
  f.antenna = link.antenna;
  f.antenna.zenith_gain_dbi = c0 - link.eirp_dbw + noise + link.implementation_loss_db;
  f.antenna.horizon_gain_dbi = f.antenna.zenith_gain_dbi + slope;
  f.slope_db = slope;
  signal::LinkBudgetConfig fitted = link;
  fitted.antenna = f.antenna;
  const signal::LinkBudgetModel model(fitted);
  double ss = 0.0;
  for (const Residual& r : res) {
    if (!std::isfinite(r.cn0_dbhz) || r.cn0_dbhz <= 0.0) continue;
    const double d = r.cn0_dbhz - model.cn0_dbhz(r.range_m, r.el_rad, 0.0);
    ss += d * d;
  }
  f.rms_db = std::sqrt(ss / n);
  f.zenith_dbhz = model.cn0_dbhz(srange / n, kPi / 2.0, 0.0);
  return f;
}

}  // namespace gnssemu::cli

#include "tools/gnssemu/calibrate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/geo/local_frame.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/atmosphere/ionosphere.hpp"
#include "core/atmosphere/receiver_corrections.hpp"
#include "core/atmosphere/troposphere.hpp"
#include "core/receiver/transmit_state.hpp"
#include "core/world/sky.hpp"
#include "core/signal/link_budget.hpp"
#include "tools/gnssemu/spp.hpp"

namespace gnssemu::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMinSatsPerEpoch = 5;     // clock estimate from 4 would leave 3 dof
constexpr int kMinEpochs = 100;
constexpr double kMaxLag_s = 3600.0;    // autocovariance lags fitted (1 h)
constexpr double kOutlier_m = 30.0;     // |residual| beyond this: not a model error (blunder)


double grid_step_s(const observation::ObsData& obs) {
  if (obs.header.interval_s > 0.0) return obs.header.interval_s;
  std::vector<double> d;
  for (std::size_t i = 1; i < obs.epochs.size(); ++i) d.push_back(obs.epochs[i].t - obs.epochs[i - 1].t);
  if (d.empty()) return 1.0;
  std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
  return std::max(d[d.size() / 2], 1e-3);
}

std::vector<Residual> station_residuals(const CalibrationInput& in, const orbit::EphemerisStore& store,
                                        double step_s, int& epochs_used) {
  const observation::ObsData& obs = *in.obs;
  const int c1c = obs.header.type_index("C1C");
  const int s1c = obs.header.type_index("S1C");
  if (c1c < 0) throw Error(obs.source, 0, "no GPS C1C (RINEX 2: C1) pseudoranges");
  const Lla lla = geo::lla_from_ecef(in.station_m);
  const time::GpsTime t0 = obs.epochs.front().t;
  std::vector<Residual> out, epoch;
  epochs_used = 0;
  for (const observation::ObsEpoch& e : obs.epochs) {
    epoch.clear();
    for (const observation::SatObs& s : e.sats) {
      const observation::ObsValue* pr = s.get(c1c);
      if (pr == nullptr) continue;
      const orbit::Ephemeris* eph = store.select(s.prn, e.t);
      if (eph == nullptr) continue;
      const orbit::SatState st = receiver::transmit_state(*eph, e.t, pr->value).state;
      // Sagnac at the known station: rotate by the geometric flight time (the
      // solver's flight time holds its clock estimate, which is not known here).
      double rho = (st.pos_m - in.station_m).norm();
      Ecef p = st.pos_m;
      for (int it = 0; it < 2; ++it) {
        p = world::rotate_earth(st.pos_m, kOmegaEarth_rad_s * rho / kSpeedOfLight_m_s);
        rho = (p - in.station_m).norm();
      }
      const geo::LookAngles look = geo::look_angles(in.station_m, lla, p);
      if (!(look.el_rad >= in.mask_rad)) continue;
      Residual r;
      r.tow_s = e.t.tow_s();
      r.prn = s.prn;
      r.el_rad = look.el_rad;
      r.az_rad = look.az_rad;
      r.range_m = rho;
      r.klobuchar_m = receiver_correction_m(in.nav->klobuchar, lla, look.az_rad, look.el_rad, e.t) -
                      atmosphere::standard_troposphere_correction_m(lla.lat_rad, lla.height_m, look.el_rad,
                                                                    e.t.fractional_day_of_year());
      r.nmf_wet = atmosphere::niell_mapping(look.el_rad, lla.lat_rad, lla.height_m, e.t.fractional_day_of_year()).wet;
      // Local time as the receiver's gradient and Klobuchar (IS-GPS-200 20.3.3.5.2.5) take it.
      r.local_time_rad = 2.0 * kPi * (e.t.tow_s() / kSecondsPerDay) + lla.lon_rad;
      r.value_m = pr->value - (rho - kSpeedOfLight_m_s * (st.clk_bias_s - eph->tgd_s) +
                               receiver_correction_m(in.nav->klobuchar, lla, look.az_rad, look.el_rad, e.t));
      if (const observation::ObsValue* sn = s.get(s1c)) r.cn0_dbhz = sn->value;
      epoch.push_back(r);
    }
    if (static_cast<int>(epoch.size()) < kMinSatsPerEpoch) continue;
    // Receiver clock: median (robust to one blunder), then the mean of the rest.
    std::vector<double> v;
    for (const Residual& r : epoch) v.push_back(r.value_m);
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    const double med = v[v.size() / 2];
    double sum = 0.0;
    int n = 0;
    for (const Residual& r : epoch) {
      if (std::fabs(r.value_m - med) < kOutlier_m) {
        sum += r.value_m;
        ++n;
      }
    }
    if (n < kMinSatsPerEpoch) continue;
    const double clock = sum / n;
    // Removing the epoch mean shrinks independent errors by (n-1)/n in variance.
    const double inflate = std::sqrt(static_cast<double>(n) / (n - 1));
    const int grid = static_cast<int>(std::lround((e.t - t0) / step_s));
    ++epochs_used;
    for (Residual r : epoch) {
      if (std::fabs(r.value_m - med) >= kOutlier_m) continue;
      r.value_m = (r.value_m - clock) * inflate;
      r.grid = grid;
      out.push_back(r);
    }
  }
  return out;
}

/// Pooled autocovariance of the per-satellite series, lags 0..max_lag.
std::vector<double> pooled_autocovariance(const std::vector<Residual>& res, int max_lag) {
  std::map<int, std::map<int, double>> by_prn;  // prn -> grid -> value
  for (const Residual& r : res) by_prn[r.prn][r.grid] = r.value_m;
  std::vector<double> sum(static_cast<std::size_t>(max_lag + 1), 0.0);
  std::vector<double> cnt(sum.size(), 0.0);
  for (const auto& [prn, series] : by_prn) {
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

struct Cn0Fit {
  signal::AntennaPattern antenna;
  double rms_db = 0.0;
  double zenith_dbhz = 0.0;
  double slope_db = 0.0;
  int n = 0;
};

/// Fit the antenna pattern of the link budget (zenith gain, horizon gain) to
/// S1C: S1C + FSPL(range) = const + slope (1 - sin el), least squares.
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

constexpr std::size_t kBiasTerms = 8;

/// Regressors of one residual for fit_atmosphere_bias: alpha, beta, G_N, G_E,
/// then the daily cycle of G_N (cos, sin LT) and of G_E.
std::array<double, kBiasTerms> bias_regressors(const Residual& r) {
  const double cn = std::cos(r.az_rad), se = std::sin(r.az_rad);
  const double cl = std::cos(r.local_time_rad), sl = std::sin(r.local_time_rad);
  return {r.klobuchar_m, r.nmf_wet, cn, se, cl * cn, sl * cn, cl * se, sl * se};
}

}  // namespace

double AtmosphereBiasFit::north_at(const Residual& r) const {
  return gradient_north_m + north_cos_m * std::cos(r.local_time_rad) + north_sin_m * std::sin(r.local_time_rad);
}

double AtmosphereBiasFit::east_at(const Residual& r) const {
  return gradient_east_m + east_cos_m * std::cos(r.local_time_rad) + east_sin_m * std::sin(r.local_time_rad);
}

AtmosphereBiasFit fit_atmosphere_bias(const std::vector<Residual>& res, bool diurnal) {
  constexpr std::size_t kN = kBiasTerms;
  const std::size_t used = diurnal ? kN : 4;
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
      for (std::size_t p = 0; p < used; ++p) {
        b[p] += u[p] * y;
        for (std::size_t q = 0; q < used; ++q) a[p][q] += u[p] * u[q];
      }
    }
    i = j;
  }
  for (std::size_t p = used; p < kN; ++p) a[p][p] = 1.0;  // terms not fitted: 0
  AtmosphereBiasFit f;
  Vec x{};
  if (!solve_linear(a, b, x)) return f;
  f.klobuchar_alpha = x[0];
  f.zwd_beta_m = x[1];
  f.gradient_north_m = x[2];
  f.gradient_east_m = x[3];
  f.diurnal = diurnal;
  f.north_cos_m = x[4];
  f.north_sin_m = x[5];
  f.east_cos_m = x[6];
  f.east_sin_m = x[7];
  f.correlation = a[0][1] / std::sqrt(a[0][0] * a[1][1]);
  return f;
}

namespace {

/// Per-epoch azimuthal gradient about its mean (after alpha, beta and the
/// mean gradient are removed), with the 2x2 estimator rows kept so the
/// leakage of the per-satellite processes can be computed afterwards.
struct GradientEpoch {
  int grid = 0;
  double g_n_m = 0.0, g_e_m = 0.0;
  std::size_t first = 0, last = 0;                 ///< residuals [first, last)
  std::vector<std::array<double, 2>> weights;      ///< estimator row per residual (N, E)
};

/// Remove alpha, beta and the whole gradient of each epoch from res (then
/// the epoch mean again, scaled for the two extra parameters per epoch);
/// returns the per-epoch gradients.
std::vector<GradientEpoch> remove_common_terms(std::vector<Residual>& res, const AtmosphereBiasFit& b) {
  std::vector<GradientEpoch> out;
  for (std::size_t i = 0; i < res.size();) {
    std::size_t j = i;
    for (; j < res.size() && res[j].grid == res[i].grid; ++j) {
      res[j].value_m -= b.klobuchar_alpha * res[j].klobuchar_m + b.zwd_beta_m * res[j].nmf_wet +
                        b.north_at(res[j]) * std::cos(res[j].az_rad) + b.east_at(res[j]) * std::sin(res[j].az_rad);
    }
    const double n = static_cast<double>(j - i);
    double mc = 0, ms = 0, mr = 0;
    for (std::size_t k = i; k < j; ++k) mc += std::cos(res[k].az_rad), ms += std::sin(res[k].az_rad), mr += res[k].value_m;
    mc /= n, ms /= n, mr /= n;
    std::array<std::array<double, 2>, 2> a{};
    std::array<double, 2> v{};
    for (std::size_t k = i; k < j; ++k) {
      const double u0 = std::cos(res[k].az_rad) - mc, u1 = std::sin(res[k].az_rad) - ms, y = res[k].value_m - mr;
      a[0][0] += u0 * u0, a[0][1] += u0 * u1, a[1][1] += u1 * u1, v[0] += u0 * y, v[1] += u1 * y;
    }
    a[1][0] = a[0][1];
    const double det = a[0][0] * a[1][1] - a[0][1] * a[0][1];
    if (n >= 5 && det > 1e-6 * (a[0][0] + a[1][1]) * (a[0][0] + a[1][1])) {
      GradientEpoch g;
      g.grid = res[i].grid;
      g.first = i, g.last = j;
      for (std::size_t k = i; k < j; ++k) {
        const double u0 = std::cos(res[k].az_rad) - mc, u1 = std::sin(res[k].az_rad) - ms;
        g.weights.push_back({(a[1][1] * u0 - a[0][1] * u1) / det, (a[0][0] * u1 - a[0][1] * u0) / det});
      }
      for (std::size_t k = i; k < j; ++k) {
        g.g_n_m += g.weights[k - i][0] * (res[k].value_m - mr);
        g.g_e_m += g.weights[k - i][1] * (res[k].value_m - mr);
      }
      for (std::size_t k = i; k < j; ++k)
        res[k].value_m -= g.g_n_m * std::cos(res[k].az_rad) + g.g_e_m * std::sin(res[k].az_rad);
      out.push_back(std::move(g));
    }
    double m = 0.0;
    for (std::size_t k = i; k < j; ++k) m += res[k].value_m;
    m /= n;
    const double inflate = n > 3.0 ? std::sqrt((n - 1.0) / (n - 3.0)) : 1.0;
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
  std::map<int, std::map<int, Row>> by_prn;  // prn -> grid -> regressors
  for (const Residual& r : res) {
    const double s = signal::dll_thermal_sigma_m(budget.cn0_dbhz(r.range_m, r.el_rad, 0.0), unit);
    by_prn[r.prn][r.grid] = Row{r.value_m, s * s, 1.0 / std::sin(std::max(r.el_rad, 5.0 * kDegToRad)),
                                m_per_tecu * atmosphere::iono_obliquity_factor(r.el_rad)};
  }
  // Lags: every step to 10 min, then sparser to 4 h (long lags are many and alike).
  std::vector<int> lags;
  const int k10 = static_cast<int>(std::lround(600.0 / step_s));
  const int kmax = static_cast<int>(std::lround(4.0 * 3600.0 / step_s));
  for (int k = 0; k <= kmax; k += k < k10 ? 1 : std::max(1, k10 / 4)) lags.push_back(k);
  std::vector<Mat> a(lags.size(), Mat{});
  std::vector<Vec> b(lags.size(), Vec{});
  ProcessFit f;
  for (const auto& [prn, series] : by_prn) {
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

/// Gauss–Markov of the per-epoch gradient: autocovariance of g_N, g_E
/// (pooled) less the leakage of the fitted per-satellite processes, whose
/// variance at lag k is sum_i w_i(t) w_i(t + k) C_i(k) (same PRN), C_i from
/// the fitted multipath + orbit/clock + iono terms.
void fit_gradient_process(const std::vector<GradientEpoch>& grads, const std::vector<Residual>& res,
                          const ProcessFit& p, double step_s, AtmosphereBiasFit& out) {
  if (grads.size() < 10) return;
  const int max_lag = static_cast<int>(std::lround(4.0 * 3600.0 / step_s));
  std::map<int, const GradientEpoch*> by_grid;
  for (const GradientEpoch& g : grads) by_grid[g.grid] = &g;
  const double m_per_tecu = atmosphere::iono_m_per_tecu(1575.42e6);
  const auto slow_cov = [&](const Residual& a, const Residual& b, double lag_s) {
    const double mp = p.multipath_sigma_m * p.multipath_sigma_m /
                      (std::sin(std::max(a.el_rad, 5.0 * kDegToRad)) * std::sin(std::max(b.el_rad, 5.0 * kDegToRad)));
    const double io = p.iono_sigma_tecu * p.iono_sigma_tecu * m_per_tecu * m_per_tecu *
                      atmosphere::iono_obliquity_factor(a.el_rad) * atmosphere::iono_obliquity_factor(b.el_rad);
    const auto e = [&](double tau) { return tau > 0.0 ? std::exp(-lag_s / tau) : 0.0; };
    return mp * e(p.multipath_tau_s) + p.orbit_clock_sigma_m * p.orbit_clock_sigma_m * e(p.orbit_clock_tau_s) +
           io * e(p.iono_tau_s);
  };
  std::vector<double> acov(static_cast<std::size_t>(max_lag + 1), 0.0), leak(acov.size(), 0.0), cnt(acov.size(), 0.0);
  for (const GradientEpoch& g : grads) {
    for (int k = 0; k <= max_lag; ++k) {
      const auto it = by_grid.find(g.grid + k);
      if (it == by_grid.end()) continue;
      const GradientEpoch& h = *it->second;
      const std::size_t ks = static_cast<std::size_t>(k);
      acov[ks] += 0.5 * (g.g_n_m * h.g_n_m + g.g_e_m * h.g_e_m);
      double l = 0.0;
      for (std::size_t a = g.first; a < g.last; ++a) {
        for (std::size_t b = h.first; b < h.last; ++b) {
          if (res[a].prn != res[b].prn) continue;
          const auto& wa = g.weights[a - g.first];
          const auto& wb = h.weights[b - h.first];
          l += 0.5 * (wa[0] * wb[0] + wa[1] * wb[1]) * slow_cov(res[a], res[b], k * step_s);
        }
      }
      leak[ks] += l;
      cnt[ks] += 1.0;
    }
  }
  std::vector<double> net;
  for (std::size_t k = 0; k < acov.size() && cnt[k] > 0.0; ++k) net.push_back((acov[k] - leak[k]) / cnt[k]);
  if (cnt[0] > 0.0) out.gradient_leak_m = std::sqrt(std::max(leak[0] / cnt[0], 0.0));
  const NoiseFit f = fit_gauss_markov(net, step_s);
  out.gradient_sigma_m = f.gm_sigma_m;
  out.gradient_tau_s = f.gm_tau_s;
}

}  // namespace

NoiseFit fit_gauss_markov(const std::vector<double>& acov, double step_s) {
  NoiseFit f;
  if (acov.empty()) return f;
  const double c0 = std::max(acov[0], 0.0);
  double best_cost = std::numeric_limits<double>::infinity(), best_a = 0.0, best_tau = 0.0;
  for (int g = 0; g <= 400; ++g) {
    const double tau = 30.0 * std::pow(21600.0 / 30.0, g / 400.0);
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

CalibrationResult calibrate(const CalibrationInput& in, const config::Config& base) {
  if (in.obs == nullptr || in.nav == nullptr) throw Error("calibrate: no data");
  const orbit::EphemerisStore store(in.nav->ephemerides);
  const double step_s = grid_step_s(*in.obs);
  CalibrationResult r;
  const std::vector<Residual> res = station_residuals(in, store, step_s, r.epochs);
  if (r.epochs < kMinEpochs) {
    throw Error(in.obs->source, 0,
                fmt::format("only {} epochs with {}+ satellites above the mask at the station; {} needed", r.epochs,
                            kMinSatsPerEpoch, kMinEpochs));
  }
  r.residuals = static_cast<int>(res.size());
  r.residual_rows = res;
  std::vector<double> values;
  for (const Residual& x : res) values.push_back(x.value_m);
  r.residual_rms_m = statistics::rms(values);

  const int max_lag = static_cast<int>(std::lround(kMaxLag_s / step_s));
  r.range_noise = fit_gauss_markov(pooled_autocovariance(res, max_lag), step_s);

  const Cn0Fit cn0 = fit_cn0(res, base.world.signal.link);
  r.cn0_rms_db = cn0.rms_db;
  r.cn0_zenith_dbhz = cn0.zenith_dbhz;
  r.cn0_slope_db = cn0.slope_db;
  r.cn0_samples = cn0.n;

  // Elevation-dependent bias of the broadcast corrections, then the processes
  // on what remains, with the C/N0 the fitted link budget will give.
  const double span_s = in.obs->epochs.back().t - in.obs->epochs.front().t;
  r.bias = fit_atmosphere_bias(res, span_s >= kMinDiurnalSpan_s);
  std::vector<Residual> rest = res;
  const std::vector<GradientEpoch> grads = remove_common_terms(rest, r.bias);
  signal::LinkBudgetConfig link = base.world.signal.link;
  if (cn0.n >= 10) link.antenna = cn0.antenna;
  r.processes = fit_processes(rest, link, base.world.signal.dll, step_s);
  fit_gradient_process(grads, res, r.processes, step_s, r.bias);

  // The data's own single-point errors through the receiver's solver.
  receiver::ReceiverConfig rx = base.receiver;
  rx.elevation_mask_rad = in.mask_rad;
  SppEngine engine(*in.nav, store, in.obs->header, rx);
  const geo::LocalFrame frame(geo::lla_from_ecef(in.station_m));
  const time::GpsTime t0 = in.obs->epochs.front().t;
  const int n_grid = static_cast<int>(std::lround((in.obs->epochs.back().t - t0) / step_s)) + 1;
  std::vector<Enu> err(static_cast<std::size_t>(std::max(n_grid, 1)), Enu(kNaN, kNaN, kNaN));
  for (const observation::ObsEpoch& e : in.obs->epochs) {
    const SppEpoch& s = engine.solve(e);
    if (!s.fix) continue;
    ++r.spp_fixes;
    const long g = std::lround((e.t - t0) / step_s);
    if (g >= 0 && g < n_grid) err[static_cast<std::size_t>(g)] = frame.to_enu(s.pos_m);
  }
  r.spp = statistics::position_error_stats(err, step_s);

  // The fitted configuration.
  config::Config c = base;
  c.source.clear();
  c.origin = geo::lla_from_ecef(in.station_m);
  c.nav_file = in.nav_path;
  c.time.start.reset();
  c.receiver.elevation_mask_rad = in.mask_rad;
  if (cn0.n >= 10) c.world.nominal_cn0_dbhz = cn0.zenith_dbhz;
  if (cn0.n >= 10) c.world.signal.link.antenna = cn0.antenna;
  const ProcessFit& p = r.processes;
  world::ErrorModelConfig& em = c.world.errors;
  em.orbit_clock = {p.orbit_clock_sigma_m, p.orbit_clock_tau_s};
  em.multipath = {p.multipath_sigma_m, p.multipath_tau_s};
  // White noise: DLL jitter from the link budget's C/N0 with the fitted loop
  // bandwidth (the config range is (0, 50] Hz; none fitted -> fixed 0).
  if (p.dll_bandwidth_hz > 1e-6) {
    em.thermal_model = world::ThermalModel::kDll;
    c.world.signal.dll.loop_bandwidth_hz = std::min(p.dll_bandwidth_hz, 50.0);
  } else {
    em.thermal_model = world::ThermalModel::kFixed;
    em.thermal_sigma_m = 0.0;
  }
  // World ionosphere: Klobuchar shape x (1 + alpha) with the broadcast
  // obliquity (what the receiver removes is 1 x the same), plus the fitted
  // per-line-of-sight TEC process.
  atmosphere::IonosphereConfig& io = c.world.atmosphere.ionosphere;
  io.enabled = true;
  io.source = atmosphere::VtecSource::kKlobucharShape;
  io.klobuchar_scale = std::max(1.0 + r.bias.klobuchar_alpha, 0.0);
  io.mapping = atmosphere::IonoMapping::kObliquityFactor;
  io.obliquity_pivot_deg = 95.4;
  io.perturbation = {p.iono_sigma_tecu, p.iono_tau_s};
  // World troposphere: the receiver's Saastamoinen ZHD, and its standard ZWD
  // plus the fitted beta (one value for the site; the common ZWD process is
  // not observable once the epoch clock is removed, so it stays off).
  const Lla site = c.origin;
  const double doy = in.obs->epochs.front().t.fractional_day_of_year();
  atmosphere::TroposphereConfig& tr = c.world.atmosphere.troposphere;
  tr.enabled = true;
  tr.zhd_model = atmosphere::ZhdModel::kSaastamoinen;
  tr.zwd_model = atmosphere::ZwdModel::kFixed;
  const double zwd_rx_m = atmosphere::standard_troposphere_correction_m(site.lat_rad, site.height_m, kPi / 2.0, doy) -
                          atmosphere::receiver_zhd_m(site.lat_rad, site.height_m);
  tr.zwd_m = std::clamp((zwd_rx_m + r.bias.zwd_beta_m) * std::exp(std::max(site.height_m, 0.0) / tr.zwd_scale_height_m),
                        0.0, 1.0);
  c.world.atmosphere.zwd_perturbation.sigma_m = 0.0;
  em.gradient.north_m = r.bias.gradient_north_m;
  em.gradient.east_m = r.bias.gradient_east_m;
  // a cos LT + b sin LT = A cos(LT - peak): amplitude and local time of the maximum.
  const auto cycle = [](double a, double b, double& amp_m, double& peak_h) {
    amp_m = std::hypot(a, b);
    peak_h = amp_m > 0.0 ? std::fmod(std::atan2(b, a) * 12.0 / kPi + 24.0, 24.0) : 0.0;
    if (!(peak_h < 24.0)) peak_h = 0.0;
  };
  cycle(r.bias.north_cos_m, r.bias.north_sin_m, em.gradient.north_diurnal_m, em.gradient.north_peak_h);
  cycle(r.bias.east_cos_m, r.bias.east_sin_m, em.gradient.east_diurnal_m, em.gradient.east_peak_h);
  em.gradient.process = {r.bias.gradient_sigma_m, r.bias.gradient_tau_s > 0.0 ? r.bias.gradient_tau_s : 3600.0};
  r.config = c;
  return r;
}

std::string calibration_toml(const CalibrationResult& r, const std::string& out_dir) {
  std::ostringstream s;
  s << "# gnssemu calibrate: receiver error model fitted to real observations.\n"
    << fmt::format("# {} epochs, {} satellite residuals (RMS {:.3f} m after the receiver's corrections and clock).\n",
                   r.epochs, r.residuals, r.residual_rms_m)
    << fmt::format("# Ionosphere: world = {:.3f} x broadcast Klobuchar; troposphere: ZWD {:+.3f} m against the "
                   "receiver's (regressor correlation {:.2f}).\n",
                   1.0 + r.bias.klobuchar_alpha, r.bias.zwd_beta_m, r.bias.correlation)
    << fmt::format("# Processes ({} products): DLL B_L {:.3f} Hz; multipath {:.3f} m / sin(el), tau {:.0f} s; "
                   "orbit/clock {:.3f} m, tau {:.0f} s; iono {:.2f} TECU x obliquity, tau {:.0f} s.\n",
                   r.processes.pairs, r.processes.dll_bandwidth_hz, r.processes.multipath_sigma_m,
                   r.processes.multipath_tau_s, r.processes.orbit_clock_sigma_m, r.processes.orbit_clock_tau_s,
                   r.processes.iono_sigma_tecu, r.processes.iono_tau_s)
    << fmt::format("# C/N0 curve: {} S1C samples, RMS {:.2f} dB-Hz about the fit.\n", r.cn0_samples, r.cn0_rms_db)
    << config::to_toml(r.config, out_dir);
  return s.str();
}

void write_residuals_csv(const CalibrationResult& r, std::ostream& out) {
  out << "tow_s,prn,el_deg,az_deg,residual_m,cn0_dbhz,klobuchar_m,nmf_wet\n";
  for (const Residual& x : r.residual_rows) {
    out << fmt::format("{:.1f},{},{:.3f},{:.3f},{:.4f},{:.2f},{:.4f},{:.4f}\n", x.tow_s, x.prn, x.el_rad / kDegToRad,
                       x.az_rad / kDegToRad, x.value_m, x.cn0_dbhz, x.klobuchar_m, x.nmf_wet);
  }
}

namespace {

struct ReportRow {
  const char* name;
  double value;
  const char* unit;
};

/// `prefix + name,value,unit` lines.
void write_rows(std::ostream& out, std::string_view prefix, std::initializer_list<ReportRow> rows) {
  for (const ReportRow& x : rows) out << fmt::format("{}{},{:.6g},{}\n", prefix, x.name, x.value, x.unit);
}

}  // namespace

void write_calibration_report(const CalibrationResult& r, std::ostream& out) {
  out << "parameter,value,unit\n";
  const auto count = [](auto n) { return static_cast<double>(n); };
  write_rows(out, "", {{"epochs", count(r.epochs), ""}, {"residuals", count(r.residuals), ""},
                       {"residual_rms", r.residual_rms_m, "m"}, {"gm_sigma", r.range_noise.gm_sigma_m, "m"},
                       {"gm_tau", r.range_noise.gm_tau_s, "s"}, {"white_sigma", r.range_noise.white_sigma_m, "m"},
                       {"klobuchar_scale", 1.0 + r.bias.klobuchar_alpha, ""}, {"zwd_residual", r.bias.zwd_beta_m, "m"},
                       {"bias_regressor_correlation", r.bias.correlation, ""}});
  const world::ErrorModelConfig::Gradient& g = r.config.world.errors.gradient;
  write_rows(out, "gradient_", {{"north", r.bias.gradient_north_m, "m"}, {"east", r.bias.gradient_east_m, "m"},
                                {"north_diurnal", g.north_diurnal_m, "m"}, {"north_peak", g.north_peak_h, "h"},
                                {"east_diurnal", g.east_diurnal_m, "m"}, {"east_peak", g.east_peak_h, "h"},
                                {"sigma", r.bias.gradient_sigma_m, "m"}, {"tau", r.bias.gradient_tau_s, "s"},
                                {"leak", r.bias.gradient_leak_m, "m"}});
  const ProcessFit& p = r.processes;
  write_rows(out, "", {{"dll_bandwidth", p.dll_bandwidth_hz, "Hz"}, {"multipath_sigma_zenith", p.multipath_sigma_m, "m"},
                       {"multipath_tau", p.multipath_tau_s, "s"}, {"orbit_clock_sigma", p.orbit_clock_sigma_m, "m"},
                       {"orbit_clock_tau", p.orbit_clock_tau_s, "s"}, {"iono_sigma", p.iono_sigma_tecu, "TECU"},
                       {"iono_tau", p.iono_tau_s, "s"}});
  write_rows(out, "cn0_", {{"samples", count(r.cn0_samples), ""}, {"zenith", r.cn0_zenith_dbhz, "dB-Hz"},
                           {"zenith_to_horizon", r.cn0_slope_db, "dB"}, {"rms", r.cn0_rms_db, "dB-Hz"}});
  const statistics::PositionErrorStats& e = r.spp;
  write_rows(out, "spp_", {{"fixes", count(r.spp_fixes), ""}, {"mean_e", e.mean_e_m, "m"}, {"mean_n", e.mean_n_m, "m"},
                           {"mean_u", e.mean_u_m, "m"}, {"sigma_e", e.sigma_e_m, "m"}, {"sigma_n", e.sigma_n_m, "m"},
                           {"sigma_u", e.sigma_u_m, "m"}, {"cep50", e.cep50_m, "m"}, {"cep95", e.cep95_m, "m"},
                           {"corr_time", e.corr_time_s, "s"}});
}

}  // namespace gnssemu::cli

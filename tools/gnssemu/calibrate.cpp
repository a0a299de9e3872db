#include "tools/gnssemu/calibrate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/geo/local_frame.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/receiver/sky.hpp"
#include "core/signal/link_budget.hpp"
#include "tools/gnssemu/spp.hpp"

namespace gnssemu::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMinSatsPerEpoch = 5;     // clock estimate from 4 would leave 3 dof
constexpr int kMinEpochs = 100;
constexpr double kMaxLag_s = 3600.0;    // autocovariance lags fitted (1 h)
constexpr double kOutlier_m = 30.0;     // |residual| beyond this: not a model error (blunder)

/// One satellite residual at the known position.
struct Residual {
  int grid = 0;          // epoch index on the regular grid
  int prn = 0;
  double el_rad = 0.0;
  double range_m = 0.0;
  double value_m = 0.0;  // pseudorange - model - epoch clock, m
  double cn0_dbhz = kNaN;
};

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
      // Transmit time from the code phase, as receiver::Solver does.
      const time::GpsTime t_sv = e.t - pr->value / kSpeedOfLight_m_s;
      const double dt0 = orbit::sat_state(*eph, t_sv).clk_bias_s - eph->tgd_s;
      const orbit::SatState st = orbit::sat_state(*eph, t_sv - dt0);
      double rho = (st.pos_m - in.station_m).norm();
      Ecef p = st.pos_m;
      for (int it = 0; it < 2; ++it) {  // Sagnac: rotate by the flight time
        p = receiver::rotate_earth(st.pos_m, kOmegaEarth_rad_s * rho / kSpeedOfLight_m_s);
        rho = (p - in.station_m).norm();
      }
      const geo::LookAngles look = geo::look_angles(in.station_m, lla, p);
      if (!(look.el_rad >= in.mask_rad)) continue;
      Residual r;
      r.prn = s.prn;
      r.el_rad = look.el_rad;
      r.range_m = rho;
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

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  const double frac = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1.0 - frac) + v[i + 1] * frac : v[i];
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

ErrorStats error_stats(const std::vector<Enu>& errors, double step_s) {
  ErrorStats s;
  std::vector<double> h;
  double se = 0, sn = 0, su = 0;
  for (const Enu& d : errors) {
    if (!d.finite()) continue;
    se += d.x, sn += d.y, su += d.z;
    ++s.n;
  }
  if (s.n == 0) return s;
  s.mean_e_m = se / s.n, s.mean_n_m = sn / s.n, s.mean_u_m = su / s.n;
  double ve = 0, vn = 0, vu = 0;
  for (const Enu& d : errors) {
    if (!d.finite()) continue;
    ve += (d.x - s.mean_e_m) * (d.x - s.mean_e_m);
    vn += (d.y - s.mean_n_m) * (d.y - s.mean_n_m);
    vu += (d.z - s.mean_u_m) * (d.z - s.mean_u_m);
    h.push_back(std::hypot(d.x, d.y));
  }
  s.sigma_e_m = std::sqrt(ve / s.n), s.sigma_n_m = std::sqrt(vn / s.n), s.sigma_u_m = std::sqrt(vu / s.n);
  s.cep50_m = quantile(h, 0.5);
  s.cep95_m = quantile(h, 0.95);
  // Mean normalised autocorrelation of the three components.
  const std::size_t n = errors.size();
  const double mean[3] = {s.mean_e_m, s.mean_n_m, s.mean_u_m};
  const double var[3] = {ve / s.n, vn / s.n, vu / s.n};
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
        const double va = c == 0 ? a.x : c == 1 ? a.y : a.z;
        const double vb = c == 0 ? b.x : c == 1 ? b.y : b.z;
        acc += (va - mean[c]) * (vb - mean[c]);
        ++cnt;
      }
      rho += cnt > 0 && var[c] > 0.0 ? acc / cnt / var[c] / 3.0 : 0.0;
    }
    const double target = std::exp(-1.0);
    if (rho < target) {
      const double frac = (prev - target) / (prev - rho);
      s.corr_time_s = (static_cast<double>(k - 1) + frac) * step_s;
      return s;
    }
    prev = rho;
  }
  s.corr_time_s = static_cast<double>(n) * step_s;  // never decorrelated within the span
  return s;
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
  double ss = 0.0;
  for (const Residual& x : res) ss += x.value_m * x.value_m;
  r.residual_rms_m = std::sqrt(ss / r.residuals);

  const int max_lag = static_cast<int>(std::lround(kMaxLag_s / step_s));
  r.range_noise = fit_gauss_markov(pooled_autocovariance(res, max_lag), step_s);

  const Cn0Fit cn0 = fit_cn0(res, signal::LinkBudgetConfig{});
  r.cn0_rms_db = cn0.rms_db;
  r.cn0_zenith_dbhz = cn0.zenith_dbhz;
  r.cn0_slope_db = cn0.slope_db;
  r.cn0_samples = cn0.n;

  // The data's own single-point errors through the receiver's solver.
  SppOptions opt;
  opt.solver = base.receiver.solver;
  opt.max_pdop = base.receiver.max_pdop;
  opt.mask_rad = in.mask_rad;
  SppEngine engine(*in.nav, store, in.obs->header, opt);
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
  r.spp = error_stats(err, step_s);

  // The fitted configuration.
  config::Config c = base;
  c.source.clear();
  c.origin = geo::lla_from_ecef(in.station_m);
  c.nav_file = in.nav_path;
  c.time.start.reset();
  c.receiver.elevation_mask_rad = in.mask_rad;
  c.receiver.errors.orbit_clock.sigma_m = r.range_noise.gm_sigma_m;
  c.receiver.errors.orbit_clock.tau_s = r.range_noise.gm_tau_s;
  c.receiver.errors.thermal_sigma_m = r.range_noise.white_sigma_m;
  if (cn0.n >= 10) c.receiver.nominal_cn0_dbhz = cn0.zenith_dbhz;
  // The fitted GM + white process already holds all the receiver's broadcast
  // corrections miss: the world's random atmosphere is off, the white part is
  // used as fitted (not from C/N0), and the link budget takes the fitted antenna.
  c.receiver.errors.thermal_model = receiver::ThermalModel::kFixed;
  c.receiver.atmosphere.ionosphere.perturbation.sigma = 0.0;
  c.receiver.atmosphere.zwd_perturbation.sigma_m = 0.0;
  if (cn0.n >= 10) c.receiver.signal.link.antenna = cn0.antenna;
  r.config = c;
  return r;
}

std::string calibration_toml(const CalibrationResult& r, const std::string& out_dir) {
  std::ostringstream s;
  s << "# gnssemu calibrate: receiver error model fitted to real observations.\n"
    << fmt::format("# {} epochs, {} satellite residuals (RMS {:.3f} m after the receiver's corrections and clock).\n",
                   r.epochs, r.residuals, r.residual_rms_m)
    << fmt::format("# Residual process: Gauss-Markov sigma {:.3f} m tau {:.0f} s + white {:.3f} m.\n",
                   r.range_noise.gm_sigma_m, r.range_noise.gm_tau_s, r.range_noise.white_sigma_m)
    << fmt::format("# C/N0 curve: {} S1C samples, RMS {:.2f} dB-Hz about the fit.\n", r.cn0_samples, r.cn0_rms_db)
    << config::to_toml(r.config, out_dir);
  return s.str();
}

void write_calibration_report(const CalibrationResult& r, std::ostream& out) {
  out << "parameter,value,unit\n";
  const auto row = [&](const char* name, double v, const char* unit) {
    out << fmt::format("{},{:.6g},{}\n", name, v, unit);
  };
  row("epochs", r.epochs, "");
  row("residuals", r.residuals, "");
  row("residual_rms", r.residual_rms_m, "m");
  row("gm_sigma", r.range_noise.gm_sigma_m, "m");
  row("gm_tau", r.range_noise.gm_tau_s, "s");
  row("white_sigma", r.range_noise.white_sigma_m, "m");
  row("cn0_samples", r.cn0_samples, "");
  row("cn0_zenith", r.cn0_zenith_dbhz, "dB-Hz");
  row("cn0_zenith_to_horizon", r.cn0_slope_db, "dB");
  row("cn0_rms", r.cn0_rms_db, "dB-Hz");
  row("spp_fixes", r.spp_fixes, "");
  row("spp_mean_e", r.spp.mean_e_m, "m");
  row("spp_mean_n", r.spp.mean_n_m, "m");
  row("spp_mean_u", r.spp.mean_u_m, "m");
  row("spp_sigma_e", r.spp.sigma_e_m, "m");
  row("spp_sigma_n", r.spp.sigma_n_m, "m");
  row("spp_sigma_u", r.spp.sigma_u_m, "m");
  row("spp_cep50", r.spp.cep50_m, "m");
  row("spp_cep95", r.spp.cep95_m, "m");
  row("spp_corr_time", r.spp.corr_time_s, "s");
}

}  // namespace gnssemu::cli

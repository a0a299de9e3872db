// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/stations/calibrate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <sstream>
#include <string_view>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "tools/gnssemu/stations/spp.hpp"

namespace gnssemu::cli {

namespace {

constexpr int kMinEpochs = 100;
constexpr double kMaxLag_s = 3600.0;  // autocovariance lags of the summary fit (1 h)
constexpr int kMinCn0Samples = 10;  // fewer S1C samples: no C/N0 curve

/// A fitted Gauss–Markov process as the loader accepts it: sigma in
/// [0, 100] m and tau in (0, 1e6] s. A fit with no power or no correlation
/// (sigma or tau not positive, e.g. a half-day with too few pairs) is off:
/// sigma 0 with the base config's tau, never a tau of 0 the loader rejects.
world::GaussMarkovConfig fitted_process(double sigma, double tau_s, const world::GaussMarkovConfig& base) {
  using Gm = world::GaussMarkovRanges;
  if (!(sigma > 0.0) || !(tau_s > 0.0) || !std::isfinite(sigma) || !std::isfinite(tau_s)) return {0.0, base.tau_s};
  return {std::min(sigma, Gm::sigma_m.max), std::min(tau_s, Gm::tau_s.max)};
}

}  // namespace

world::WorldConfig fitted_world(const CalibrationResult& r, const world::WorldConfig& base) {
  world::WorldConfig w = base;
  if (r.cn0.n >= kMinCn0Samples) {
    w.nominal_cn0_dbhz = r.cn0.zenith_dbhz;
    w.signal.link.antenna = r.cn0.antenna;
  }
  const ProcessFit& p = r.processes;
  world::ErrorModelConfig& em = w.errors;
  em.orbit_clock = fitted_process(p.orbit_clock_sigma_m, p.orbit_clock_tau_s, base.errors.orbit_clock);
  em.multipath = fitted_process(p.multipath_sigma_m, p.multipath_tau_s, base.errors.multipath);
  // White noise: DLL jitter from the link budget's C/N0 with the fitted loop
  // bandwidth (the config range is (0, 50] Hz; none fitted -> fixed 0).
  if (p.dll_bandwidth_hz > 1e-6) {
    em.thermal_model = world::ThermalModel::kDll;
    w.signal.dll.loop_bandwidth_hz = std::min(p.dll_bandwidth_hz, 50.0);
  } else {
    em.thermal_model = world::ThermalModel::kFixed;
    em.thermal_sigma_m = 0.0;
  }
  // World ionosphere: Klobuchar shape x (1 + alpha) (what the receiver
  // removes is 1 x the same), the common relative error process and the
  // per-line-of-sight TEC process. Troposphere: the receiver's own (beta is
  // 0: what is common and elevation-dependent is carried by the ionosphere's
  // terms, AtmosphereBiasFit).
  const world::GaussMarkovConfig iono = fitted_process(
      p.iono_sigma_tecu, p.iono_tau_s, {base.atmosphere.ionosphere.perturbation.sigma, base.atmosphere.ionosphere.perturbation.tau_s});
  world::use_klobuchar_ionosphere(w.atmosphere, 1.0 + r.bias.klobuchar_alpha, iono.sigma_m, iono.tau_s);
  em.iono_scale = {std::min(r.bias.scale_sigma, 2.0), r.bias.scale_tau_s > 0.0 ? r.bias.scale_tau_s : 3600.0};
  world::use_receiver_troposphere(w.atmosphere);
  // Azimuthal gradient: the mean of the data plus a slow random process
  // (a daily cycle fitted at one site does not hold at the next).
  em.gradient.north_m = r.bias.gradient_north_m;
  em.gradient.east_m = r.bias.gradient_east_m;
  em.gradient.north_diurnal_m = em.gradient.east_diurnal_m = 0.0;
  em.gradient.north_peak_h = em.gradient.east_peak_h = 0.0;
  em.gradient.process = fitted_process(r.bias.gradient_sigma_m, r.bias.gradient_tau_s > 0.0 ? r.bias.gradient_tau_s : 3600.0,
                                       {0.0, 3600.0});
  return w;
}

CalibrationResult calibrate(const std::vector<CalibrationInput>& days, const config::Config& base) {
  if (days.empty()) throw Error("calibrate: no data");
  CalibrationResult r;
  std::vector<Residual> res;
  double step_s = 0.0;
  for (std::size_t d = 0; d < days.size(); ++d) {
    const CalibrationInput& in = days[d];
    if (in.obs == nullptr || in.nav == nullptr || in.obs->epochs.empty()) throw Error("calibrate: no data");
    const double step = grid_step_s(*in.obs);
    if (d == 0) step_s = step;
    if (std::fabs(step - step_s) > 1e-6 * step_s) {
      throw Error(in.obs->source, 0,
                  fmt::format("sampled every {} s, the first file every {} s: pooled days need one interval", step,
                              step_s));
    }
    if (in.mask_rad != days.front().mask_rad) throw Error(in.obs->source, 0, "pooled days need one elevation mask");
    const orbit::EphemerisStore store(in.nav->ephemerides);
    DayCalibration day;
    day.source = in.obs->source;
    const std::vector<Residual> rows = station_residuals(in, store, step_s, static_cast<int>(d), day.epochs);
    if (day.epochs < kMinEpochs) {
      throw Error(in.obs->source, 0,
                  fmt::format("only {} epochs with 5+ satellites above the mask at the station; {} needed",
                              day.epochs, kMinEpochs));
    }
    day.residuals = static_cast<int>(rows.size());
    res.insert(res.end(), rows.begin(), rows.end());
    r.epochs += day.epochs;
    // The data's own single-point errors through the receiver's solver.
    receiver::ReceiverConfig rx = base.receiver;
    rx.elevation_mask_rad = in.mask_rad;
    day.spp = statistics::position_error_stats(
        spp_error_series(*in.obs, *in.nav, store, rx, in.station_m, step_s, &day.spp_fixes), step_s);
    r.days.push_back(day);
  }
  r.residuals = static_cast<int>(res.size());
  std::vector<double> values;
  for (const Residual& x : res) values.push_back(x.value_m);
  r.residual_rms_m = statistics::rms(values);
  r.range_noise = fit_gauss_markov(pooled_autocovariance(res, static_cast<int>(std::lround(kMaxLag_s / step_s))), step_s);
  r.cn0 = fit_cn0(res, base.world.signal.link);

  // Mean common terms, then each epoch's own about them; the per-satellite
  // processes on what remains (with the C/N0 the fitted link budget will
  // give); then the processes of the common terms, less what the
  // per-satellite ones leak into their estimates.
  r.bias = fit_atmosphere_bias(res);
  r.zwd_diagnostic = fit_atmosphere_bias(res, true);
  std::vector<Residual> rest = res;
  const std::vector<CommonEpoch> common = remove_common_terms(rest, r.bias);
  signal::LinkBudgetConfig link = base.world.signal.link;
  if (r.cn0.n >= kMinCn0Samples) link.antenna = r.cn0.antenna;
  r.processes = fit_processes(rest, link, base.world.signal.dll, step_s);
  fit_common_processes(common, res, r.processes, step_s, r.bias);
  r.residual_rows = std::move(res);

  const CalibrationInput& first = days.front();
  config::Config c = base;
  c.source.clear();
  c.origin = geo::lla_from_ecef(first.station_m);
  c.nav_file = first.nav_path;
  c.time.start.reset();
  c.receiver.elevation_mask_rad = first.mask_rad;
  c.world = fitted_world(r, base.world);
  r.config = c;
  return r;
}

CalibrationResult calibrate(const CalibrationInput& in, const config::Config& base) {
  return calibrate(std::vector<CalibrationInput>{in}, base);
}

std::string calibration_toml(const CalibrationResult& r, const std::string& out_dir) {
  std::ostringstream s;
  const AtmosphereBiasFit& b = r.bias;
  const ProcessFit& p = r.processes;
  s << fmt::format("# gnssemu calibrate: world error model fitted to real observations ({} station-day{}).\n",
                   r.days.size(), r.days.size() == 1 ? "" : "s");
  for (const DayCalibration& d : r.days) s << "#   " << d.source << '\n';
  s << fmt::format("# {} epochs, {} satellite residuals (RMS {:.3f} m after the receiver's corrections and clock).\n",
                   r.epochs, r.residuals, r.residual_rms_m)
    << fmt::format("# Ionosphere: world = {:.3f} x broadcast Klobuchar; troposphere: the receiver's (a free ZWD "
                   "would take {:+.3f} m, regressor correlation {:.2f}).\n",
                   1.0 + b.klobuchar_alpha, r.zwd_diagnostic.zwd_beta_m, b.correlation)
    << fmt::format("# Processes ({} products): DLL B_L {:.3f} Hz; multipath {:.3f} m / sin(el), tau {:.0f} s; "
                   "orbit/clock {:.3f} m, tau {:.0f} s; iono {:.2f} TECU x obliquity, tau {:.0f} s.\n",
                   p.pairs, p.dll_bandwidth_hz, p.multipath_sigma_m, p.multipath_tau_s, p.orbit_clock_sigma_m,
                   p.orbit_clock_tau_s, p.iono_sigma_tecu, p.iono_tau_s)
    << fmt::format("# Common ionospheric error (relative to the world's ionosphere): sigma {:.3f}, tau {:.0f} s.\n"
                   "#   No configuration key carries it yet (errors.iono_scale in the core): a world loaded from\n"
                   "#   this file runs without it.\n",
                   r.config.world.errors.iono_scale.sigma, r.config.world.errors.iono_scale.tau_s)
    << fmt::format("# C/N0 curve: {} S1C samples, RMS {:.2f} dB-Hz about the fit.\n", r.cn0.n, r.cn0.rms_db)
    << config::to_toml(r.config, out_dir);
  return s.str();
}

void write_residuals_csv(const CalibrationResult& r, std::ostream& out) {
  const bool pooled = r.days.size() > 1;
  out << "tow_s,sat,prn,el_deg,az_deg,residual_m,cn0_dbhz,klobuchar_m,nmf_wet" << (pooled ? ",day" : "") << '\n';
  for (const Residual& x : r.residual_rows) {
    out << fmt::format("{:.1f},{},{},{:.3f},{:.3f},{:.4f},{:.2f},{:.4f},{:.4f}", x.tow_s, sat_name(x.sat).data(),
                       x.sat.prn(), x.el_rad / kDegToRad,
                       x.az_rad / kDegToRad, x.value_m, x.cn0_dbhz, x.klobuchar_m, x.nmf_wet);
    if (pooled) out << ',' << x.day + 1;
    out << '\n';
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
  const AtmosphereBiasFit& b = r.bias;
  write_rows(out, "", {{"epochs", count(r.epochs), ""}, {"residuals", count(r.residuals), ""},
                       {"residual_rms", r.residual_rms_m, "m"}, {"gm_sigma", r.range_noise.gm_sigma_m, "m"},
                       {"gm_tau", r.range_noise.gm_tau_s, "s"}, {"white_sigma", r.range_noise.white_sigma_m, "m"},
                       {"klobuchar_scale", 1.0 + b.klobuchar_alpha, ""}, {"zwd_residual", r.zwd_diagnostic.zwd_beta_m, "m"},
                       {"bias_regressor_correlation", b.correlation, ""}, {"iono_scale_sigma", b.scale_sigma, ""},
                       {"iono_scale_tau", b.scale_tau_s, "s"}, {"iono_scale_leak", b.scale_leak, ""}});
  write_rows(out, "gradient_", {{"north", b.gradient_north_m, "m"}, {"east", b.gradient_east_m, "m"},
                                {"sigma", b.gradient_sigma_m, "m"}, {"tau", b.gradient_tau_s, "s"},
                                {"leak", b.gradient_leak_m, "m"}});
  const ProcessFit& p = r.processes;
  write_rows(out, "", {{"dll_bandwidth", p.dll_bandwidth_hz, "Hz"}, {"multipath_sigma_zenith", p.multipath_sigma_m, "m"},
                       {"multipath_tau", p.multipath_tau_s, "s"}, {"orbit_clock_sigma", p.orbit_clock_sigma_m, "m"},
                       {"orbit_clock_tau", p.orbit_clock_tau_s, "s"}, {"iono_sigma", p.iono_sigma_tecu, "TECU"},
                       {"iono_tau", p.iono_tau_s, "s"}});
  write_rows(out, "cn0_", {{"samples", count(r.cn0.n), ""}, {"zenith", r.cn0.zenith_dbhz, "dB-Hz"},
                           {"zenith_to_horizon", r.cn0.slope_db, "dB"}, {"rms", r.cn0.rms_db, "dB-Hz"}});
  for (std::size_t d = 0; d < r.days.size(); ++d) {
    const std::string prefix = r.days.size() == 1 ? "spp_" : fmt::format("spp{}_", d + 1);
    const statistics::PositionErrorStats& e = r.days[d].spp;
    write_rows(out, prefix,
               {{"fixes", count(r.days[d].spp_fixes), ""}, {"mean_e", e.mean_e_m, "m"}, {"mean_n", e.mean_n_m, "m"},
                {"mean_u", e.mean_u_m, "m"}, {"sigma_e", e.sigma_e_m, "m"}, {"sigma_n", e.sigma_n_m, "m"},
                {"sigma_u", e.sigma_u_m, "m"}, {"cep50", e.cep50_m, "m"}, {"cep95", e.cep95_m, "m"},
                {"corr_time", e.corr_time_s, "s"}});
  }
}

}  // namespace gnssemu::cli

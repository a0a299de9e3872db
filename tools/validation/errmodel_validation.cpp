// SPDX-License-Identifier: Apache-2.0
// errmodel_validation: does the fitted error model hold on a station it has
// never seen? (docs/validation.md, "An error model that holds on unseen
// stations".) For every station, `gnssemu calibrate`'s pooled fit on the
// other stations' days, then that station's days simulated by the world
// (tools/validation/simulated_station) and both real and simulated
// observations through the same single-point solver; plus the half day
// ahead at one station (fit 00-12 h, predict 12-24 h). Prints markdown
// tables and, with --csv, one row per day and metric.
//
// errmodel_validation --day NAME,STATION,OBS,NAV [--day ...] [--seeds 20]
//     [--mask 10] [--half-day NAME] [--only STATION] [--csv FILE]
// (tools/validation/errmodel_validation.py passes the station-days of
// ../shared/data.)
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/observation/rinex_obs.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/pipeline/receiver_profile.hpp"
#include "core/statistics/statistics.hpp"
#include "tools/gnssemu/stations/calibrate.hpp"
#include "tools/gnssemu/stations/spp.hpp"
#include "tools/gnssemu/stations/simulated_station.hpp"

namespace gnssemu::validation {
namespace {

struct Day {
  std::string name, station;
  observation::ObsData obs;
  orbit::NavData nav;
  std::unique_ptr<orbit::EphemerisStore> store;
  Ecef arp;
};

/// The statistics compared: sigma E/N/U, CEP50, CEP95 (about the truth),
/// correlation time, and the seed's criterion: mean and standard deviation
/// of the 3D error.
struct Stats {
  static constexpr int kCount = 8;
  static constexpr std::array<const char*, kCount> kName{"σE", "σN", "σU", "CEP50", "CEP95", "corr. time",
                                                        "mean 3D", "sd 3D"};
  static constexpr std::array<const char*, kCount> kUnit{"m", "m", "m", "m", "m", "s", "m", "m"};
  std::array<double, kCount> v{};
  std::array<double, 3> mean_enu{};
};

Stats stats_of(const std::vector<Enu>& err, double step_s) {
  const statistics::PositionErrorStats p = statistics::position_error_stats(err, step_s);
  std::vector<double> r3;
  for (const Enu& e : err)
    if (e.finite()) r3.push_back(std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z));
  Stats s;
  const double m = statistics::mean(r3);
  s.v = {p.sigma_e_m, p.sigma_n_m, p.sigma_u_m, p.cep50_m, p.cep95_m, p.corr_time_s, m, statistics::std_dev(r3, m)};
  s.mean_enu = {p.mean_e_m, p.mean_n_m, p.mean_u_m};
  return s;
}

/// The solver of the comparison, the same on both sides: the receiver's
/// weights without the C/N0 term (two of the stations record no C/N0).
receiver::ReceiverConfig comparison_receiver(const config::Config& base, double mask_rad) {
  receiver::ReceiverConfig rx = base.receiver;
  rx.elevation_mask_rad = mask_rad;
  rx.solver.sigma_c_m_sqrt_hz = 0.0;
  return rx;
}

cli::CalibrationInput input_of(const Day& d, const observation::ObsData& obs, double mask_rad) {
  cli::CalibrationInput in;
  in.obs = &obs;
  in.nav = &d.nav;
  in.nav_path = d.name;
  in.station_m = d.arp;
  in.mask_rad = mask_rad;
  return in;
}

/// obs with only the epochs whose GPS time of day is in [from_h, to_h).
observation::ObsData hours(const observation::ObsData& obs, double from_h, double to_h) {
  observation::ObsData out = obs;
  out.epochs.clear();
  for (const observation::ObsEpoch& e : obs.epochs) {
    const double h = std::fmod(e.t.tow_s(), 86400.0) / 3600.0;
    if (h >= from_h && h < to_h) out.epochs.push_back(e);
  }
  return out;
}

struct Comparison {
  std::string title;
  Stats real;
  std::vector<Stats> sims;
};

/// Terms the --without option can switch off in the simulation (an error
/// budget: what each term contributes).
void switch_off(world::WorldConfig& w, const std::vector<std::string>& terms) {
  for (const std::string& t : terms) {
    if (t == "scale") w.errors.iono_scale.sigma = 0.0;
    else if (t == "gradient") w.errors.gradient = {};
    else if (t == "orbit") w.errors.orbit_clock.sigma_m = 0.0;
    else if (t == "iono") w.atmosphere.ionosphere.perturbation.sigma = 0.0;
    else if (t == "multipath") w.errors.multipath.sigma_m = 0.0;
    else if (t == "white") w.errors.thermal_model = world::ThermalModel::kFixed, w.errors.thermal_sigma_m = 0.0;
    else throw Error("--without: unknown term '" + t + "' (scale, gradient, orbit, iono, multipath, white)");
  }
}

std::vector<std::string> g_without;  // --without terms
bool g_filtered = false;              // --filtered

/// --filtered: the whole receiver (acquisition, navigation filter, the
/// default dynamic model) at the station's antenna in world w, stepped at
/// 1 Hz over obs's span and sampled at its epochs; NaN where it has no fix.
std::vector<Enu> filtered_error_series(const Day& d, const observation::ObsData& obs, const world::WorldConfig& w,
                                       const receiver::ReceiverConfig& rx) {
  std::vector<Enu> out;
  if (obs.epochs.empty()) return out;
  pipeline::Pipeline p(*d.store, pipeline::PipelineConfig{w, rx}, pipeline::broadcast_of(d.nav));
  const Lla lla = geo::lla_from_ecef(d.arp);
  world::Truth truth;
  truth.pos_m = d.arp;
  truth.valid = true;
  time::GpsTime t = obs.epochs.front().t;
  std::size_t k = 0;
  while (k < obs.epochs.size()) {
    truth.t = t;
    const receiver::Fix& f = p.step(t, truth);
    while (k < obs.epochs.size() && obs.epochs[k].t - t < 0.5) {
      const bool gnss = f.type == receiver::FixType::k3D || f.type == receiver::FixType::k2D;
      const double nan = std::numeric_limits<double>::quiet_NaN();
      out.push_back(gnss ? geo::ecef_to_enu_vector(f.pos_m - d.arp, lla.lat_rad, lla.lon_rad) : Enu(nan, nan, nan));
      ++k;
    }
    t = t + 1.0;
  }
  return out;
}

/// Real against simulated: obs of day d, the world w simulated for seeds 1..seeds.
Comparison compare(const std::string& title, const Day& d, const observation::ObsData& obs, world::WorldConfig w,
                   const config::Config& base, double mask_rad, int seeds,
                   SystemSet systems = SystemSet::only(GnssSystem::kGps)) {
  const double step_s = cli::grid_step_s(obs);
  const receiver::ReceiverConfig rx = comparison_receiver(base, mask_rad);
  Comparison c;
  c.title = title;
  c.real = stats_of(cli::spp_error_series(obs, d.nav, *d.store, rx, d.arp, step_s, nullptr, systems), step_s);
  switch_off(w, g_without);
  for (int seed = 1; seed <= seeds; ++seed) {
    w.seed = static_cast<uint64_t>(seed);
    if (g_filtered) {
      receiver::ReceiverConfig filtered = base.receiver;
      filtered.elevation_mask_rad = mask_rad;
      c.sims.push_back(stats_of(filtered_error_series(d, obs, w, filtered), step_s));
      continue;
    }
    const observation::ObsData sim = cli::simulate_station(obs, d.nav, *d.store, w, d.arp, mask_rad, systems);
    c.sims.push_back(
        stats_of(cli::spp_error_series(sim, d.nav, *d.store, rx, d.arp, step_s, nullptr, systems), step_s));
  }
  return c;
}

/// Sample standard deviation over the seeds (n - 1 in the denominator).
double sample_sd(const std::vector<double>& v, double mean_v) {
  const double n = static_cast<double>(v.size());
  return std::sqrt(statistics::variance(v, mean_v) * n / std::max(n - 1.0, 1.0));
}

struct Summary {
  double mean_abs_pct = 0.0, max_abs_pct = 0.0, corr_pct = 0.0, seed_mean_pct = 0.0, seed_sd_pct = 0.0;
  double spread_pct = 0.0;  ///< mean seed-to-seed coefficient of variation of the five size metrics
  /// What a perfect model would show: each seed taken as "the real day"
  /// against the mean of the other seeds, mean |relative difference| of the
  /// five size metrics averaged over seeds.
  double floor_pct = 0.0;
};

double noise_floor_pct(const std::vector<Stats>& sims) {
  const std::size_t n = sims.size();
  if (n < 3) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < 5; ++k) {
      double others = 0.0;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i) others += sims[j].v[k] / static_cast<double>(n - 1);
      sum += 100.0 * std::fabs(others - sims[i].v[k]) / sims[i].v[k] / 5.0;
    }
  }
  return sum / static_cast<double>(n);
}

Summary print(const Comparison& c, std::ostream& out, std::ostream* csv) {
  out << "\n#### " << c.title << "\n\n| metric | real | simulated (mean ± sd over " << c.sims.size()
      << " seeds) | relative difference |\n|---|---|---|---|\n";
  Summary s;
  std::array<double, Stats::kCount> rel{};
  for (int k = 0; k < Stats::kCount; ++k) {
    std::vector<double> v;
    for (const Stats& x : c.sims) v.push_back(x.v[static_cast<std::size_t>(k)]);
    const double m = statistics::mean(v);
    const double sd = sample_sd(v, m);
    const double real = c.real.v[static_cast<std::size_t>(k)];
    rel[static_cast<std::size_t>(k)] = 100.0 * (m - real) / real;
    const int digits = k == 5 ? 0 : 3;  // seconds / metres
    const auto num = [digits](double x) { return fmt::format("{:.{}f}", x, digits); };
    out << fmt::format("| {} | {} {} | {} ± {} {} | {:+.1f} % |\n", Stats::kName[static_cast<std::size_t>(k)], num(real),
                       Stats::kUnit[static_cast<std::size_t>(k)], num(m), num(sd),
                       Stats::kUnit[static_cast<std::size_t>(k)], rel[static_cast<std::size_t>(k)]);
    if (csv != nullptr)
      *csv << fmt::format("{},{},{:.4f},{:.4f},{:.4f},{:.2f}\n", c.title, Stats::kName[static_cast<std::size_t>(k)],
                          real, m, sd, rel[static_cast<std::size_t>(k)]);
    if (k < 5) {
      s.mean_abs_pct += std::fabs(rel[static_cast<std::size_t>(k)]) / 5.0;
      s.max_abs_pct = std::max(s.max_abs_pct, std::fabs(rel[static_cast<std::size_t>(k)]));
      s.spread_pct += 100.0 * sd / m / 5.0;
    }
  }
  s.floor_pct = noise_floor_pct(c.sims);
  s.corr_pct = rel[5];
  s.seed_mean_pct = rel[6];
  s.seed_sd_pct = rel[7];
  std::array<double, 3> me{};
  for (const Stats& x : c.sims)
    for (std::size_t i = 0; i < 3; ++i) me[i] += x.mean_enu[i] / static_cast<double>(c.sims.size());
  out << fmt::format("| mean E / N / U | {:.2f} / {:.2f} / {:.2f} m | {:.2f} / {:.2f} / {:.2f} m | |\n",
                     c.real.mean_enu[0], c.real.mean_enu[1], c.real.mean_enu[2], me[0], me[1], me[2]);
  out << fmt::format(
      "\nmean |relative difference| of σE, σN, σU, CEP50, CEP95: **{:.1f} %** (largest {:.1f} %); correlation "
      "time {:+.1f} %; seed criterion (mean, sd of the 3D error) {:+.1f} / {:+.1f} %; seed-to-seed spread of the "
      "five {:.1f} %; one seed against the others (a perfect model's figure) {:.1f} %\n",
      s.mean_abs_pct, s.max_abs_pct, s.corr_pct, s.seed_mean_pct, s.seed_sd_pct, s.spread_pct, s.floor_pct);
  return s;
}

/// The multi-system gain: each size metric with `systems` over the same with
/// GPS alone, real against simulated (the ratio per seed: both runs of a
/// seed share its world's draws).
void print_gain(const std::string& title, const Comparison& gps, const Comparison& multi, std::ostream& out,
                std::ostream* csv) {
  out << "\n#### " << title << "\n\n| metric | real GPS | real multi | real ratio | simulated ratio (mean ± sd over "
      << gps.sims.size() << " seeds) |\n|---|---|---|---|---|\n";
  for (std::size_t k = 0; k < 5; ++k) {
    std::vector<double> r;
    for (std::size_t i = 0; i < gps.sims.size() && i < multi.sims.size(); ++i)
      r.push_back(multi.sims[i].v[k] / gps.sims[i].v[k]);
    const double m = statistics::mean(r);
    const double sd = sample_sd(r, m);
    const double real = multi.real.v[k] / gps.real.v[k];
    out << fmt::format("| {} | {:.3f} m | {:.3f} m | {:.3f} | {:.3f} ± {:.3f} |\n", Stats::kName[k], gps.real.v[k],
                       multi.real.v[k], real, m, sd);
    if (csv != nullptr)
      *csv << fmt::format("{},{} ratio,{:.4f},{:.4f},{:.4f},{:.2f}\n", title, Stats::kName[k], real, m, sd,
                          100.0 * (m - real) / real);
  }
}

void print_fit(const cli::CalibrationResult& r, std::ostream& out) {
  const cli::AtmosphereBiasFit& b = r.bias;
  const cli::ProcessFit& p = r.processes;
  out << fmt::format(
      "\nfit ({} days, {} epochs): iono {:.3f} x Klobuchar, common scale σ {:.3f} τ {:.0f} s; ZWD {:+.3f} m; "
      "gradient N {:+.3f} E {:+.3f} m, σ {:.3f} m τ {:.0f} s; DLL B_L {:.3f} Hz; multipath {:.3f} m/sin el τ {:.0f} "
      "s; orbit/clock {:.3f} m τ {:.0f} s; iono {:.2f} TECU τ {:.0f} s; C/N0 {} samples\n",
      r.days.size(), r.epochs, 1.0 + b.klobuchar_alpha, b.scale_sigma, b.scale_tau_s, b.zwd_beta_m,
      b.gradient_north_m, b.gradient_east_m, b.gradient_sigma_m, b.gradient_tau_s, p.dll_bandwidth_hz,
      p.multipath_sigma_m, p.multipath_tau_s, p.orbit_clock_sigma_m, p.orbit_clock_tau_s, p.iono_sigma_tecu,
      p.iono_tau_s, r.cn0.n);
}

int run(int argc, char** argv) {
  CLI::App app{"errmodel_validation: leave-one-station-out and half-day-ahead check of the fitted error model"};
  std::vector<std::string> day_args;
  int seeds = 20;
  double mask_deg = 10.0;
  std::string half_day, only, csv_path;
  bool default_world = false;
  std::string profile;
  app.add_option("--day", day_args, "NAME,STATION,OBS,NAV (plain nav file); repeat per station-day")->required();
  app.add_option("--seeds", seeds, "simulations per day")->check(CLI::Range(1, 1000));
  app.add_option("--mask", mask_deg, "elevation mask, deg")->check(CLI::Range(0.0, 60.0));
  app.add_option("--half-day", half_day, "day NAME for the half-day-ahead check (fit 00-12 h, predict 12-24 h)");
  app.add_option("--only", only, "leave out this station only");
  app.add_option("--without", g_without, "switch a simulated term off: scale, gradient, orbit, iono, multipath, white");
  app.add_flag("--default-world", default_world,
               "instead: the built-in default world (no fit) against every day, as the issue measured it");
  app.add_option("--profile", profile, "instead: this receiver profile (ublox_m8, geodetic) against every day");
  app.add_flag("--filtered", g_filtered,
               "simulate with the whole default receiver (navigation filter, 1 Hz) at the antenna instead of "
               "solving simulated observations epoch by epoch");
  app.add_option("--csv", csv_path, "also write title,metric,real,sim_mean,sim_sd,rel_pct rows here");
  std::string gain_letters;
  std::vector<std::string> gain_days;
  app.add_option("--gain-day", gain_days, "with --gain: a day (NAME of a --day) to compare; the others train");
  app.add_option("--gain", gain_letters,
                 "instead: for each day with these systems (RINEX letters, e.g. G,R,E,C) the size metrics against "
                 "GPS alone, real and simulated, the model fitted (GPS) on the other stations' days");
  CLI11_PARSE(app, argc, argv);
  const double mask_rad = mask_deg * kDegToRad;

  std::vector<Day> days;
  for (const std::string& a : day_args) {
    std::vector<std::string> f;
    std::size_t pos = 0;
    for (std::size_t end; (end = a.find(',', pos)) != std::string::npos; pos = end + 1) f.push_back(a.substr(pos, end - pos));
    f.push_back(a.substr(pos));
    if (f.size() != 4) throw Error("--day: '" + a + "' is not NAME,STATION,OBS,NAV");
    Day d;
    d.name = f[0];
    d.station = f[1];
    d.obs = observation::read_rinex_obs(f[2]);
    d.nav = orbit::read_rinex_nav(f[3]);
    d.store = std::make_unique<orbit::EphemerisStore>(d.nav.ephemerides);
    d.arp = cli::antenna_reference_point(d.obs.header, f[2]);
    days.push_back(std::move(d));
  }
  const config::Config base = config::default_config();
  std::ofstream csv_file;
  std::ostream* csv = nullptr;
  if (!csv_path.empty()) {
    csv_file.open(csv_path);
    if (!csv_file) throw Error(csv_path, 0, "cannot open for writing");
    csv = &csv_file;
    *csv << "title,metric,real,sim_mean,sim_sd,rel_pct\n";
  }
  std::ostream& out = std::cout;
  std::vector<std::string> stations;
  for (const Day& d : days)
    if (std::find(stations.begin(), stations.end(), d.station) == stations.end()) stations.push_back(d.station);

  std::vector<std::pair<std::string, Summary>> summary;
  if (!gain_letters.empty()) {
    const std::optional<SystemSet> multi = parse_systems(gain_letters);
    if (!multi || multi->empty()) throw Error("--gain: '" + gain_letters + "' is not a list of RINEX system letters");
    out << "### Multi-system gain (" << seeds << " seeds, mask " << mask_deg << " deg, systems " << gain_letters
        << ")\n";
    const auto is_gain_day = [&](const Day& d) {
      return std::find(gain_days.begin(), gain_days.end(), d.name) != gain_days.end();
    };
    for (const Day& d : days) {
      if (!is_gain_day(d) || (!only.empty() && d.station != only)) continue;
      std::vector<cli::CalibrationInput> train;  // the GPS days of the other stations
      for (const Day& o : days)
        if (o.station != d.station && !is_gain_day(o)) train.push_back(input_of(o, o.obs, mask_rad));
      const world::WorldConfig w =
          train.empty() ? base.world : cli::fitted_world(cli::calibrate(train, base), base.world);
      const Comparison g = compare(d.name + " GPS", d, d.obs, w, base, mask_rad, seeds);
      const Comparison m = compare(d.name + " " + gain_letters, d, d.obs, w, base, mask_rad, seeds, *multi);
      summary.emplace_back(g.title, print(g, out, csv));
      summary.emplace_back(m.title, print(m, out, csv));
      print_gain(d.name + ": " + gain_letters + " over GPS", g, m, out, csv);
      out.flush();
    }
    half_day.clear();
    stations.clear();
  } else if (default_world || !profile.empty()) {
    const std::string what = default_world ? "the built-in default world" : "profile " + profile;
    out << "### " << what << " (" << seeds << " seeds, mask " << mask_deg << " deg)\n";
    for (const Day& d : days) {
      pipeline::PipelineConfig pc{base.world, base.receiver};
      if (!profile.empty())
        pc = pipeline::apply_profile(pc, pipeline::receiver_profile(profile), geo::lla_from_ecef(d.arp).lat_rad);
      const Comparison c = compare(d.name + " (" + what + ")", d, d.obs, pc.world, base, mask_rad, seeds);
      summary.emplace_back(d.name, print(c, out, csv));
    }
    half_day.clear();
    stations.clear();
  } else {
    out << "### Leave one station out (" << seeds << " seeds, mask " << mask_deg << " deg)\n";
  }
  for (const std::string& held : stations) {
    if (!only.empty() && held != only) continue;
    std::vector<cli::CalibrationInput> train;
    for (const Day& d : days)
      if (d.station != held) train.push_back(input_of(d, d.obs, mask_rad));
    if (train.empty()) continue;
    const cli::CalibrationResult fit = cli::calibrate(train, base);
    out << "\n### " << held << " held out\n";
    print_fit(fit, out);
    for (const Day& d : days) {
      if (d.station != held) continue;
      const Comparison c = compare(d.name + " (fit without " + held + ")", d, d.obs, cli::fitted_world(fit, base.world),
                                   base, mask_rad, seeds);
      summary.emplace_back(d.name, print(c, out, csv));
      out.flush();
    }
  }
  if (!half_day.empty()) {
    const auto it = std::find_if(days.begin(), days.end(), [&](const Day& d) { return d.name == half_day; });
    if (it == days.end()) throw Error("--half-day: no day named " + half_day);
    const observation::ObsData first = hours(it->obs, 0.0, 12.0), second = hours(it->obs, 12.0, 24.0);
    // The station's morning alone, then the morning pooled with the other
    // stations' days (what a user with more data would fit).
    std::vector<cli::CalibrationInput> site{input_of(*it, first, mask_rad)}, pooled = site;
    for (const Day& d : days)
      if (d.station != it->station) pooled.push_back(input_of(d, d.obs, mask_rad));
    for (const auto& [label, in] : {std::pair{"00-12 h", site}, std::pair{"00-12 h + the other stations", pooled}}) {
      const cli::CalibrationResult fit = cli::calibrate(in, base);
      out << "\n### Half day ahead: " << half_day << ", fit on " << label << "\n";
      print_fit(fit, out);
      const std::string title = half_day + " 12-24 h (fit on " + label + ")";
      const Comparison c = compare(title, *it, second, cli::fitted_world(fit, base.world), base, mask_rad, seeds);
      summary.emplace_back(title, print(c, out, csv));
    }
  }
  out << "\n### Summary\n\n| day | mean abs rel. diff. | largest | corr. time | seed criterion mean / sd | "
         "seed-to-seed spread | perfect model |\n|---|---|---|---|---|---|---|\n";
  for (const auto& [name, s] : summary)
    out << fmt::format("| {} | {:.1f} % | {:.1f} % | {:+.1f} % | {:+.1f} / {:+.1f} % | {:.1f} % | {:.1f} % |\n", name,
                       s.mean_abs_pct, s.max_abs_pct, s.corr_pct, s.seed_mean_pct, s.seed_sd_pct, s.spread_pct,
                       s.floor_pct);
  return 0;
}

}  // namespace
}  // namespace gnssemu::validation

int main(int argc, char** argv) {
  try {
    return gnssemu::validation::run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "errmodel_validation: " << e.what() << '\n';
    return 1;
  }
}

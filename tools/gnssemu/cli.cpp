// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/cli.hpp"
#include "tools/gnssemu/ctl.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "config/setup/device_setup.hpp"
#include "config/setup/footprint_file.hpp"
#include "config/setup/nav_setup.hpp"
#include "config/receiver_config.hpp"
#include "config/scenario_file.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/observation/rinex_obs.hpp"
#include "core/orbit/almanac.hpp"
#include "core/orbit/constellation.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/ubx/config/ubx_gnss.hpp"
#include "core/scene/scene.hpp"
#include "tools/gnssemu/base_command.hpp"
#include "tools/gnssemu/batch/batch.hpp"
#include "tools/gnssemu/bench_multipath.hpp"
#include "tools/gnssemu/stations/calibrate.hpp"
#include "tools/gnssemu/report/plot.hpp"
#include "tools/gnssemu/report/report.hpp"
#include "tools/gnssemu/batch/rinex_output.hpp"
#include "tools/gnssemu/satpos.hpp"
#include "tools/gnssemu/batch/sats_csv.hpp"
#include "tools/gnssemu/sky.hpp"
#include "tools/gnssemu/stations/spp.hpp"
#include "tools/gnssemu/sweep/sweep_cli.hpp"
#include "tools/gnssemu/batch/truth_csv.hpp"
#include "tools/gnssemu/version.hpp"

namespace gnssemu::cli {

namespace {

constexpr int kMaxWeek = 9999;

struct TimeArgs {
  int week = -1;
  double tow_s = -1.0;
};

struct SiteArgs {
  double lat_deg = 0.0, lon_deg = 0.0, height_m = 0.0;
  double mask_deg = 5.0;
};

struct SceneArgs {
  std::string mesh_path;
  std::vector<double> origin;  ///< lat_deg, lon_deg, height_m; empty: the site
  // Mirrors the [scene] keys of the config (docs/scene.md), same defaults.
  int rays = scene::SearchConfig{}.rays;
  int azimuth_rays = scene::SearchConfig{}.azimuth_rays;
  int bounces = scene::SearchConfig{}.max_bounces;
  double match_factor = scene::SearchConfig{}.match_factor;
  double min_arrival_elevation_deg = scene::SearchConfig{}.min_arrival_el_rad * kRadToDeg;
  double max_loss_db = scene::SearchConfig{}.max_loss_db;
  double reflection_loss_db = config::SceneConfig{}.reflection_loss_db;
  std::vector<double> offset_m;  ///< east, north, up; empty: 0, 0, 0
  double yaw_deg = scene::Placement{}.yaw_rad * kRadToDeg;
  double scale = scene::Placement{}.scale;
  std::string up_axis = scene::Placement{}.y_up ? "y" : "z";
};

struct BatchArgs {
  std::string config_path, truth_path, nmea_path, errors_path, ubx_path;
  std::string scenario_path;   ///< --scenario
  std::string vehicle, receiver;  ///< --vehicle / --receiver: one receiver of a fleet's file
  std::string sats_path;       ///< --sats
  std::string report_dir;      ///< --report
  std::string reference_path;  ///< --cn0-reference (with --report)
  std::optional<std::string> systems;  ///< --systems: RINEX letters; none: the config's [receiver] constellations
  std::string rinex_obs_path, rinex_nav_path;  ///< --rinex-obs, --rinex-nav
  std::string preset;          ///< --preset: "rtklib" or empty
  std::optional<int> bands;    ///< --bands: 1 or 2; none: the config's [receiver] bands
};

/// Where satpos, sky and dop take their satellites from.
struct NavArgs {
  std::vector<std::string> paths;  ///< --nav, repeatable: one ephemeris store
  std::string mode = "as_is";      ///< --nav-mode
  std::string almanac;             ///< --almanac (mode almanac)
  std::optional<std::string> systems;  ///< --systems: RINEX letters; none: every system of the nav files
};

struct ObsArgs {
  std::string obs_path, station, config_path;
  std::vector<std::string> nav_paths;
  std::string preset;  ///< spp: "rtklib" or empty
  std::string systems;  ///< spp --systems: RINEX letters; empty: every system of the nav files
  double mask_deg = 5.0;
};

/// v within the core's range r, else "<option>: <v> is out of range <r>".
void check_range(const char* option, double v, const Range& r) {
  if (!std::isfinite(v)) throw Error(fmt::format("{}: {} is not a finite number", option, v));
  if (!r.contains(v)) throw Error(fmt::format("{}: {} is out of range {}", option, format_number(v), format_range(r)));
}

void check_range(const char* option, double v, double lo, double hi, bool hi_open = false) {
  if (!std::isfinite(v)) throw Error(fmt::format("{}: {} is not a finite number", option, v));
  if (v < lo || v > hi || (hi_open && v == hi)) {
    throw Error(fmt::format("{}: {} outside [{}, {}{}", option, v, lo, hi, hi_open ? ")" : "]"));
  }
}

time::GpsTime checked_time(const TimeArgs& a) {
  if (a.week < 0 || a.week > kMaxWeek) throw Error(fmt::format("--week: {} outside [0, {}]", a.week, kMaxWeek));
  check_range("--tow", a.tow_s, 0.0, kSecondsPerWeek, true);
  return time::GpsTime(a.week, a.tow_s);
}

SkyRequest checked_site(const SiteArgs& s, const time::GpsTime& t) {
  check_range("--lat", s.lat_deg, -90.0, 90.0);
  check_range("--lon", s.lon_deg, -180.0, 180.0);
  check_range("--height", s.height_m, -1.0e4, 1.0e6);
  check_range("--mask", s.mask_deg, 0.0, 90.0, true);
  SkyRequest r;
  r.t = t;
  r.rx_lla = Lla{s.lat_deg * kDegToRad, s.lon_deg * kDegToRad, s.height_m};
  r.mask_rad = s.mask_deg * kDegToRad;
  return r;
}

constexpr const char* kSystemsHelp =
    "RINEX system letters, comma-separated: G GPS, R GLONASS, E Galileo, C BeiDou, J QZSS, S SBAS (e.g. G,R,E,C,J)";

/// --systems TEXT as a set; fallback when the option was not given.
SystemSet checked_systems(const std::optional<std::string>& text, SystemSet fallback) {
  if (!text) return fallback;
  const std::optional<SystemSet> set = parse_systems(*text);
  if (!set) {
    throw Error(fmt::format("--systems: '{}' is not a list of distinct RINEX system letters: G GPS, R GLONASS, "
                            "E Galileo, C BeiDou, J QZSS, S SBAS, comma-separated (e.g. G,R,E,C,J)",
                            *text));
  }
  return *set;
}

std::string describe(const time::GpsTime& t) { return fmt::format("week {} tow {:.3f}", t.week(), t.tow_s()); }


/// The satellites at t from --nav/--nav-mode/--almanac (a store with at least
/// one healthy set of *systems valid at t; with klobuchar, the header's
/// broadcast iono). as_is serves the files' own span only (RTKLIB); relabel
/// and almanac move the data to t's date and continue past them, as the
/// daemon does. *systems: --systems, or every system the data hold; a
/// requested system the data lack is named on err.
orbit::EphemerisStore load_store(const NavArgs& a, const time::GpsTime& t, SystemSet* systems, std::ostream& err,
                                 orbit::KlobucharParams* klobuchar = nullptr) {
  const std::optional<orbit::NavMode> mode = orbit::nav_mode_from_name(a.mode);
  if (!mode) throw Error("--nav-mode: '" + a.mode + "' is not auto, as_is, relabel or almanac");
  if (*mode == orbit::NavMode::kAlmanac && a.almanac.empty()) throw Error("--nav-mode almanac needs --almanac FILE");
  if (*mode != orbit::NavMode::kAlmanac && !a.almanac.empty()) throw Error("--almanac needs --nav-mode almanac");
  if (a.paths.empty() && a.almanac.empty()) throw Error("--nav FILE is required");
  const orbit::NavData nav = a.paths.empty() ? orbit::NavData{} : orbit::read_rinex_nav_files(a.paths);
  orbit::ConstellationRequest req;
  req.mode = *mode;
  req.start = t;
  req.continue_after_data = *mode != orbit::NavMode::kAsIs;
  orbit::Constellation c;
  if (*mode == orbit::NavMode::kAsIs) {
    // The files' own span, nothing more (RTKLIB): the check below names it.
    c.source = nav.source;
    c.nav = nav;
    c.continues = false;
    c.coverage = orbit::EphemerisStore(nav.ephemerides).coverage();
  } else if (*mode == orbit::NavMode::kAlmanac) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(a.almanac, ec)) throw Error(a.almanac, 0, "almanac file not found");
    c = orbit::build_constellation(orbit::read_almanac(a.almanac, t.week()), a.almanac, nav, req);
  } else {
    c = orbit::build_constellation(nav, req);
  }
  if (klobuchar) *klobuchar = c.nav.klobuchar;
  const SystemSet held = orbit::systems_of(c.nav);
  *systems = checked_systems(a.systems, held);
  for (const SatNumbering& n : kSatNumbering) {
    if (systems->has(n.system) && !held.has(n.system)) {
      err << "gnssemu: --systems: " << c.source << " holds no " << system_name(n.system) << " (" << n.letter
          << ") ephemerides\n";
    }
  }
  orbit::EphemerisStore store(c.nav.ephemerides, c.store_options());
  for (int i = 0; i < kNumSats; ++i) {
    const SatId sat = SatId::from_index(i);
    if (systems->has(sat.system) && store.select(sat, t) != nullptr) return store;
  }
  throw Error(c.source, 0,
              fmt::format("no healthy ephemeris valid at {}{}; the data cover {}{}", describe(t),
                          a.systems ? fmt::format(" for --systems {}", systems_text(*systems).data()) : "",
                          orbit::spans_text(c.coverage),
                          *mode == orbit::NavMode::kAsIs ? " (--nav-mode relabel moves them to that date)" : ""));
}

/// An output file, or stdout for "-".
class OutputFile {
public:
  OutputFile(const std::string& path, std::ostream& stdout_stream) {
    if (path.empty()) return;
    if (path == "-") {
      stream_ = &stdout_stream;
      return;
    }
    file_ = std::make_unique<std::ofstream>(path, std::ios::binary | std::ios::trunc);
    if (!*file_) throw Error(path, 0, "cannot open for writing");
    stream_ = file_.get();
  }
  std::ostream* get() const { return stream_; }
  void close(const std::string& path) {
    if (!file_) return;
    file_->close();
    if (!*file_) throw Error(path, 0, "write failed");
  }

private:
  std::unique_ptr<std::ofstream> file_;
  std::ostream* stream_ = nullptr;
};

// One receiver of a file's vehicles as the daemon runs it: its merged
// settings (the sky still the top level's seed) and its outputs.
config::Config fleet_receiver(const config::Config& cfg, const std::string& vehicle, const std::string& receiver) {
  for (const config::VehicleConfig& v : config::resolve_vehicles(cfg)) {
    if (v.id != vehicle) continue;
    for (const config::VehicleReceiverConfig& r : v.receivers) {
      if (!receiver.empty() && r.name != receiver) continue;
      return config::receiver_config(cfg, v, r);
    }
    throw Error(cfg.source, 0, "vehicle " + vehicle + " has no receiver " + receiver);
  }
  throw Error(cfg.source, 0, "no vehicle " + vehicle + " in the file");
}

int run_batch_command(const BatchArgs& a, std::ostream& out, std::ostream& err) {
  if ((a.nmea_path == "-") + (a.errors_path == "-") + (a.ubx_path == "-") + (a.sats_path == "-") +
          (a.rinex_obs_path == "-") + (a.rinex_nav_path == "-") >
      1) {
    throw Error("--nmea, --ubx, --errors, --sats, --rinex-obs, --rinex-nav: two outputs cannot both be '-' (stdout)");
  }
  if (!a.reference_path.empty() && a.report_dir.empty()) throw Error("--cn0-reference needs --report DIR");
  config::Config cfg = config::load_config(a.config_path);
  if (!a.vehicle.empty()) cfg = fleet_receiver(cfg, a.vehicle, a.receiver);
  cfg.world.systems = checked_systems(a.systems, cfg.world.systems);
  if (a.bands) {
    if (*a.bands > config::default_bands(cfg.generation)) {
      throw Error(a.config_path, 0, "--bands " + std::to_string(*a.bands) + ": " + config::single_band_reason(cfg.generation));
    }
    cfg.receiver.bands = *a.bands;
  }
  if (a.preset == "rtklib") {
    // rnx2rtkp's single point on the receiver's own code: its models and
    // weights, a snapshot fix each epoch, no carrier smoothing.
    cfg.receiver.solver = receiver::rtklib_single_point(cfg.receiver.solver);
    cfg.receiver.filter.type = receiver::NavFilterType::kNone;
    cfg.receiver.filter.smoothing_window_s = 0.0;
  }
  const world::TruthTrack track(read_truth_csv(a.truth_path));
  for (const std::string& p : config::nav_paths(cfg)) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) throw Error(a.config_path, 0, "nav file not found: " + p);
  }
  // The truth's own dates, with the satellites dated for them as the daemon
  // dates them ([nav] mode; as_is: the truth must start inside the data).
  const orbit::Constellation c = config::make_constellation(cfg, config::load_nav(cfg), track.first());
  const SystemSet tracked = protocol::ubx::gnss_capabilities(cfg.generation).defaults.intersect(cfg.world.systems);
  err << "gnssemu batch: satellites: " << c.describe() << "; systems " << systems_text(cfg.world.systems).data()
      << " in the sky, the chip tracks " << systems_text(tracked).data() << " (its factory CFG-GNSS)\n";
  std::vector<faults::FaultEvent> scenario;
  if (!a.scenario_path.empty()) {
    scenario = config::read_scenario(a.scenario_path);
    for (const faults::FaultEvent& e : scenario) {
      if (e.type == faults::FaultType::kPort) {
        err << "gnssemu batch: " << a.scenario_path << ':' << e.line
            << ": port event not applied in batch (link faults act on the daemon's ports)\n";
      }
    }
  }
  OutputFile nmea(a.nmea_path, out);
  OutputFile errors(a.errors_path, out);
  OutputFile ubx(a.ubx_path, out);
  OutputFile sats(a.sats_path, out);
  std::vector<BatchObserver*> observers;
  std::optional<SatsCsvWriter> sats_writer;
  if (sats.get() != nullptr) observers.push_back(&sats_writer.emplace(*sats.get()));
  OutputFile rinex_obs(a.rinex_obs_path, out);
  OutputFile rinex_nav(a.rinex_nav_path, out);
  std::optional<RinexOutput> rinex;
  if (rinex_obs.get() != nullptr || rinex_nav.get() != nullptr) {
    observers.push_back(&rinex.emplace(cfg, c.nav, c.store_options(), rinex_obs.get(), rinex_nav.get()));
  }
  ReportData report;
  ReportCollector collector(report);
  if (!a.report_dir.empty()) {
    if (!a.reference_path.empty()) report.reference = read_cn0_reference(a.reference_path);
    observers.push_back(&collector);
  }
  const BatchSummary sum =
      run_batch(cfg, c.nav, track, nmea.get(), errors.get(), ubx.get(), c.store_options(), observers,
                a.scenario_path.empty() ? nullptr : &scenario);
  nmea.close(a.nmea_path);
  ubx.close(a.ubx_path);
  errors.close(a.errors_path);
  sats.close(a.sats_path);
  if (rinex) rinex->finish();
  rinex_obs.close(a.rinex_obs_path);
  rinex_nav.close(a.rinex_nav_path);
  write_summary(sum, err);
  if (!a.report_dir.empty()) {
    report.title = "gnssemu batch: " + std::filesystem::path(a.truth_path).filename().string();
    report.inputs = {"config: " + a.config_path, "truth: " + a.truth_path, "satellites: " + c.describe()};
    if (report.reference) report.inputs.push_back("C/N0 reference: " + a.reference_path);
    report.elevation_mask_deg = cfg.receiver.elevation_mask_rad * kRadToDeg;
    report.acquire_dbhz = cfg.receiver.tracking.acquire_dbhz;
    report.lose_dbhz = cfg.receiver.tracking.lose_dbhz;
    write_cn0_comparison(report, err);
    err << "gnssemu batch: report " << write_report(report, a.report_dir) << '\n';
  }
  return kExitOk;
}

/// "X,Y,Z" in metres (ECEF), e.g. a station's known coordinates.
Ecef parse_station(const std::string& text) {
  double v[3] = {0.0, 0.0, 0.0};
  std::size_t pos = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t end = text.find(',', pos);
    const std::string cell = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    try {
      std::size_t used = 0;
      v[k] = std::stod(cell, &used);
      if (used != cell.size()) throw std::invalid_argument(cell);
    } catch (const std::exception&) {
      throw Error("--station: '" + text + "' is not X,Y,Z in metres");
    }
    if (!std::isfinite(v[k])) throw Error("--station: '" + text + "' is not finite");
    if ((end == std::string::npos) != (k == 2)) throw Error("--station: '" + text + "' needs exactly X,Y,Z");
    pos = end + 1;
  }
  const Ecef p(v[0], v[1], v[2]);
  if (p.norm() < 6.0e6 || p.norm() > 7.0e6) {
    throw Error(fmt::format("--station: {} is {:.0f} m from the Earth's centre, not near the surface", text, p.norm()));
  }
  return p;
}

/// The systems spp solves with: --systems, else every ranging system with
/// ephemerides in nav (SBAS is not ranged).
SystemSet spp_systems(const std::string& letters, const orbit::NavData& nav) {
  if (!letters.empty()) {
    const std::optional<SystemSet> set = parse_systems(letters);
    if (!set) throw Error("--systems: '" + letters + "' is not a list of RINEX letters G,R,E,C,J (comma-separated, each once)");
    if (set->has(GnssSystem::kSbas)) throw Error("--systems: S: SBAS satellites are not used for ranging");
    return *set;
  }
  SystemSet set;
  for (const orbit::Ephemeris& e : nav.ephemerides)
    if (e.sat.system != GnssSystem::kSbas) set = set.with(e.sat.system);
  return set;
}

/// Observation and navigation files, both checked. Only GPS observations are
/// read (calibrate), or, with systems given, those of spp_systems(a.systems),
/// which it is set to.
std::pair<observation::ObsData, orbit::NavData> load_obs_nav(const ObsArgs& a, SystemSet* systems = nullptr) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(a.obs_path, ec)) throw Error(a.obs_path, 0, "observation file not found");
  orbit::NavData nav = orbit::read_rinex_nav_files(a.nav_paths);
  if (systems != nullptr) {
    *systems = spp_systems(a.systems, nav);
    if (systems->empty()) throw Error(nav.source, 0, "no ephemerides of a ranging system (G, R, E, C, J)");
  }
  const SystemSet read = systems != nullptr ? *systems : SystemSet::only(GnssSystem::kGps);
  observation::ObsData obs = observation::read_rinex_obs(a.obs_path, read);
  if (obs.epochs.empty()) {
    throw Error(a.obs_path, 0, fmt::format("no observation epochs of {}", systems_text(read).data()));
  }
  const orbit::EphemerisStore store(nav.ephemerides);
  const time::GpsTime t0 = obs.epochs.front().t, t1 = obs.epochs.back().t;
  if (t0 - store.last_valid() > 0.0 || store.first_valid() - t1 > 0.0) {
    throw Error(a.obs_path, 0,
                fmt::format("observations run from {} to {}, outside the nav file{} {} ({})", describe(t0),
                            describe(t1), a.nav_paths.size() > 1 ? "s" : "", nav.source,
                            orbit::spans_text(store.coverage())));
  }
  return {std::move(obs), std::move(nav)};
}

int run_spp_command(const ObsArgs& a, std::ostream& out, std::ostream& err) {
  check_range("--mask", a.mask_deg, 0.0, 90.0, true);
  std::optional<Ecef> station;
  if (!a.station.empty()) station = parse_station(a.station);
  SystemSet systems;
  const auto [obs, nav] = load_obs_nav(a, &systems);
  const config::Config base = a.config_path.empty() ? config::Config{} : config::load_config(a.config_path);
  receiver::ReceiverConfig rx = base.receiver;
  rx.elevation_mask_rad = a.mask_deg * kDegToRad;
  if (a.preset == "rtklib") rx.solver = receiver::rtklib_single_point(rx.solver);
  const SppSummary sum = write_spp(obs, nav, rx, station, out, systems, a.preset == "rtklib");
  err << fmt::format("gnssemu spp: {} epochs, {} with a fix\n", sum.epochs, sum.fixes);
  return kExitOk;
}

/// calibrate: one or several station-days (--obs, --nav, --station given as
/// often, matched in order).
struct CalibrateArgs {
  std::vector<std::string> obs_paths, nav_paths, stations;
  std::string out_path, config_path, residuals_path;
  std::optional<std::string> systems;  ///< --systems: RINEX letters; none: GPS
  double mask_deg = 5.0;
};

int run_calibrate_command(const CalibrateArgs& a, std::ostream& out, std::ostream& err) {
  check_range("--mask", a.mask_deg, 0.0, 90.0, true);
  // The fit solves with one receiver clock: GPS alone until the solver
  // estimates one per system.
  constexpr SystemSet kCalibrateSystems = SystemSet::only(GnssSystem::kGps);
  const SystemSet systems = checked_systems(a.systems, kCalibrateSystems);
  if (systems.without(GnssSystem::kGps) != SystemSet()) {
    throw Error(fmt::format("--systems {}: calibrate fits GPS alone so far (supported: {})",
                            systems_text(systems).data(), systems_text(kCalibrateSystems).data()));
  }
  if (a.nav_paths.size() != a.obs_paths.size() || a.stations.size() != a.obs_paths.size()) {
    throw Error(fmt::format("calibrate: {} --obs, {} --nav and {} --station: give one of each per station-day",
                            a.obs_paths.size(), a.nav_paths.size(), a.stations.size()));
  }
  config::Config base = a.config_path.empty() ? config::default_config() : config::load_config(a.config_path);
  std::vector<observation::ObsData> obs;
  std::vector<orbit::NavData> nav;
  std::vector<Ecef> station;
  for (std::size_t i = 0; i < a.obs_paths.size(); ++i) {
    station.push_back(parse_station(a.stations[i]));
    ObsArgs one;
    one.obs_path = a.obs_paths[i];
    one.nav_paths = {a.nav_paths[i]};
    auto [o, n] = load_obs_nav(one);
    obs.push_back(std::move(o));
    nav.push_back(std::move(n));
  }
  std::vector<CalibrationInput> in(obs.size());
  for (std::size_t i = 0; i < obs.size(); ++i) {
    in[i].obs = &obs[i];
    in[i].nav = &nav[i];
    in[i].nav_path = a.nav_paths[i];
    in[i].station_m = station[i];
    in[i].mask_rad = a.mask_deg * kDegToRad;
  }
  const CalibrationResult r = calibrate(in, base);
  const std::string out_dir = std::filesystem::absolute(a.out_path).parent_path().string();
  std::ofstream f(a.out_path, std::ios::binary | std::ios::trunc);
  if (!f) throw Error(a.out_path, 0, "cannot open for writing");
  f << calibration_toml(r, out_dir);
  f.close();
  if (!f) throw Error(a.out_path, 0, "write failed");
  if (!a.residuals_path.empty()) {
    std::ofstream rf(a.residuals_path, std::ios::binary | std::ios::trunc);
    if (!rf) throw Error(a.residuals_path, 0, "cannot open for writing");
    write_residuals_csv(r, rf);
    rf.close();
    if (!rf) throw Error(a.residuals_path, 0, "write failed");
  }
  write_calibration_report(r, out);
  err << "gnssemu calibrate: wrote " << a.out_path << '\n';
  return kExitOk;
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{"gnssemu: offline tools of the GNSS receiver emulator (CSV on stdout, see docs/cli.md)", "gnssemu"};
  app.require_subcommand(1);

  TimeArgs time_args;
  SiteArgs site;
  NavArgs nav_args;
  BatchArgs batch;

  auto add_time = [&](CLI::App* sub) {
    sub->add_option("--nav", nav_args.paths, "RINEX 2.x/3.x navigation file, plain or .gz; repeat for several")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    sub->add_option("--nav-mode", nav_args.mode,
                    "as_is: the files' own dates; relabel: moved by whole days to --week/--tow; almanac: --almanac "
                    "moved and propagated; auto: as_is if the files cover the time, else relabel")
        ->check(CLI::IsMember({"auto", "as_is", "relabel", "almanac"}))
        ->capture_default_str();
    sub->add_option("--almanac", nav_args.almanac, "YUMA or SEM almanac (with --nav-mode almanac)");
    sub->add_option("--systems", nav_args.systems,
                    std::string(kSystemsHelp) + "; default: every system in the nav files");
    sub->add_option("--week", time_args.week, "GPS week (continuous, not mod 1024)")->required();
    sub->add_option("--tow", time_args.tow_s, "GPS time of week, s [0, 604800)")->required();
  };
  auto add_site = [&](CLI::App* sub) {
    add_time(sub);
    sub->add_option("--lat", site.lat_deg, "receiver latitude, deg [-90, 90]")->required();
    sub->add_option("--lon", site.lon_deg, "receiver longitude, deg [-180, 180]")->required();
    sub->add_option("--height", site.height_m, "receiver height above the WGS-84 ellipsoid, m")->required();
    sub->add_option("--mask", site.mask_deg, "elevation mask, deg [0, 90)")->capture_default_str();
  };

  CLI::App* satpos = app.add_subcommand("satpos", "broadcast satellite position, velocity and clock at a GPS time");
  add_time(satpos);
  CLI::App* sky = app.add_subcommand("sky", "azimuth, elevation and range of the satellites above the mask");
  add_site(sky);
  SceneArgs scene_args;
  sky->add_option("--scene", scene_args.mesh_path, "buildings: .obj/.ply/.toml mesh in the local ENU frame of --scene-origin");
  sky->add_option("--scene-origin", scene_args.origin, "scene frame origin LAT_DEG,LON_DEG,HEIGHT_M (default: the site)")
      ->delimiter(',')
      ->expected(3);
  sky->add_option("--rays", scene_args.rays, "reflection search: hemisphere launch rays ([scene] rays)")->capture_default_str();
  sky->add_option("--azimuth-rays", scene_args.azimuth_rays,
                  "reflection search: cone rays per blocked satellite on vertical/horizontal scenes, 0: hemisphere")
      ->capture_default_str();
  sky->add_option("--bounces,--max-bounces", scene_args.bounces, "reflection search: bounces at most [1, 32]")
      ->capture_default_str();
  sky->add_option("--match-factor", scene_args.match_factor, "reflection search: candidate tolerance in ray spacings")
      ->capture_default_str();
  sky->add_option("--min-arrival-elevation-deg", scene_args.min_arrival_elevation_deg,
                  "reflected arrivals from below this elevation are rejected, deg [-89, 89]")
      ->capture_default_str();
  sky->add_option("--max-loss-db", scene_args.max_loss_db, "paths weaker than this are not received, dB")
      ->capture_default_str();
  sky->add_option("--reflection-loss-db", scene_args.reflection_loss_db, "loss per reflection, dB [0, 100]")
      ->capture_default_str();
  sky->add_option("--offset-m", scene_args.offset_m, "mesh placement: model origin in ENU E,N,U m")
      ->delimiter(',')
      ->expected(3);
  sky->add_option("--yaw-deg", scene_args.yaw_deg, "mesh placement: rotation about up, deg, east towards north")
      ->capture_default_str();
  sky->add_option("--scale", scene_args.scale, "mesh placement: model units to metres (> 0)")->capture_default_str();
  sky->add_option("--up-axis", scene_args.up_axis, "mesh placement: z, or y for Y-up exports")
      ->check(CLI::IsMember({"z", "y"}))
      ->capture_default_str();
  CLI::App* dop = app.add_subcommand("dop", "dilutions of precision of the satellites above the mask");
  add_site(dop);
  CLI::App* batch_cmd =
      app.add_subcommand("batch", "run the receiver over a truth trajectory faster than real time");
  batch_cmd->add_option("--config", batch.config_path, "gnssemu TOML configuration")->required();
  batch_cmd->add_option("--truth", batch.truth_path, "truth trajectory CSV")->required();
  batch_cmd->add_option("--nmea", batch.nmea_path, "write the NMEA stream here ('-' = stdout)");
  batch_cmd->add_option("--ubx", batch.ubx_path, "write the UBX stream here ('-' = stdout)");
  batch_cmd->add_option("--errors", batch.errors_path, "write per-epoch fix errors CSV here ('-' = stdout)");
  batch_cmd->add_option("--rinex-obs", batch.rinex_obs_path,
                        "write the receiver's raw measurements as RINEX 3.04 observations here ('-' = stdout)");
  batch_cmd->add_option("--rinex-nav", batch.rinex_nav_path,
                        "write the broadcast sets the receiver measured with as RINEX 3.04 navigation here");
  batch_cmd->add_option("--preset", batch.preset,
                        "rtklib: the receiver solves as rnx2rtkp's single point (its weights and models, snapshot "
                        "least squares, no smoothing)")
      ->check(CLI::IsMember({"rtklib"}));
  batch_cmd->add_option("--scenario", batch.scenario_path, "fault scenario TOML ([[event]] tables, docs/faults.md)");
  batch_cmd->add_option("--vehicle", batch.vehicle,
                        "run this [[vehicle]] / [fleet] vehicle's receiver as gnssemud runs it (its settings, the "
                        "top level's sky)");
  batch_cmd->add_option("--receiver", batch.receiver, "with --vehicle: this receiver of it (default: its first)")
      ->needs("--vehicle");
  batch_cmd->add_option("--sats", batch.sats_path,
                        "write per epoch and satellite gps_week,tow_s,sat,prn,az_deg,el_deg,cn0_dbhz,tracked,used here "
                        "('-' = stdout)");
  batch_cmd->add_option("--report", batch.report_dir, "write an HTML report with plots to DIR/report.html");
  batch_cmd->add_option("--systems", batch.systems,
                        std::string(kSystemsHelp) + "; default: the config's [receiver] constellations");
  batch_cmd->add_option("--bands", batch.bands, "signals tracked per satellite, 1 or 2 (2: a generation = \"f9p\" config); default: the config's [receiver] bands")
      ->check(CLI::Range(1, 2));
  batch_cmd->add_option("--cn0-reference", batch.reference_path,
                        "a real receiver's C/N0 for the report: NMEA log (GSV) or CSV with el_deg,cn0_dbhz");
  PlotArgs plot_args;
  CLI::App* plot = app.add_subcommand("plot", "HTML report from batch / bench multipath CSVs");
  plot->add_option("--errors", plot_args.errors_path, "batch --errors CSV");
  plot->add_option("--sats", plot_args.sats_path, "batch --sats CSV");
  plot->add_option("--multipath", plot_args.multipath_path, "bench multipath CSV");
  plot->add_option("--cn0-reference", plot_args.reference_path,
                   "a real receiver's C/N0: NMEA log (GSV) or CSV with el_deg,cn0_dbhz");
  plot->add_option("--mask", plot_args.mask_deg, "elevation mask to draw, deg [0, 90)");
  plot->add_option("--out", plot_args.out_dir, "report folder (report.html is written there)")->required();
  ObsArgs obs_args;
  CLI::App* spp = app.add_subcommand(
      "spp", "single-point positions from a real RINEX observation file (GPS/QZSS/GLONASS C1C, Galileo E1, BeiDou B1I)");
  spp->add_option("--obs", obs_args.obs_path, "RINEX 2.11/3.x observation file (.gz read too)")->required();
  spp->add_option("--nav", obs_args.nav_paths, "RINEX 2.x/3.x navigation file, plain or .gz; repeat for several")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  spp->add_option("--mask", obs_args.mask_deg, "elevation mask, deg [0, 90)")->capture_default_str();
  spp->add_option("--station", obs_args.station, "known position X,Y,Z (ECEF m): adds e_m,n_m,u_m columns");
  spp->add_option("--systems", obs_args.systems,
                  "systems to solve with, RINEX letters G,R,E,C,J (default: every system in the nav files)");
  spp->add_option("--config", obs_args.config_path, "take the solver settings (weights, corrections) from this config");
  spp->add_option("--preset", obs_args.preset,
                  "rtklib: RTKLIB rnx2rtkp single-point weights, corrections and residual test (after --config)")
      ->check(CLI::IsMember({"rtklib"}));
  CalibrateArgs cal;
  CLI::App* calib = app.add_subcommand(
      "calibrate", "fit the error model to real receivers at known positions (one or several station-days)");
  calib->add_option("--obs", cal.obs_paths, "RINEX 2.11/3.x observation file (.gz read too); repeat per day")
      ->required();
  calib->add_option("--nav", cal.nav_paths, "RINEX 2.x/3.x navigation file of that day; repeat per day")->required();
  calib->add_option("--station", cal.stations, "known antenna position X,Y,Z (ECEF m) of that day; repeat per day")
      ->required();
  calib->add_option("--out", cal.out_path, "write the fitted TOML configuration here")->required();
  calib->add_option("--mask", cal.mask_deg, "elevation mask, deg [0, 90)")->capture_default_str();
  calib->add_option("--config", cal.config_path, "start from this config (default: the built-in one)");
  calib->add_option("--residuals", cal.residuals_path, "also write every satellite residual used as CSV");
  calib->add_option("--systems", cal.systems, std::string(kSystemsHelp) + "; default and supported so far: G");
  CLI::App* bench = app.add_subcommand("bench", "benchmarks that print time next to the error it costs");
  bench->require_subcommand(1);
  CLI::App* bench_mp = bench->add_subcommand("multipath", "scene stage: time per epoch vs error against a dense reference");
  BenchMultipathArgs bmp;
  int bench_week = -1;
  double bench_tow_s = -1.0;
  bench_mp->add_option("--scene", bmp.scene_path, "buildings: .obj/.ply/.toml in the ENU frame of --origin");
  bench_mp->add_option("--city", bmp.city_blocks, "instead of --scene: procedural city of N x N blocks (N=10: ~160k triangles)");
  bench_mp->add_option("--write-city", bmp.write_city, "write the procedural city as OBJ");
  bench_mp->add_option("--origin", bmp.origin, "scene frame origin LAT_DEG,LON_DEG,HEIGHT_M")->delimiter(',')->expected(3)->required();
  bench_mp->add_option("--nav", bmp.nav_paths, "RINEX navigation file, plain or .gz; repeat for several")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  bench_mp->add_option("--week", bench_week, "GPS week of the first epoch (default: nav start + 2 h)");
  bench_mp->add_option("--tow", bench_tow_s, "GPS time of week of the first epoch, s");
  bench_mp->add_option("--path", bmp.path_en_m, "drive polyline E0,N0,E1,N1,... (ENU m)")->delimiter(',')->required();
  bench_mp->add_option("--speed", bmp.speed_m_s, "drive speed, m/s")->capture_default_str();
  bench_mp->add_option("--rate", bmp.rate_hz, "epoch rate, Hz")->capture_default_str();
  bench_mp->add_option("--antenna-height", bmp.antenna_height_m, "antenna above the scene's z = 0, m")->capture_default_str();
  bench_mp->add_option("--mask", bmp.mask_deg, "elevation mask, deg")->capture_default_str();
  bench_mp->add_option("--reference-rays", bmp.reference_rays, "dense reference rays")->capture_default_str();
  bench_mp->add_option("--repeats", bmp.repeats, "timing passes; the median one gives mean, p95 and max")
      ->capture_default_str();
  bench_mp->add_option("--settings", bmp.settings,
                       "instead of the sweep: AZIMUTH_RAYS,RAYS,BOUNCES,REUSE_M,REUSE_DEG[,...] (groups of 5)")
      ->delimiter(',');
  bench_mp->add_option("--max-loss-db", bmp.max_loss_db, "loss cap of every path, dB (1000: off)")->capture_default_str();
  CLI::App* version = app.add_subcommand("version", "versions of gnssemu, Embree and GeographicLib");
  CtlArgs ctl_args;
  CLI::App* ctl = app.add_subcommand("ctl", "talk to a running gnssemud on its control socket ([control] socket)");
  ctl->add_option("--socket", ctl_args.socket, "the daemon's control socket path")->required();
  ctl->add_option("--timeout", ctl_args.timeout_s, "seconds to wait for the reply (0, 600]")
      ->check(CLI::Range(1e-3, 600.0))
      ->capture_default_str();
  ctl->add_option("--vehicle", ctl_args.vehicle, "act on this vehicle's receivers only (default: every receiver)");
  ctl->add_option("--receiver", ctl_args.receiver, "with --vehicle: act on this receiver of it only");
  ctl->require_subcommand(1);
  CLI::App* ctl_status = ctl->add_subcommand("status", "fix, satellites (C/N0, state), faults, counters as JSON");
  CLI::App* ctl_inject = ctl->add_subcommand("inject", "add the events of a scenario file, start times from now");
  ctl_inject->add_option("file", ctl_args.file, "scenario file (TOML [[event]] tables, docs/faults.md)")->required();
  CLI::App* ctl_clear = ctl->add_subcommand("clear", "remove every fault (injected and scenario)");
  sweep::SweepCommand sweep_cmd(app);
  BaseCommand base_cmd(app);

  // CLI11 reports a mistyped subcommand only as "A subcommand is required".
  const auto known = [&](const std::string& name) {
    for (const CLI::App* sub : {satpos, sky, dop, batch_cmd, plot, spp, calib, bench, version, ctl, sweep_cmd.app(),
                               base_cmd.app()}) {
      if (sub->get_name() == name) return true;
    }
    return false;
  };
  // `gnssemu --version` as every packaged tool has it (same text as `gnssemu version`).
  if (argc == 2 && std::string_view(argv[1]) == "--version") {
    write_version(out);
    return kExitOk;
  }
  if (argc > 1 && argv[1][0] != '-' && !known(argv[1])) {
    err << "gnssemu: unknown subcommand '" << argv[1] << "' (satpos, sky, dop, batch, plot, spp, calibrate, bench, ctl, sweep, base, version; see --help)\n";
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e, out, err) == 0 ? kExitOk : kExitUsage;
  }

  try {
    if (*version) {
      write_version(out);
    } else if (*ctl) {
      ctl_args.command = *ctl_status ? "status" : *ctl_inject ? "inject" : "clear";
      (void)ctl_clear;
      return run_ctl(ctl_args, out, err);
    } else if (*satpos) {
      const time::GpsTime t = checked_time(time_args);
      SystemSet systems;
      const orbit::EphemerisStore store = load_store(nav_args, t, &systems, err);
      write_satpos(store, t, out, systems);
    } else if (*sky || *dop) {
      const time::GpsTime t = checked_time(time_args);
      SkyRequest req = checked_site(site, t);
      const orbit::EphemerisStore store = load_store(nav_args, t, &req.systems, err, &req.klobuchar);
      if (*sky) {
        SkyRequest sreq = req;
        std::unique_ptr<scene::Scene> buildings;
        if (!scene_args.mesh_path.empty()) {
          sreq.scene_origin = req.rx_lla;
          if (!scene_args.origin.empty()) {
            check_range("--scene-origin latitude", scene_args.origin[0], -90.0, 90.0);
            check_range("--scene-origin longitude", scene_args.origin[1], -180.0, 180.0);
            check_range("--scene-origin height", scene_args.origin[2], -1.0e4, 1.0e6);  // as --height
            sreq.scene_origin = Lla{scene_args.origin[0] * kDegToRad, scene_args.origin[1] * kDegToRad, scene_args.origin[2]};
          }
          sreq.search.rays = scene_args.rays;
          sreq.search.azimuth_rays = scene_args.azimuth_rays;
          sreq.search.max_bounces = scene_args.bounces;
          sreq.search.match_factor = scene_args.match_factor;
          check_range("--min-arrival-elevation-deg", scene_args.min_arrival_elevation_deg,
                      scene::SearchRanges::min_arrival_elevation_deg);
          sreq.search.min_arrival_el_rad = scene_args.min_arrival_elevation_deg * kDegToRad;
          check_range("--max-loss-db", scene_args.max_loss_db, scene::SearchRanges::max_loss_db);
          sreq.search.max_loss_db = scene_args.max_loss_db;
          scene::validate(sreq.search);
          check_range("--reflection-loss-db", scene_args.reflection_loss_db, scene::SceneRanges::reflection_loss_db);
          scene::Placement place;
          if (!scene_args.offset_m.empty()) {
            for (const double v : scene_args.offset_m) check_range("--offset-m", v, scene::PlacementRanges::offset_m);
            place.offset_m = Enu(scene_args.offset_m[0], scene_args.offset_m[1], scene_args.offset_m[2]);
          }
          check_range("--yaw-deg", scene_args.yaw_deg, scene::PlacementRanges::yaw_deg);
          place.yaw_rad = scene_args.yaw_deg * kDegToRad;
          check_range("--scale", scene_args.scale, scene::PlacementRanges::scale);
          place.scale = scene_args.scale;
          place.y_up = scene_args.up_axis == "y";
          const scene::Mesh mesh = config::load_mesh(scene_args.mesh_path, place);
          if (const std::string w = scene::skip_report(mesh.stats); !w.empty()) err << "gnssemu sky: " << w << '\n';
          buildings = std::make_unique<scene::Scene>(mesh);
          buildings->set_default_loss_db(scene_args.reflection_loss_db);
          sreq.scene = buildings.get();
        }
        write_sky(store, sreq, out);
      } else if (const DopResult d = write_dop(store, req, out); !d.defined) {
        err << "gnssemu dop: DOP undefined: " << d.nsat << " satellites above the mask"
            << (d.nsat < 4 ? " (4 needed)\n" : " in a singular geometry\n");
      }
    } else if (*batch_cmd) {
      return run_batch_command(batch, out, err);
    } else if (sweep_cmd.parsed()) {
      return sweep_cmd.run(out, err);
    } else if (base_cmd.parsed()) {
      return base_cmd.run(out, err);
    } else if (*plot) {
      if (!std::isnan(plot_args.mask_deg)) check_range("--mask", plot_args.mask_deg, 0.0, 90.0, true);
      run_plot(plot_args, out, err);
    } else if (*spp) {
      return run_spp_command(obs_args, out, err);
    } else if (*calib) {
      return run_calibrate_command(cal, out, err);
    } else if (*bench_mp) {
      if (bmp.scene_path.empty() == (bmp.city_blocks <= 0)) throw Error("bench multipath: give either --scene or --city");
      if (bench_week >= 0 || bench_tow_s >= 0.0) bmp.start = checked_time(TimeArgs{bench_week, bench_tow_s});
      run_bench_multipath(bmp, out, err);
    }
  } catch (const Error& e) {
    err << "gnssemu: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::exception& e) {
    err << "gnssemu: " << e.what() << '\n';
    return kExitBadInput;
  }
  out.flush();
  return kExitOk;
}

}  // namespace gnssemu::cli

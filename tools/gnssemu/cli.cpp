#include "tools/gnssemu/cli.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "config/config.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "tools/gnssemu/batch.hpp"
#include "tools/gnssemu/satpos.hpp"
#include "tools/gnssemu/sky.hpp"
#include "tools/gnssemu/truth_csv.hpp"
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

struct BatchArgs {
  std::string config_path, truth_path, nmea_path, errors_path;
};

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

std::string describe(const time::GpsTime& t) { return fmt::format("week {} tow {:.3f}", t.week(), t.tow_s()); }

/// Ephemeris store of a nav file that has at least one healthy set valid at t
/// (and, if klobuchar is given, the header's broadcast ionosphere).
orbit::EphemerisStore load_store(const std::string& nav_path, const time::GpsTime& t,
                                 orbit::KlobucharParams* klobuchar = nullptr) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(nav_path, ec)) throw Error(nav_path, 0, "nav file not found");
  const orbit::NavData nav = orbit::read_rinex_nav(nav_path);
  if (klobuchar) *klobuchar = nav.klobuchar;
  orbit::EphemerisStore store(nav.ephemerides);
  if (store.size() == 0) throw Error(nav_path, 0, "no GPS ephemerides in the file");
  for (int prn = 1; prn <= kMaxGpsPrn; ++prn) {
    if (store.select(prn, t) != nullptr) return store;
  }
  throw Error(nav_path, 0,
              fmt::format("no healthy ephemeris valid at {}; the file covers {} to {}", describe(t),
                          describe(store.first_valid()), describe(store.last_valid())));
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

int run_batch_command(const BatchArgs& a, std::ostream& out, std::ostream& err) {
  if (a.nmea_path == "-" && a.errors_path == "-") throw Error("--nmea and --errors cannot both be '-' (stdout)");
  const config::Config cfg = config::load_config(a.config_path);
  const TruthTrack track(read_truth_csv(a.truth_path));
  std::error_code ec;
  if (!std::filesystem::is_regular_file(cfg.nav_file, ec)) {
    throw Error(a.config_path, 0, "nav file not found: " + cfg.nav_file);
  }
  const orbit::NavData nav = orbit::read_rinex_nav(cfg.nav_file);
  const orbit::EphemerisStore store(nav.ephemerides);
  if (store.size() == 0) throw Error(cfg.nav_file, 0, "no GPS ephemerides in the file");
  if (track.first() - store.last_valid() > 0.0 || store.first_valid() - track.last() > 0.0) {
    throw Error(a.truth_path, 0,
                fmt::format("truth runs from {} to {}, outside the nav file {} ({} to {})", describe(track.first()),
                            describe(track.last()), cfg.nav_file, describe(store.first_valid()),
                            describe(store.last_valid())));
  }
  OutputFile nmea(a.nmea_path, out);
  OutputFile errors(a.errors_path, out);
  const BatchSummary sum = run_batch(cfg, nav, track, nmea.get(), errors.get());
  nmea.close(a.nmea_path);
  errors.close(a.errors_path);
  write_summary(sum, err);
  return kExitOk;
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{"gnssemu: offline tools of the GNSS receiver emulator (CSV on stdout, see docs/cli.md)", "gnssemu"};
  app.require_subcommand(1);

  TimeArgs time_args;
  SiteArgs site;
  std::string nav_path;
  BatchArgs batch;

  auto add_time = [&](CLI::App* sub) {
    sub->add_option("--nav", nav_path, "RINEX 2.x/3.x navigation file")->required();
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
  CLI::App* dop = app.add_subcommand("dop", "dilutions of precision of the satellites above the mask");
  add_site(dop);
  CLI::App* batch_cmd =
      app.add_subcommand("batch", "run the receiver over a truth trajectory faster than real time");
  batch_cmd->add_option("--config", batch.config_path, "gnssemu TOML configuration")->required();
  batch_cmd->add_option("--truth", batch.truth_path, "truth trajectory CSV")->required();
  batch_cmd->add_option("--nmea", batch.nmea_path, "write the NMEA stream here ('-' = stdout)");
  batch_cmd->add_option("--errors", batch.errors_path, "write per-epoch fix errors CSV here ('-' = stdout)");
  CLI::App* version = app.add_subcommand("version", "versions of gnssemu, Embree and GeographicLib");

  // CLI11 reports a mistyped subcommand only as "A subcommand is required".
  const auto known = [&](const std::string& name) {
    for (const CLI::App* sub : {satpos, sky, dop, batch_cmd, version}) {
      if (sub->get_name() == name) return true;
    }
    return false;
  };
  if (argc > 1 && argv[1][0] != '-' && !known(argv[1])) {
    err << "gnssemu: unknown subcommand '" << argv[1] << "' (satpos, sky, dop, batch, version; see --help)\n";
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
    } else if (*satpos) {
      const time::GpsTime t = checked_time(time_args);
      write_satpos(load_store(nav_path, t), t, out);
    } else if (*sky || *dop) {
      const time::GpsTime t = checked_time(time_args);
      SkyRequest req = checked_site(site, t);
      const orbit::EphemerisStore store = load_store(nav_path, t, &req.klobuchar);
      if (*sky) {
        write_sky(store, req, out);
      } else if (const DopResult d = write_dop(store, req, out); !d.defined) {
        err << "gnssemu dop: DOP undefined: " << d.nsat << " satellites above the mask"
            << (d.nsat < 4 ? " (4 needed)\n" : " in a singular geometry\n");
      }
    } else if (*batch_cmd) {
      return run_batch_command(batch, out, err);
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

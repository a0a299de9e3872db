// SPDX-License-Identifier: Apache-2.0
// gnssemud: GNSS receiver emulator daemon. Usage: docs/daemon.md.
#include <unistd.h>

#include <array>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "config/config.hpp"
#include "config/scenario_file.hpp"
#include "config/setup/nav_setup.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "daemon/service/build_info.hpp"
#include "daemon/service/config_locator.hpp"
#include "daemon/daemon.hpp"
#include "daemon/status/status_setup.hpp"

namespace {

using namespace gnssemu;

std::string self_exe() {
  std::array<char, 4096> buf{};
  const ssize_t n = ::readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  return n > 0 ? std::string(buf.data(), static_cast<std::size_t>(n)) : std::string();
}

void print_port(const config::OutputPortConfig& p) {
  std::string where;
  if (const auto* pty = std::get_if<config::PtyPortConfig>(&p.transport)) where = pty->path;
  if (const auto* file = std::get_if<config::FilePortConfig>(&p.transport)) where = file->path;
  if (const auto* serial = std::get_if<config::SerialPortConfig>(&p.transport)) where = serial->device;
  if (const auto* tcp = std::get_if<config::TcpPortConfig>(&p.transport)) {
    where = "listen " + tcp->bind + ":" + std::to_string(tcp->port);
  }
  if (const auto* udp = std::get_if<config::UdpPortConfig>(&p.transport)) {
    where = "to " + udp->address + ":" + std::to_string(udp->port);
  }
  std::string protos;
  if (p.protocols_out & protocol::ubx::proto::kNmea) protos += "NMEA";
  if (p.protocols_out & protocol::ubx::proto::kUbx) protos += protos.empty() ? "UBX" : "+UBX";
  const std::string type(config::port_type_name(p.type()));
  std::printf("output:  %s: %s %s, %u baud, out %s, %zu UBX message(s)\n", p.name.c_str(), type.c_str(), where.c_str(),
              static_cast<unsigned>(p.baud), protos.empty() ? "nothing" : protos.c_str(), p.ubx_messages.size());
}

void print_summary(const config::Config& cfg, const orbit::NavData& nav, const daemon::RunPlan& plan) {
  const orbit::Constellation& c = plan.constellation;
  std::printf("config:  %s\n", cfg.source.empty() ? "(built-in default.toml)" : cfg.source.c_str());
  std::printf("origin:  lat %.7f deg, lon %.7f deg, height %.2f m\n", cfg.origin.lat_rad * kRadToDeg,
              cfg.origin.lon_rad * kRadToDeg, cfg.origin.height_m);
  for (const std::string& p : config::nav_paths(cfg)) std::printf("nav:     %s\n", p.c_str());
  std::printf("nav:     RINEX %.2f, %zu GPS ephemerides, covering %s\n", nav.rinex_version, nav.ephemerides.size(),
              orbit::spans_text(orbit::EphemerisStore(nav.ephemerides).coverage()).c_str());
  std::printf("sats:    mode %s: %s\n", std::string(orbit::nav_mode_name(cfg.nav.mode)).c_str(), c.describe().c_str());
  std::printf("leap:    %s\n", c.nav.leap_seconds ? (std::to_string(*c.nav.leap_seconds) + " s (nav header)").c_str()
                                                   : "from the built-in table");
  std::printf("epochs:  %.3g Hz, %s, start %s (week %d tow %.1f s)%s\n", cfg.rate_hz,
              cfg.time.mode == config::TimeMode::kRealtime ? "realtime" : "lockstep",
              time::calendar_text(plan.start).c_str(), plan.start.week(), plan.start.tow_s(),
              cfg.time.use_wall_clock_date && !cfg.time.start ? ", today (system clock)" : "");
  if (cfg.time.mode == config::TimeMode::kRealtime) {
    std::printf("timing:  first byte %.0f ms after each epoch\n", cfg.time.output_delay_s * 1e3);
  }
  std::printf("truth:   udp %s:%u, timeout %.2f s, max extrapolation %.2f s\n", cfg.truth.bind_address.c_str(),
              static_cast<unsigned>(cfg.truth.port), cfg.truth.timeout_s, cfg.truth.max_extrapolation_s);
  if (cfg.status.port == 0 && !cfg.status.free_port) {
    std::printf("status:  off\n");
  } else {
    const bool v6 = cfg.status.bind.find(':') != std::string::npos;
    std::printf("status:  http://%s%s%s:%s/%s\n", v6 ? "[" : "", cfg.status.bind.c_str(), v6 ? "]" : "",
                cfg.status.free_port ? "(free port)" : std::to_string(cfg.status.port).c_str(),
                daemon::is_loopback(cfg.status.bind) ? "" : " (not loopback: reachable from other machines)");
  }
  std::printf("demo:    %s (circle r=%.1f m, %.1f m/s)\n", cfg.demo.enabled ? "on" : "off", cfg.demo.radius_m,
              cfg.demo.speed_m_s);
  // Every vehicle, receiver and port the daemon opens.
  const std::vector<config::VehicleConfig> vehicles = config::resolve_vehicles(cfg);
  std::size_t receivers = 0;
  std::size_t ports = 0;
  for (const config::VehicleConfig& v : vehicles) {
    std::printf("vehicle: %s\n", v.id.empty() ? "(any: the first heard)" : v.id.c_str());
    for (const config::VehicleReceiverConfig& r : v.receivers) {
      const config::ReceiverSettings& s = r.settings;
      std::printf("receiver: %s/%s: lever arm [%.3f, %.3f, %.3f] m, u-blox %s, seed %llu, %.3g Hz\n",
                  v.id.empty() ? "*" : v.id.c_str(), r.name.c_str(), r.lever_arm_m.x, r.lever_arm_m.y,
                  r.lever_arm_m.z, std::string(protocol::ubx::generation_name(s.generation)).c_str(),
                  static_cast<unsigned long long>(s.world.seed), s.rate_hz);
      for (const config::OutputPortConfig& p : r.outputs) print_port(p);
      ++receivers;
      ports += r.outputs.size();
    }
  }
  std::printf("fleet:   %zu vehicle(s), %zu receiver(s), %zu port(s)\n", vehicles.size(), receivers, ports);
}

// Exit status (docs/daemon.md §Exit status; gnssemud(8)).
constexpr int kExitOk = 0;       // clean shutdown on a signal, --check-config OK, --help, --version
constexpr int kExitRuntime = 1;  // failed while running (unexpected error)
constexpr int kExitConfig = 2;   // command line, configuration, nav data, ports: nothing started

// The configuration as the command line asks for it: file (or the default),
// overrides, port checks. Throws gnssemu::Error naming file:line.
struct Options {
  std::string config_path;
  std::string pty_path;
  int truth_port = -1;
  std::string status_port;  ///< --status-port: a number, or "free"
  std::string scenario_path;  ///< --scenario: fault events (docs/faults.md)
};

config::Config load_run_config(const Options& o) {
  config::Config cfg = o.config_path.empty() ? config::default_config() : config::load_config(o.config_path);
  if (!o.pty_path.empty()) {
    if (!cfg.vehicles.empty() || cfg.fleet) {
      throw Error(cfg.source, 0, "--pty sets the single-vehicle form's first port; this file has [[vehicle]] or [fleet]");
    }
    if (cfg.outputs.empty()) {
      config::OutputPortConfig p;
      p.name = "pty";
      cfg.outputs.push_back(p);
    }
    cfg.outputs.front().transport = config::PtyPortConfig{o.pty_path};
  }
  if (o.truth_port >= 0) cfg.truth.port = static_cast<uint16_t>(o.truth_port);
  if (o.status_port == "free") {
    cfg.status.free_port = true;
  } else if (!o.status_port.empty()) {
    cfg.status.port = static_cast<uint16_t>(std::stoi(o.status_port));
    cfg.status.free_port = false;
  }
  for (const config::VehicleConfig& v : config::resolve_vehicles(cfg)) {
    for (const config::VehicleReceiverConfig& r : v.receivers) {
      for (const config::OutputPortConfig& p : r.outputs) daemon::validate_port(p);
    }
  }
  return cfg;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gnssemud: GNSS receiver emulator daemon (NMEA on a pty from UDP vehicle truth)", "gnssemud"};
  Options opt;
  bool verbose = false;
  bool check_only = false;
  app.add_option("-c,--config", opt.config_path, "TOML configuration (default: the shipped default.toml)");
  app.add_option("--pty", opt.pty_path, "path of the pty symlink of the first output (overrides the config)");
  app.add_option("--truth-port", opt.truth_port, "UDP port of the truth input, 0: any free one (overrides the config)")
      ->check(CLI::Range(0, 65535));
  app.add_option("--status-port", opt.status_port,
                 "TCP port of the status page: a number, 0: no page, free: any free port (overrides [status])")
      ->check([](const std::string& v) -> std::string {
        if (v == "free") return {};
        int n = -1;
        try {
          std::size_t used = 0;
          n = std::stoi(v, &used);
          if (used != v.size()) n = -1;
        } catch (const std::exception&) {
          n = -1;
        }
        return n >= 0 && n <= 65535 ? std::string() : "a port 0..65535 or 'free'";
      });
  app.add_option("--scenario", opt.scenario_path,
                 "scenario file (TOML [[event]] list, docs/faults.md): faults from the first epoch on");
  app.add_flag("-v,--verbose", verbose, "debug logging");
  app.add_flag("--check-config", check_only, "load and validate the configuration, print a summary, exit");
  app.set_version_flag("--version", daemon::version_line("gnssemud"));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11's own codes (105-114) mean nothing to a caller: usage is 2.
    return app.exit(e) == 0 ? kExitOk : kExitConfig;
  }

  auto logger = spdlog::stderr_color_mt("gnssemud");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("%Y-%m-%d %H:%M:%S.%e %^%l%$ %v");

  bool started = false;
  try {
    if (opt.config_path.empty()) opt.config_path = daemon::find_default_config(self_exe());
    // No file anywhere: the copy of default.toml compiled into the binary.
    const config::Config cfg = load_run_config(opt);
    const orbit::NavData nav = config::load_nav(cfg);
    // The start must be served by the nav data (as the configured mode dates
    // them): an error here, not a receiver without a fix forever.
    const daemon::RunPlan plan = daemon::plan_run(cfg, nav, daemon::system_clock_gps());
    std::vector<config::ScenarioEvent> scenario;
    if (!opt.scenario_path.empty()) scenario = config::read_targeted_scenario(opt.scenario_path);

    if (check_only) {
      boost::asio::io_context check_io;
      daemon::Daemon check(check_io, cfg, nav, plan);  // builds the receiver: validates its config
      if (!opt.scenario_path.empty()) check.set_scenario(scenario, opt.scenario_path);
      print_summary(cfg, nav, plan);
      if (!opt.scenario_path.empty()) std::printf("scenario: %s, %zu event(s)\n", opt.scenario_path.c_str(), scenario.size());
      std::printf("configuration OK\n");
      return kExitOk;
    }

    auto level = spdlog::level::from_str(cfg.log.level);
    spdlog::set_level(verbose ? spdlog::level::debug : level);
    std::size_t outputs = 0;
    for (const config::VehicleConfig& v : config::resolve_vehicles(cfg)) {
      for (const config::VehicleReceiverConfig& r : v.receivers) outputs += r.outputs.size();
    }
    if (outputs == 0) spdlog::warn("no outputs configured: epochs are computed but go nowhere");

    boost::asio::io_context io;
    daemon::Daemon d(io, cfg, nav, plan);
    if (!opt.scenario_path.empty()) {
      d.set_scenario(scenario, opt.scenario_path);
      spdlog::info("scenario {}: {} event(s) from the first epoch", opt.scenario_path, scenario.size());
    }
    if (!opt.config_path.empty()) d.set_reloader([opt] { return load_run_config(opt); });
    d.start();
    started = true;
    io.run();
    return kExitOk;
  } catch (const gnssemu::Error& e) {
    std::fprintf(stderr, "gnssemud: %s\n", e.what());
    return started ? kExitRuntime : kExitConfig;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gnssemud: error: %s\n", e.what());
    return started ? kExitRuntime : kExitConfig;
  }
}

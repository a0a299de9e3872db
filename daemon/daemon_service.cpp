// SPDX-License-Identifier: Apache-2.0
// Daemon: its service side — signals, SIGHUP reload, the once-a-second tick
// (drop summaries, the status line), and the log lines a person acts on
// (docs/daemon.md §Signals, §Reload, §Logs).
#include <memory>

#include <spdlog/spdlog.h>

#include "config/device_setup.hpp"
#include "config/pipeline_setup.hpp"
#include "core/common/error.hpp"
#include "daemon/daemon.hpp"
#include "daemon/reload_plan.hpp"
#include "daemon/scene_setup.hpp"

namespace gnssemu::daemon {
namespace {

constexpr double kStatusIntervalS = 60.0;

}  // namespace

void Daemon::on_signal(SignalAction action, int sig) {
  switch (action) {
    case SignalAction::kTerminate:
      spdlog::info("signal {} ({}): shutting down", sig, strsignal(sig));
      shutdown();
      break;
    case SignalAction::kReload:
      spdlog::info("signal {} ({}): reloading the configuration", sig, strsignal(sig));
      reload();
      break;
    case SignalAction::kStatus:
      spdlog::info("status: {}", status_line());
      if (fleet_) {
        for (const std::string& l : status_lines()) spdlog::info("status: {}", l);
      }
      break;
    case SignalAction::kIgnore:
      break;
  }
}

void Daemon::reload() noexcept {
  const auto t0 = Clock::now();
  if (!reloader_) {
    spdlog::warn("reload: no configuration file to reload (built-in configuration)");
    return;
  }
  notify_.reloading();
  try {
    config::Config loaded = reloader_();
    ReloadPlan plan = plan_reload(cfg_, loaded);
    if (fleet_ && (plan.receiver || plan.scene || !plan.reopen.empty())) {
      // A fleet's receivers are built at start; truth, log and demo settings apply live.
      spdlog::warn("reload: receiver, scene and port changes of a fleet apply at the next restart");
      plan.receiver = plan.scene = false;
      plan.reopen.clear();
    }
    if (fleet_) {
      spdlog::info("reload: [[vehicle]] and [fleet] are read at start: vehicles added or removed in {} "
                   "apply at the next restart", loaded.source);
    }
    // Build everything that can fail before anything running is touched.
    const std::vector<std::string> port_event_warnings =
        fleet_ ? std::vector<std::string>{} : check_reload_port_events(loaded);
    std::unique_ptr<scene::Scene> scene;
    if (plan.scene) scene = load_scene_logged(loaded);
    std::unique_ptr<pipeline::Pipeline> receiver;
    if (plan.receiver || plan.scene) {
      // A reload is not a power cycle: the new receiver keeps what the
      // running one knew (a hot start, whatever start the file gives).
      config::Config hot = loaded;
      hot.receiver.acquisition.start = receiver::StartMode::kHot;
      receiver = config::make_pipeline(hot, store_, pipeline::broadcast_of(constellation_.nav),
                                       plan.scene ? scene.get() : scene_.get());
    }
    // New ports open before the old ones close: a port that cannot open
    // fails the reload with everything as it was.
    std::vector<std::unique_ptr<OutputPort>> reopened;
    for (std::size_t i : plan.reopen) {
      validate_port(loaded.outputs[i]);
      reopened.push_back(open_port(loaded.outputs[i], io_));
    }
    // Apply.
    for (std::size_t k = 0; k < plan.reopen.size(); ++k) {
      const std::size_t i = plan.reopen[k];
      cfg_.outputs[i] = loaded.outputs[i];
      open_channel(rig(), i, std::move(reopened[k]));
      rig().channels[i]->start();
      spdlog::info("reload: output {} now on {}", cfg_.outputs[i].name, rig().channels[i]->port().describe());
    }
    if (plan.log_level) spdlog::set_level(spdlog::level::from_str(loaded.log.level));
    if (plan.truth) {
      take_live_truth(cfg_.truth, loaded.truth);
      allow_ = TruthAllowList(cfg_.truth.allow);
      router_.set_params(TrackParams{cfg_.truth.timeout_s, cfg_.truth.max_extrapolation_s});
      if (!fleet_ && cfg_.truth.vehicle != router_.router(0).wanted_vehicle()) {
        router_.router(0).set_driving_vehicle(cfg_.truth.vehicle);
        noted_vehicles_.clear();
        if (!cfg_.truth.vehicle.empty()) spdlog::info("truth: vehicle '{}' drives the receiver now", cfg_.truth.vehicle);
      }
      spdlog::info("truth: accepting packets from {}", allow_.describe());
    }
    if (plan.demo) {
      cfg_.demo = loaded.demo;
      // DemoTrajectory refers to frame_ (not assignable): built anew in place.
      std::destroy_at(&demo_);
      std::construct_at(&demo_, frame_, cfg_.demo.radius_m, cfg_.demo.speed_m_s, cfg_.demo.height_m);
    }
    if (plan.receiver || plan.scene) {
      cfg_.receiver = loaded.receiver;
      cfg_.world = loaded.world;
      for (const auto& c : rig().channels) c->set_link_seed(cfg_.world.seed);
      if (plan.scene) {
        cfg_.scene = loaded.scene;
        rig().receiver.reset();  // holds the old scene
        scene_ = std::move(scene);
      }
      receiver->adopt_faults(rig().receiver->take_faults());  // the faults go on around the new receiver
      rig().receiver = std::move(receiver);
      rig().device.set_coast_as_no_fix(config::coast_as_no_fix(cfg_));
      apply_chip_settings(rig());  // the chip's CFG-NAV5 (what a host set, what its polls read back) stays in force
    }
    if (plan.log_level) cfg_.log = loaded.log;
    if (!fleet_) rig().cfg = cfg_;  // the single form's receiver runs the top level
    for (const std::string& what : plan.need_restart) {
      spdlog::warn("reload: {} changed: applies at the next restart; running on the old value", what);
    }
    for (const std::string& w : port_event_warnings) spdlog::warn("reload: {}", w);
    refresh_status_setup();  // mask, thresholds, reopened ports
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    spdlog::info("reload: {} applied in {:.1f} ms ({})", cfg_.source, ms, plan.describe(cfg_));
    notify_.ready("reloaded: " + plan.describe(cfg_));
  } catch (const std::exception& e) {
    spdlog::error("reload failed, keeping the running configuration: {}", e.what());
    notify_.ready("reload failed: " + std::string(e.what()));
  }
}

std::vector<std::string> Daemon::status_lines() {
  std::vector<std::string> lines;
  const double now = std::max(now_s(), 0.0);
  for (std::size_t v = 0; v < vehicles_.size(); ++v) {
    VehicleState& vs = vehicles_[v];
    const TruthRouter& r = router_.router(v);
    // A vehicle's line shows its first receiver's fix and every receiver's ports.
    const Rig* first = nullptr;
    StatusSnapshot s;
    for (const auto& rp : rigs_) {
      if (rp->vehicle_index != v) continue;
      if (first == nullptr) first = rp.get();
      for (const auto& c : rp->channels) s.ports.push_back({c->port().config().name, c->port().readers()});
    }
    s.now_s = now;
    if (first != nullptr) {
      s.fix_type = first->last_fix_type < 0 ? 0 : first->last_fix_type;
      s.sats_used = first->last_num_used;
      s.sats_tracked = first->last_num_tracked;
    }
    s.packets_ok = fleet_ ? vs.packets_ok : packets_ok_;
    s.drops = fleet_ ? vs.drops.total() : drops_.total();
    s.epochs = epochs_;
    s.driver = r.has_driver() ? r.driver_id() : std::string();
    s.driver_fresh = r.driver_fresh(now);
    s.demo = demo_drives(v);
    s.vehicles = fleet_ ? 1 : r.vehicle_count();
    std::string line = vs.line.line(s);
    lines.push_back(fleet_ ? "vehicle '" + router_.id(v) + "': " + line : line);
  }
  return lines;
}

std::string Daemon::status_line() {
  std::vector<std::string> lines = status_lines();
  if (!fleet_) return lines.front();
  int fixed = 0;
  for (const auto& rp : rigs_) fixed += rp->last_fix_type >= 3 ? 1 : 0;
  uint64_t unknown = drops_.count(DropReason::kUnknownVehicle);
  return fmt::format("fleet: {} vehicle(s), {} of {} receiver(s) with a 3D fix; {} packets accepted, {} dropped "
                     "({} from unknown vehicles); {} epochs",
                     vehicles_.size(), fixed, rigs_.size(), packets_ok_, drops_.total(), unknown, epochs_);
}

void Daemon::arm_tick() {
  tick_timer_.expires_after(std::chrono::seconds(1));
  tick_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec && !stopped_) on_tick();
  });
}

void Daemon::on_tick() {
  const double now = now_s();
  const DropCounts due = drops_.take_due(now);
  if (const uint64_t n = drop_counts_sum(due); n > 0) {
    spdlog::warn("truth: dropped {} more packet(s) in the last {:.0f} s: {}; {} dropped in total", n,
                 drops_.interval_s(), drop_counts_text(due), drops_.total());
  }
  if (now - last_status_s_ >= kStatusIntervalS) {
    last_status_s_ = now;
    const std::string line = status_line();
    spdlog::info("status: {}", line);
    if (fleet_) {
      for (const std::string& l : status_lines()) spdlog::info("status: {}", l);
    }
    notify_.status(line);
  }
  arm_tick();
}

void Daemon::log_port_change(Rig& rig, std::size_t src) {
  if (src >= rig.channels.size() || !rig.channels[src]) return;
  const std::string now(rig.channels[src]->output_summary());
  if (now == rig.out_summary[src]) return;
  const std::string& was = rig.out_summary[src];
  const protocol::ubx::PortSettings& p = rig.device.port(rig.channels[src]->link());
  spdlog::info("output {}: a host reconfigured the port: now sends {} (was {}), {} baud{}", rig.cfg.outputs[src].name,
               now, was, p.baud_bps,
               p.outputs_nmea() ? ""
                                : "; NMEA is off: a gpsd without -b does this when it probes a u-blox, "
                                  "run gpsd -b to keep the port as configured");
  rig.out_summary[src] = now;
}

void Daemon::note_other_vehicle(const std::string& id) {
  for (const std::string& v : noted_vehicles_) {
    if (v == id) return;
  }
  if (noted_vehicles_.size() >= TruthRouter::kMaxVehicles) return;
  noted_vehicles_.push_back(id);
  const TruthRouter& router = router_.router(0);
  if (router.has_driver()) {
    spdlog::warn("truth: vehicle '{}' from {}:{} is not driving the receiver: '{}' is{}; set [truth] vehicle = \"{}\" "
                 "to follow it",
                 id, peer_.address().to_string(), peer_.port(), router.driver_id(),
                 router.wanted_vehicle().empty() ? " (the first heard)" : " ([truth] vehicle)", id);
  } else {
    spdlog::warn("truth: vehicle '{}' from {}:{} is ignored: waiting for vehicle '{}' ([truth] vehicle)", id,
                 peer_.address().to_string(), peer_.port(), router.wanted_vehicle());
  }
}

}  // namespace gnssemu::daemon

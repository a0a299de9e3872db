// SPDX-License-Identifier: Apache-2.0
// Daemon: its service side — signals, the once-a-second tick (drop
// summaries, the status line), and the log lines a person acts on
// (docs/daemon.md §Signals, §Logs). The reload is daemon_reload.cpp.
#include <cstring>

#include <spdlog/spdlog.h>

#include "daemon/daemon.hpp"

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

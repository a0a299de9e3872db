// SPDX-License-Identifier: Apache-2.0
// The daemon's hooks for the status page (docs/status.md): the server is
// started with the ports and every epoch feeds the one StatusProducer.
#include <cstdio>
#include <string_view>

#include <spdlog/spdlog.h>

#include "core/common/error.hpp"
#include "daemon/daemon.hpp"
#include "daemon/status/status_setup.hpp"

namespace gnssemu::daemon {

namespace {

CorrectionCounters correction_counters(const protocol::ubx::Device& d, const receiver::rtk::RtkStatus& rtk,
                                       const receiver::Fix& fix) noexcept {
  const protocol::ubx::RtcmInputStats& in = d.rtcm_input().stats();
  const receiver::Corrections& c = d.corrections();
  CorrectionCounters out;
  out.messages = in.frames;
  out.used = in.used;
  out.crc_failed = in.crc_failed;
  out.ignored = in.ignored;
  out.lost = in.outage;
  out.epochs = d.rtcm_input().decoder_stats().epochs;
  if (c.station.position_valid || c.station.moving) out.station_id = c.station.station_id;
  if (c.obs_valid && fix.time_valid) out.age_s = fix.t - c.obs_received;
  if (fix.diff_soln && !fix.sbas_soln) out.baseline_m = rtk.baseline_m;
  out.baseline_big = rtk.baseline_big;
  out.long_baseline = rtk.long_baseline;
  return out;
}

}  // namespace

void Daemon::refresh_status_setup() {
  for (const auto& rp : rigs_) {
    Rig& rig = *rp;
    StatusSettings s = status_settings(rig.cfg);
    s.rate_hz = rate_hz_;  // a host's CFG-RATE
    rig.status.set_settings(std::move(s));
    std::vector<PortInfo> ports;
    for (const auto& c : rig.channels) {
      const config::OutputPortConfig& pc = c->port().config();
      ports.push_back(PortInfo{pc.name, std::string(config::port_type_name(pc.type())), c->port().describe()});
    }
    rig.status.set_ports(std::move(ports));
  }
}

void Daemon::start_status_page() {
  refresh_status_setup();
  const config::StatusConfig& sc = cfg_.status;
  if (sc.port == 0 && !sc.free_port) return;
  status_server_ = std::make_unique<StatusServer>(io_, rig().status);
  try {
    status_server_->start(sc.bind, sc.free_port ? 0 : sc.port);
  } catch (const Error& e) {
    // The page is a window on the receiver, not part of it: a taken port
    // moves it to a free one rather than stopping the emulator.
    spdlog::warn("{}; serving the status page on a free port instead", e.what());
    status_server_ = std::make_unique<StatusServer>(io_, rig().status);
    status_server_->start(sc.bind, 0);
  }
  if (!is_loopback(sc.bind)) {
    spdlog::warn("status page on {}: reachable from other machines (it shows the vehicle's position); "
                 "[status] bind = \"127.0.0.1\" keeps it local",
                 sc.bind);
  }
  status_server_->set_selector(
      [this](std::string_view vehicle, std::string_view receiver) -> const StatusProducer* {
        for (const auto& rp : rigs_) {
          if (rp->vehicle == vehicle && (receiver.empty() || rp->name == receiver)) return &rp->status;
        }
        return nullptr;
      },
      [this] {
        std::string out = "[";
        for (const auto& rp : rigs_) {
          out += fmt::format("{}{{\"vehicle\":\"{}\",\"receiver\":\"{}\"}}", out.size() > 1 ? "," : "",
                             rp->vehicle, rp->name);
        }
        return out + "]";
      });
  status_server_->set_roster([this](std::vector<OverviewEntry>& out) {
    out.clear();
    for (const auto& rp : rigs_) out.push_back(OverviewEntry{rp->vehicle, rp->name, &rp->status});
  });
  const auto ep = status_server_->local_endpoint();
  const std::string host = ep.address().is_v6() ? "[" + ep.address().to_string() + "]" : ep.address().to_string();
  std::printf("gnssemud: status page http://%s:%u/\n", host.c_str(), static_cast<unsigned>(ep.port()));
}

double Daemon::run_time_s(const time::GpsTime& t) noexcept {
  if (!status_first_t_) status_first_t_ = t;
  return t - *status_first_t_;
}

void Daemon::record_status(Rig& rig, double run_s, const receiver::Fix& fix) noexcept {
  record_faults(rig, run_s);
  const protocol::ubx::EpochInfo& info = rig.device.epoch_info();
  EpochStatus e;
  e.fix = &fix;
  e.truth = &rig.truth;
  e.run_s = run_s;
  e.uptime_s = info.msss_ms * 1e-3;
  e.ttff_s = info.ttff_ms * 1e-3;
  rig.status.on_epoch(e);

  // A fleet's receiver counts its vehicle's packets; the single form counts all.
  const std::size_t v = rig.vehicle_index;
  const VehicleState& vs = vehicles_[v];
  const DropStats& drops = fleet_ ? vs.drops : drops_;
  TruthCounters tc;
  tc.packets_accepted = fleet_ ? vs.packets_ok : packets_ok_;
  for (std::size_t r = 0; r < kDropReasonCount; ++r) tc.dropped[r] = drops.count(static_cast<DropReason>(r));
  const double now = now_s();
  tc.simulator = router_.router(v).has_driver();
  tc.fresh = tc.simulator && router_.router(v).driver_fresh(now);
  tc.age_s = router_.router(v).driver_age_s(now);
  tc.demo = demo_drives(v);
  rig.status.set_truth(tc);
  rig.status.set_corrections(correction_counters(rig.device, rig.receiver->receiver().rtk().status(), fix));
}

void Daemon::publish_status() noexcept {
  for (const auto& rp : rigs_) record_port_counters(*rp);
  if (status_server_) status_server_->publish();
}

void Daemon::record_port_counters(Rig& rig) noexcept {
  for (std::size_t i = 0; i < rig.channels.size(); ++i) {
    const PortChannel& c = *rig.channels[i];
    PortCounters pc;
    pc.protocols = c.output_summary();
    pc.baud_bps = c.budget().limited() ? c.budget().baud_bps() : 0;
    pc.bytes_offered = c.stats().bytes_offered;
    pc.bytes_written = c.port().stats().bytes_written;
    pc.epochs_written = c.port().stats().epochs_written;
    pc.epochs_dropped = c.port().stats().epochs_dropped;
    pc.messages_dropped = c.stats().messages_dropped;
    pc.tx_level_bytes = c.budget().level_bytes();
    pc.tx_capacity_bytes = static_cast<double>(c.budget().capacity_bytes());
    pc.link_faults = c.stats().link_faults;
    rig.status.set_port_counters(i, pc);
  }
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#include "daemon/daemon.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include <spdlog/spdlog.h>

#include "config/setup/device_setup.hpp"
#include "config/setup/nav_setup.hpp"
#include "config/setup/pipeline_setup.hpp"
#include "config/receiver_config.hpp"
#include "config/setup/scene_loader.hpp"
#include "core/common/error.hpp"
#include "daemon/epoch_schedule.hpp"
#include "daemon/scene_setup.hpp"
#include "daemon/service/state_file.hpp"
#include "daemon/status/status_setup.hpp"
#include "daemon/truth/lever_arm.hpp"
#include "daemon/truth/truth_packet.hpp"

namespace gnssemu::daemon {
namespace {

// Lockstep: a time within this of a grid epoch is on it (as gnssemu batch), s.
constexpr double kLockGridTolerance_s = 1e-6;

// The emulated receiver's power-on in realtime mode: the process start
// (static initialisation, before the config and nav file are read).
// NAV-STATUS msss and the time to first fix count from here, so ttff is what
// the emulator really took. Lockstep counts in epoch time (chip_clock_s).
const std::chrono::steady_clock::time_point kProcessStart = std::chrono::steady_clock::now();

const char* start_name(receiver::StartMode m) {
  switch (m) {
    case receiver::StartMode::kHot: return "hot";
    case receiver::StartMode::kWarm: return "warm";
    case receiver::StartMode::kCold: break;
  }
  return "cold";
}

std::string gps_text(const time::GpsTime& t) {
  const time::CalendarTime c = t.to_calendar();
  char buf[64];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02d %02d:%02d:%02.0f GPST (week %d, tow %.1f)", c.year,
                c.month, c.day, c.hour, c.minute, std::floor(c.second), t.week(), t.tow_s());
  return buf;
}

// The vehicles' ids as the router takes them: the single form's one takes any id.
std::vector<std::string> router_ids(const config::Config& cfg, const std::vector<config::VehicleConfig>& vehicles) {
  if (cfg.vehicles.empty() && !cfg.fleet) return {std::string()};
  std::vector<std::string> ids;
  for (const config::VehicleConfig& v : vehicles) ids.push_back(v.id);
  return ids;
}

// The systems every receiver's world evaluates: the sky holds their union.
SystemSet sky_systems(const std::vector<config::VehicleConfig>& vehicles) {
  SystemSet all;
  for (const config::VehicleConfig& v : vehicles) {
    for (const config::VehicleReceiverConfig& r : v.receivers) {
      all = SystemSet(static_cast<uint8_t>(all.bits() | r.settings.world.systems.bits()));
    }
  }
  return all;
}

}  // namespace

Daemon::Daemon(asio::io_context& io, const config::Config& cfg, const orbit::NavData& nav, const RunPlan& plan)
    : io_(io),
      cfg_(cfg),
      raw_nav_(nav),
      constellation_(plan.constellation),
      store_(constellation_.nav.ephemerides, constellation_.store_options()),
      frame_(cfg.origin),
      scene_(load_scene_logged(cfg)),
      demo_(frame_, cfg.demo.radius_m, cfg.demo.speed_m_s, cfg.demo.height_m),
      fleet_(!cfg.vehicles.empty() || cfg.fleet.has_value()),
      router_(TrackParams{cfg.truth.timeout_s, cfg.truth.max_extrapolation_s}, cfg.time.mode,
              router_ids(cfg, config::resolve_vehicles(cfg)), cfg.truth.vehicle),
      start_(plan.start),
      period_s_(1.0 / cfg.rate_hz),
      output_delay_s_(cfg.time.output_delay_s),
      rate_hz_(cfg.rate_hz),
      sky_(store_, sky_systems(config::resolve_vehicles(cfg)), world::sky_errors_config(cfg.world)),
      timer_(io),
      retry_timer_(io),
      socket_(io),
      notify_(io),
      allow_(cfg.truth.allow),
      tick_timer_(io) {
  const std::vector<config::VehicleConfig> vehicles = config::resolve_vehicles(cfg);
  const SystemSet nav_systems = orbit::systems_of(constellation_.nav);
  for (std::size_t v = 0; v < vehicles.size(); ++v) {
    for (const config::VehicleReceiverConfig& r : vehicles[v].receivers) {
      rigs_.push_back(std::make_unique<Rig>(vehicles[v].id, r.name, v, config::receiver_config(cfg, vehicles[v], r),
                                            r.lever_arm_m, nav_systems));
    }
  }
  vehicles_.resize(router_.size());
  refresh_vehicle_allows();
  antennas_.reserve(rigs_.size());
  if (store_.size() == 0) throw Error(nav.source, 0, "no GPS ephemerides in the nav file");
  check_range(output_delay_s_, config::TimeRanges::output_delay_s, cfg.source, "time.output_delay_s");
  power_on_ = kProcessStart;
  for (std::size_t i = 0; i < rigs_.size(); ++i) {
    // One chip's saved configuration per file: two receivers would overwrite each other's.
    const std::string& f = rigs_[i]->cfg.state_file;
    for (std::size_t j = 0; j < i && !f.empty(); ++j) {
      if (rigs_[j]->cfg.state_file == f) {
        throw Error(cfg.source, 0, "receivers " + rigs_[j]->label() + " and " + rigs_[i]->label() +
                                       " share state_file " + f + ": give each its own in [[vehicle.receiver]]");
      }
    }
  }
  for (const auto& rp : rigs_) {
    Rig& r = *rp;
    if (r.cfg.state_file.empty()) continue;
    // A module boots with what it saved: rate, ports, messages, GNSS.
    if (load_state_file(r.cfg.state_file, r.device)) {
      spdlog::info("{}receiver: saved configuration loaded from {} ({:.0f} Hz)", who(r), r.cfg.state_file,
                   1.0 / r.device.epoch_period_s());
    } else {
      spdlog::info("{}receiver: no saved configuration yet in {}: factory settings", who(r), r.cfg.state_file);
    }
  }
  // One epoch clock for every receiver: the first one's saved rate, if any.
  if (!rig().cfg.state_file.empty()) {
    period_s_ = rig().device.epoch_period_s();
    rate_hz_ = 1.0 / period_s_;
  }
  for (const auto& rp : rigs_) {
    Rig& r = *rp;
    restart_receiver(r, r.cfg.receiver.acquisition.start);
    if (const SystemSet off = r.cfg.world.systems.minus(r.device.enabled_systems()); !off.empty()) {
      spdlog::info("{}receiver: constellations {} are in the sky but off on the chip (its CFG-GNSS): tracked "
                   "once a host enables them",
                   who(r), systems_text(off).data());
    }
  }
  if (fleet_) spdlog::info("fleet: {} vehicle(s), {} receiver(s) in one sky", vehicles_.size(), rigs_.size());
  spdlog::info("receiver: {} start at power-on", start_name(cfg_.receiver.acquisition.start));
  if (scene_) spdlog::info("scene {}: {} triangles", cfg_.scene->mesh_file, scene_->triangle_count());
  if (cfg_.base) start_base();
  lock_grid_from(start_);
}

void Daemon::start_base() {
  base_ = std::make_unique<config::BaseStation>(cfg_, store_, pipeline::broadcast_of(constellation_.nav), scene_.get());
  base_bytes_.reserve(16384);
  if (const std::string w = config::base_distance_warning(cfg_); !w.empty()) spdlog::warn("{}", w);
  if (cfg_.base->ntrip.enabled) {
    caster_ = std::make_unique<NtripCaster>(io_, cfg_.base->ntrip, sourcetable_str(*base_));
    spdlog::info("base {}: NTRIP caster on 127.0.0.1:{}/{} ({})", cfg_.base->station_id, caster_->port(),
                 cfg_.base->ntrip.mountpoint, base_->format_details());
  }
  for (const config::OutputPortConfig& o : cfg_.base->outputs) {
    validate_port(o);
    base_ports_.push_back(open_port(o, io_));
    base_ports_.back()->start(nullptr);
    spdlog::info("base {}: RTCM on output {}: {} ({})", cfg_.base->station_id, o.name, base_ports_.back()->describe(),
                 base_->format_details());
  }
}

void Daemon::lock_grid_from(const time::GpsTime& t) noexcept {
  // The first epoch of the rate's grid at or after t (batch's tolerance).
  lock_week_ = t.week();
  lock_k_ = std::ceil(t.tow_s() * rate_hz_ - kLockGridTolerance_s * rate_hz_);
  lock_next_ = time::GpsTime::make(lock_week_, lock_k_ / rate_hz_).value_or(t);
}

void Daemon::lock_step(double n) noexcept {
  // Epoch k is (week, k / rate) as gnssemu batch computes it: adding the
  // period each epoch would drift off the grid (NAV-PVT nano -1 ns at 5 Hz).
  lock_k_ += n;
  lock_next_ = time::GpsTime::make(lock_week_, lock_k_ / rate_hz_).value_or(lock_next_ + n * period_s_);
}

void Daemon::restart_receiver(Rig& rig, receiver::StartMode start) {
  // With the broadcast leap seconds and Klobuchar coefficients of the run's dates.
  config::Config c = rig.cfg;
  c.receiver.acquisition.start = start;
  // The faults are in the world around the receiver: they go on.
  std::unique_ptr<faults::FaultStage> faults = rig.receiver ? rig.receiver->take_faults() : nullptr;
  rig.receiver = config::make_pipeline(c, store_, pipeline::broadcast_of(constellation_.nav), scene_.get());
  rig.receiver->adopt_faults(std::move(faults));
  // The corrections its ports' hosts send (RTCM 3 on any port that takes it).
  rig.receiver->receiver().set_corrections(&rig.device.corrections());
  apply_chip_settings(rig);
}

void Daemon::apply_chip_settings(Rig& rig) { config::apply_chip_settings(rig.device, rig.receiver->receiver()); }

void Daemon::on_host_input(Rig& rig, std::size_t src, const protocol::ubx::InputResult& result) {
  const std::vector<config::OutputPortConfig>& outputs = rig.cfg.outputs;
  // A moving base's epoch that arrived within the rover's epoch: the F9P
  // sends the time-matched RELPOSNED now, not with its next epoch.
  if (result.corrections_changed && rig.receiver && rig.receiver->on_corrections()) {
    rig.device.on_relative_position(rig.receiver->last_fix().rel_pos);
    for (const auto& c : rig.channels) c->send_relative_position();
  }
  if (result.nav_rate_changed || result.reset) on_nav_period(rig, src);
  if (result.saved_changed && !rig.cfg.state_file.empty()) {
    if (const std::string err = save_state_file(rig.cfg.state_file, rig.device); !err.empty()) {
      spdlog::warn("output {}: saved configuration not written: {}", outputs[src].name, err);
    }
  }
  if (result.gnss_changed) {
    // A real chip restarts its GNSS engine after a change of the GNSS
    // selection (M8 spec CFG-GNSS; satpulse#108): tracking starts over with
    // what it knew, on the systems now enabled.
    spdlog::info("output {}: GNSS selection changed to {}: the receiver restarts tracking", outputs[src].name,
                 systems_text(rig.device.enabled_systems()).data());
    rig.receiver->receiver().restart(receiver::StartState{true, true, true, true});
    apply_chip_settings(rig);
  }
  if (result.nav_config_changed) {
    const protocol::ubx::wire::CfgNav5& n = rig.device.config().nav5;
    spdlog::info("output {}: CFG-NAV5 dynModel {}, static hold {} cm/s / {} m", outputs[src].name,
                 static_cast<unsigned>(n.dynModel), static_cast<unsigned>(n.staticHoldThresh),
                 static_cast<unsigned>(n.staticHoldMaxDist));
    apply_chip_settings(rig);
  }
  if (result.hpg_changed) {
    const protocol::ubx::HpgSettings h = rig.device.hpg_settings();
    spdlog::info("output {}: RTK mode {}, DGNSS timeout {} s", outputs[src].name,
                 h.dgnss_mode == protocol::ubx::DgnssMode::kRtkFixed ? "fixed" : "float", h.dgnss_timeout_s);
    apply_chip_settings(rig);
  }
  if (result.ports_changed || result.reset) {
    for (std::size_t i = 0; i < rig.channels.size(); ++i) log_port_change(rig, i);
  }
  // One chip: a reset or a configuration load from any host changes the
  // other outputs' UART1s too (their bauds; a reset drops partial input).
  if (result.reset || result.ports_changed) {
    for (std::size_t i = 0; i < rig.channels.size(); ++i)
      if (i != src) rig.channels[i]->follow_device(result.reset.has_value());
  }
  if (!result.reset) return;
  // Every reset mode but "GNSS stop" restarts navigation: the tracked
  // satellites and the solution are gone and the fix is reacquired with
  // what navBbrMask kept (hot: about 1 s, cold: about 30 s); the device
  // measures the time to first fix from the reset on every port. All ports
  // share the one receiver, so all of them see the fix drop. The world
  // (satellite errors, the oscillator) runs on.
  const protocol::ubx::Reset& reset = *result.reset;
  if (!reset.restarts_navigation()) {
    spdlog::info("output {}: CFG-RST GNSS stop: not modelled, the receiver keeps navigating",
                 outputs[src].name);
    return;
  }
  spdlog::info("output {}: CFG-RST {} start (navBbrMask 0x{:04X}): the receiver restarts and reacquires",
               outputs[src].name, reset.start_name(), reset.nav_bbr_mask);
  rig.receiver->receiver().restart(receiver::StartState{reset.keeps_ephemeris(), reset.keeps_almanac(),
                                                     reset.keeps_position(), reset.keeps_time()});
  // The device restarted its uptime on the wall clock; in lockstep the chip
  // counts in epoch time, from the epoch it has reached (the rate count starts over too).
  if (cfg_.time.mode == config::TimeMode::kLockstep) rig.device.power_on(chip_clock_s(last_epoch_t_));
  apply_chip_settings(rig);  // a reboot may have loaded the saved CFG-NAV5
}

Daemon::~Daemon() { shutdown(); }

double Daemon::now_s() const noexcept {
  return std::chrono::duration<double>(Clock::now() - t0_).count();
}

double Daemon::chip_clock_s(const time::GpsTime& t) const noexcept {
  return cfg_.time.mode == config::TimeMode::kRealtime ? now_s() : t - chip_origin_;
}

void Daemon::open_channel(Rig& rig, std::size_t i, std::unique_ptr<OutputPort> port) {
  rig.channels[i] = std::make_unique<PortChannel>(std::move(port), rig.device, i, [this] { return now_s(); });
  PortChannel& c = *rig.channels[i];
  // In lockstep the serial line is simulated too: its budget drains in simulation time.
  if (cfg_.time.mode != config::TimeMode::kRealtime) c.set_line_clock([this] { return line_s_; });
  c.use_idle_timer(io_);
  c.set_link_seed(rig.cfg.world.seed);
  Rig* r = &rig;  // rigs_ holds each Rig by pointer: it stays put
  c.on_input([this, r, i](const protocol::ubx::InputResult& in) { on_host_input(*r, i, in); });
}

void Daemon::wire_rig(Rig& r, std::vector<std::unique_ptr<OutputPort>> ports, double power_on_s) {
  r.device.power_on(power_on_s);
  r.channels.resize(ports.size());
  for (std::size_t i = 0; i < ports.size(); ++i) open_channel(r, i, std::move(ports[i]));
  for (const auto& c : r.channels) c->start();
  // Lines follow the chip's UART1s (a saved configuration may have changed their bauds).
  if (!r.cfg.state_file.empty()) {
    for (const auto& c : r.channels) c->follow_device(false);
  }
  for (const auto& c : r.channels) r.out_summary.emplace_back(c->output_summary());
}

void Daemon::print_ports(const Rig& rig) const {
  for (const auto& c : rig.channels) {
    std::printf("gnssemud: %s%s on %s\n", who(rig).c_str(), std::string(c->output_summary()).c_str(),
                c->port().describe().c_str());
  }
}

void Daemon::log_port_summary(const Rig& rig) const {
  for (const auto& c : rig.channels) {
    const PortStats& ps = c->port().stats();
    std::string drops;
    for (const auto& [name, n] : c->drops()) drops += fmt::format("{}{} {}", drops.empty() ? "" : ", ", name, n);
    spdlog::info("{}output {}: {} epochs written, {} dropped; {} replies; {} bytes in; {} messages over the line "
                 "budget{}{}",
                 who(rig), c->port().config().name, ps.epochs_written, ps.epochs_dropped, ps.replies_written,
                 ps.bytes_from_reader, c->stats().messages_dropped, drops.empty() ? "" : ": ", drops);
  }
}

void Daemon::start() {
  t0_ = Clock::now();
  if (cfg_.time.use_wall_clock_date && cfg_.time.mode == config::TimeMode::kRealtime) {
    // Epoch 0 at the next whole GPS second of the wall clock, so every epoch
    // sits on a whole multiple of the period in GPS time (as a u-blox's do).
    const WholeSecondStart w = whole_second_start(system_clock_gps());
    start_ = w.start;
    lock_next_ = w.start;
    t0_ += std::chrono::nanoseconds(std::llround(w.wait_s * 1e9));
  }
  if (cfg_.time.mode != config::TimeMode::kRealtime) chip_origin_ = lock_next_;
  for (const auto& rp : rigs_) {
    Rig& r = *rp;
    std::vector<std::unique_ptr<OutputPort>> ports;
    for (const config::OutputPortConfig& o : r.cfg.outputs) ports.push_back(open_port(o, io_));
    wire_rig(r, std::move(ports),
             cfg_.time.mode == config::TimeMode::kRealtime ? std::chrono::duration<double>(power_on_ - t0_).count()
                                                           : 0.0);
  }

  boost::system::error_code ec;
  const auto addr = asio::ip::make_address(cfg_.truth.bind_address, ec);
  if (ec) throw Error("truth input: bad bind_address '" + cfg_.truth.bind_address + "'");
  const asio::ip::udp::endpoint ep(addr, cfg_.truth.port);
  socket_.open(ep.protocol(), ec);
  if (!ec) socket_.bind(ep, ec);
  if (ec) {
    throw Error("truth input: cannot bind udp " + cfg_.truth.bind_address + ":" +
                std::to_string(cfg_.truth.port) + ": " + ec.message());
  }
  const auto local = socket_.local_endpoint(ec);

  for (const auto& rp : rigs_) print_ports(*rp);
  std::printf("gnssemud: truth input udp %s:%u\n", local.address().to_string().c_str(),
              static_cast<unsigned>(local.port()));
  start_status_page();
  start_control_socket();
  std::fflush(stdout);

  const std::optional<int>& leap = constellation_.nav.leap_seconds;
  spdlog::info("config {}; {} GPS ephemerides; leap seconds {}", cfg_.source.empty() ? "(built in)" : cfg_.source,
               store_.size(), leap ? std::to_string(*leap) + " (nav header)" : std::string("from the built-in table"));
  spdlog::info("satellites: {}", constellation_.describe());
  spdlog::info("epochs at {} Hz, {} mode, starting {}{}", cfg_.rate_hz,
               cfg_.time.mode == config::TimeMode::kRealtime ? "realtime" : "lockstep", gps_text(start_),
               cfg_.time.mode == config::TimeMode::kRealtime
                   ? fmt::format(", output {:.0f} ms after each epoch", output_delay_s_ * 1e3)
                   : std::string());
  if (cfg_.demo.enabled) {
    spdlog::info("demo circle r={} m at {} m/s drives the receiver until a simulator sends truth", cfg_.demo.radius_m,
                 cfg_.demo.speed_m_s);
  }

  if (!allow_.empty()) spdlog::info("truth: accepting packets from {} only", allow_.describe());
  if (fleet_) {
    spdlog::info("truth: each packet's vehicle id picks its vehicle; ids not configured are dropped (unknown_vehicle)");
  } else if (!cfg_.truth.vehicle.empty()) {
    spdlog::info("truth: vehicle '{}' drives the receiver ([truth] vehicle); other vehicles are ignored",
                 cfg_.truth.vehicle);
  }
  signals_ = std::make_unique<SignalDispatch>(io_, [this](SignalAction a, int sig) { on_signal(a, sig); });

  index_ = 0;
  receive();
  arm_timer();
  arm_tick();
  std::size_t outputs = 0;
  for (const auto& rp : rigs_) outputs += rp->channels.size();
  notify_.ready(fmt::format("{} output(s), truth on udp port {}", outputs, local.port()));
}

void Daemon::shutdown() {
  if (stopped_) return;
  stopped_ = true;
  boost::system::error_code ec;
  notify_.stopping();
  timer_.cancel();
  retry_timer_.cancel();
  tick_timer_.cancel();
  socket_.close(ec);
  if (signals_) signals_->cancel();
  if (status_server_) status_server_->stop();
  if (control_) control_->stop();  // removes the socket file
  if (base_) {
    const config::BaseStats& b = base_->stats();
    spdlog::info("base {}: {} epochs, {} messages, {} bytes; {} signals dropped", cfg_.base->station_id, b.epochs,
                 b.messages, b.bytes, b.dropped_cells);
  }
  if (caster_) {
    const NtripStats& n = caster_->stats();
    spdlog::info("ntrip: {} clients served, {} sourcetables, {} refused, {} epochs dropped for slow clients",
                 n.clients_served, n.sourcetables, n.refused, n.dropped_epochs);
    caster_.reset();  // closes the listener and every client
  }
  bool any_channel = false;
  for (const auto& rp : rigs_) {
    any_channel = any_channel || !rp->channels.empty();
    log_port_summary(*rp);
  }
  if (any_channel) {
    if (fleet_) {
      for (std::size_t v = 0; v < vehicles_.size(); ++v) {
        const VehicleState& vs = vehicles_[v];
        spdlog::info("truth: vehicle '{}': {} packets accepted, {} dropped{}{}{}{}", router_.id(v), vs.packets_ok,
                     vs.drops.total(), vs.drops.total() > 0 ? ": " : "", drop_counts_text(vs.drops.totals()),
                     vs.jumps > 0 ? fmt::format("; {} jump(s)", vs.jumps) : "",
                     vs.ever_driven ? "" : " (never heard)");
      }
    }
    const uint64_t single_jumps = fleet_ || vehicles_.empty() ? 0 : vehicles_.front().jumps;
    spdlog::info("truth: {} packets accepted, {} dropped{}{}{}; {} epochs, {} skipped", packets_ok_, drops_.total(),
                 drops_.total() > 0 ? ": " : "", drop_counts_text(drops_.totals()),
                 single_jumps > 0 ? fmt::format("; {} jump(s)", single_jumps) : "", epochs_, epochs_skipped_);
  }
  for (const auto& rp : rigs_) rp->channels.clear();  // closes ports, removes pty symlinks
}

time::GpsTime Daemon::realtime_clock_gps() noexcept { return start_ + now_s(); }

void Daemon::arm_timer() {
  // Realtime: epoch k is measured at t0 + k / rate, computed compute_lead_s_
  // before it leaves and sent output_delay_s after it.
  const bool realtime = cfg_.time.mode == config::TimeMode::kRealtime;
  const double delay_s = realtime ? output_delay_s_ - (send_pending_ ? 0.0 : compute_lead_s_) : 0.0;
  const auto base = std::chrono::nanoseconds(std::llround((sched_base_s_ + delay_s) * 1e9));
  timer_.expires_at(t0_ + base + std::chrono::nanoseconds(epoch_deadline_ns(index_, rate_hz_)));
  timer_.async_wait([this](const boost::system::error_code& ec) { on_timer(ec); });
}

void Daemon::note_coverage(const time::GpsTime& t) noexcept {
  const bool served = constellation_.serves(t);
  if (served == served_) return;
  served_ = served;
  if (!served) {
    spdlog::warn("epoch {}: outside the nav data ({}): no satellites until the data resume", gps_text(t),
                 orbit::spans_text(constellation_.coverage));
  } else {
    spdlog::info("epoch {}: back inside the nav data", gps_text(t));
  }
}

void Daemon::redate_constellation(const time::GpsTime& t) {
  try {
    const orbit::Constellation c = config::make_constellation(cfg_, raw_nav_, t);
    constellation_ = c;
    store_ = orbit::EphemerisStore(constellation_.nav.ephemerides, constellation_.store_options());
    served_ = true;
    spdlog::info("lockstep: satellites for the simulator's date: {}", constellation_.describe());
  } catch (const Error& e) {
    spdlog::error("lockstep: the simulator's GPS time {} cannot be served: {}", gps_text(t), e.what());
  }
}

world::Truth Daemon::fallback_truth(std::size_t v, const time::GpsTime& t, double demo_elapsed_s) const noexcept {
  if (demo_drives(v)) return demo_.truth(t, demo_elapsed_s);
  world::Truth none;
  none.t = t;
  return none;
}

void Daemon::on_timer(const boost::system::error_code& ec) {
  // A handler already queued when shutdown() cancelled the timer still runs, with success.
  if (ec || stopped_) return;
  const double now = now_s();
  if (cfg_.time.mode == config::TimeMode::kRealtime) {
    if (!send_pending_) {
      const auto c0 = Clock::now();
      const double offset_s = sched_base_s_ + epoch_offset_s(index_, rate_hz_);
      emit_epoch(start_ + offset_s, offset_s, false, false);
      const double took_s = std::chrono::duration<double>(Clock::now() - c0).count();
      // A slow epoch now and then (a shared machine) must not make the next late:
      // the lead follows the slowest recent epoch, forgetting it slowly.
      compute_max_s_ = std::max(took_s, 0.97 * compute_max_s_);
      compute_lead_s_ = std::clamp(2.0 * compute_max_s_ + 0.005, 0.0, output_delay_s_);
      send_pending_ = true;
      arm_timer();  // the same epoch's output time
      return;
    }
    send_epochs();
  } else if (!router_.any_fresh(now)) {
    // Lockstep without a live simulator: keep the receivers talking at the
    // configured rate (demo before any simulator, no fix after one stopped).
    emit_epoch(lock_next_, lock_next_ - start_, true);
    lock_step(1.0);
  }
  const double delay_s = cfg_.time.mode == config::TimeMode::kRealtime ? output_delay_s_ : 0.0;
  const auto now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t0_).count() -
                      std::llround((sched_base_s_ + delay_s) * 1e9);
  const ScheduleStep step = next_epoch(index_, rate_hz_, now_ns);
  if (step.skipped > 0) {
    epochs_skipped_ += static_cast<uint64_t>(step.skipped);
    spdlog::warn("epoch loop late: skipped {} epoch(s) ({} in total)", step.skipped, epochs_skipped_);
  }
  index_ = step.next_index;
  arm_timer();
}

void Daemon::lockstep_advance(const time::GpsTime& stamp) {
  // Far behind (simulator jumped ahead): move to the newest due epoch.
  const double behind_s = stamp - lock_next_;
  if (behind_s > 10.0 * period_s_) {
    const double n = std::floor(behind_s / period_s_);
    epochs_skipped_ += static_cast<uint64_t>(n);
    lock_step(n);
    spdlog::warn("lockstep: simulator jumped {:.1f} s ahead; skipped {:.0f} epochs", behind_s, n);
  }
  while (!(stamp < lock_next_)) {
    emit_epoch(lock_next_, lock_next_ - start_, false);
    lock_step(1.0);
  }
}

void Daemon::send_epochs() noexcept {
  send_pending_ = false;
  for (const auto& rp : rigs_) send_rig_epoch(*rp);
  publish_status();
}

/// The port events acting on rig's ports (docs/faults.md "Link faults"); no stage: none.
std::span<const faults::FaultStatus> Daemon::link_status(const Rig& rig) noexcept {
  faults::FaultStage* stage = rig.receiver->faults();
  return stage != nullptr ? stage->status() : std::span<const faults::FaultStatus>{};
}

void Daemon::send_rig_epoch(Rig& rig) noexcept {
  const std::span<const faults::FaultStatus> faults_now = link_status(rig);
  for (const auto& c : rig.channels) {
    c->set_link_faults(faults_now);
    c->send_epoch();
  }
}

void Daemon::emit_epoch(const time::GpsTime& t, double demo_elapsed_s, bool fallback_only, bool send) {
  note_coverage(t);
  const double now = now_s();
  for (std::size_t v = 0; v < vehicles_.size(); ++v) {
    const TruthRouter& r = router_.router(v);
    vehicles_[v].truth = !fallback_only && r.has_driver() ? r.truth_at(t, now) : fallback_truth(v, t, demo_elapsed_s);
  }
  // The sky once for every antenna (a receiver's world would update its own
  // the same way for its one antenna: World::step).
  antennas_.clear();
  SystemSet tracked;  // what some receiver tracks (CFG-GNSS): the sky evaluates only those
  for (const auto& rp : rigs_) {
    Rig& rig = *rp;
    rig.truth = antenna_truth(vehicles_[rig.vehicle_index].truth, rig.lever_arm_m, router_.attitude(rig.vehicle_index));
    antennas_.push_back(rig.truth.pos_m);
    tracked = tracked.unite(rig.receiver->receiver().systems());
  }
  if (base_) {
    antennas_.push_back(base_->position_ecef_m());
    tracked = SystemSet::all();
  }
  // A receiver's observables do not depend on which others read the sky
  // (SkyErrors' grid is GPS time's), so each is gnssemu batch's.
  sky_.update(t, antennas_, tracked);
  if (base_ && base_->is_epoch(t)) {
    base_bytes_.clear();
    base_->step(sky_, base_bytes_);
    if (caster_) caster_->publish(base_bytes_);
    for (const auto& port : base_ports_) port->write_epoch(base_bytes_);
  }
  if (epochs_ > 0 && t > last_epoch_t_) line_s_ += t - last_epoch_t_;
  ++epochs_;
  last_epoch_t_ = t;
  const double run_s = run_time_s(t);
  last_run_s_ = run_s;
  for (const auto& rp : rigs_) emit_rig_epoch(*rp, t, run_s, send);
  if (send) publish_status();
}

void Daemon::emit_rig_epoch(Rig& rig, const time::GpsTime& t, double run_s, bool send) {
  const world::Truth& truth = rig.truth;
  const receiver::Fix& fix = rig.receiver->step(sky_, truth);
  const receiver::RawEpoch& raw = rig.receiver->receiver().raw();
  rig.device.on_epoch(fix, chip_clock_s(t),
                      protocol::ubx::RawSource{&raw, &store_, {&raw_nav_.klobuchar, &raw_nav_.utc, raw.leap_seconds}, &raw_nav_.galileo_nequick, &raw_nav_.beidou_klobuchar});
  if (send) send_rig_epoch(rig);
  log_fault_transitions(rig, link_status(rig), run_s);
  record_status(rig, run_s, fix);
  const int type = static_cast<int>(fix.type);
  rig.last_num_used = fix.num_used;
  rig.last_num_tracked = fix.num_tracked;
  if (type != rig.last_fix_type || truth.valid != rig.last_truth_valid) {
    spdlog::info("{}epoch {}: truth {}, fix {} with {} satellites (PDOP {:.1f})", who(rig), gps_text(t),
                 truth.valid ? "valid" : "none", receiver::fix_type_name(fix.type), fix.num_used, fix.dop.pdop);
    rig.last_fix_type = type;
    rig.last_truth_valid = truth.valid;
  }
  spdlog::debug("{}epoch tow {:.2f}: fix {} nsat {} lat {:.7f} lon {:.7f} h {:.1f}", who(rig), t.tow_s(), type,
                fix.num_used, fix.lla.lat_rad * kRadToDeg, fix.lla.lon_rad * kRadToDeg, fix.lla.height_m);
}

void Daemon::on_nav_period(Rig& rig, std::size_t src) {
  apply_chip_settings(rig);  // the solution's satellite cap follows the chip's rate
  // The emulator runs 1..10 Hz (docs/configuration.md rate_hz); the
  // device gives a host asking for more or less the nearest rate it runs.
  // One epoch clock drives every receiver of a fleet: the last host's rate
  // is everyone's (docs/configuration.md §Vehicles).
  const double period_s = rig.device.config().nav_period_s();
  const double p = rig.device.epoch_period_s();
  const protocol::ubx::wire::CfgRate rate = rig.device.config().rate;
  if (p != period_s) {
    spdlog::warn("output {}: host asked for a {:.3f} s navigation period (CFG-RATE measRate {} ms, navRate {}); "
                 "running at {:.3g} Hz, the nearest rate within 1..10 Hz",
                 rig.cfg.outputs[src].name, period_s, rate.measRate, rate.navRate, 1.0 / p);
  }
  if (std::abs(p - period_s_) < 1e-9) return;
  spdlog::info("output {}: host set the navigation rate to {:.3g} Hz (CFG-RATE measRate {} ms)", rig.cfg.outputs[src].name,
               1.0 / p, rate.measRate);
  period_s_ = p;
  rate_hz_ = 1.0 / p;
  refresh_status_setup();
  if (cfg_.time.mode == config::TimeMode::kRealtime) {
    // Next epoch on a whole multiple of the new period (u-blox aligns
    // measurements to GPS time; elapsed 0 is on a whole GPS second).
    // Before the first epoch (the clock waits for a whole GPS second) the
    // schedule starts at that epoch.
    const double elapsed = std::max(now_s(), 0.0);
    sched_base_s_ = std::ceil(elapsed / p - 1e-9) * p;
    index_ = 0;
  } else {
    lock_grid_from(lock_next_);  // the pending epoch, or the next one of the new grid
  }
  if (send_pending_) send_epochs();  // the computed epoch leaves now, not never
  arm_timer();  // replaces the pending wait
}

void Daemon::receive() {
  socket_.async_receive_from(asio::buffer(rx_buf_), peer_,
                             [this](const boost::system::error_code& ec, std::size_t n) {
                               if (ec == asio::error::operation_aborted || !socket_.is_open()) return;
                               if (ec) {
                                 // Back off rather than spin on a persistent error.
                                 spdlog::warn("truth input: receive error: {}; retrying in 0.5 s", ec.message());
                                 retry_timer_.expires_after(std::chrono::milliseconds(500));
                                 retry_timer_.async_wait([this](const boost::system::error_code& tec) {
                                   if (!tec && !stopped_ && socket_.is_open()) receive();
                                 });
                                 return;
                               }
                               on_datagram(n);
                               drain_truth();
                               receive();
                             });
}

void Daemon::drain_truth() {
  // The truth socket's share of a wake-up: what the kernel holds, up to
  // kTruthPerWake datagrams, before the other handlers (ports, timers) run again.
  for (int k = 0; k < kTruthPerWake; ++k) {
    boost::system::error_code ec;
    if (socket_.available(ec) == 0 || ec) return;
    const std::size_t n = socket_.receive_from(asio::buffer(rx_buf_), peer_, 0, ec);
    if (ec) return;
    on_datagram(n);
  }
}

void Daemon::refresh_vehicle_allows() {
  for (std::size_t v = 0; v < vehicles_.size(); ++v) {
    VehicleState& vs = vehicles_[v];
    vs.allow = TruthAllowList{};
    for (const config::VehicleConfig& vc : cfg_.vehicles) {
      if (vc.id != router_.id(v) || vc.allow.empty()) continue;
      vs.allow = TruthAllowList(vc.allow);
      spdlog::info("truth: vehicle '{}' accepts packets from {} only", vc.id, vs.allow.describe());
    }
  }
}

void Daemon::on_datagram(std::size_t n) {
  const double now = now_s();
  const std::string_view data(rx_buf_.data(), n);
  auto report = [&](DropReason reason, const std::string& detail) {
    const uint64_t count = drops_.record(reason, now);
    if (count > 0) {
      spdlog::warn("truth: dropped {} packet(s) from {}:{}: {} ({}); {} dropped in total", count,
                   peer_.address().to_string(), peer_.port(), drop_reason_name(reason), detail, drops_.total());
    }
  };
  if (!allow_.allows(peer_.address())) {
    report(DropReason::kNotAllowed, "sender not in [truth] allow");
    return;
  }
  const ParseResult parsed = parse_truth_packet(data, frame_);
  if (!parsed.ok) {
    report(parsed.reason, parsed.detail);
    return;
  }
  const std::optional<std::size_t> vi = router_.find(parsed.sample.vehicle);
  if (!vi) {
    // Never a new receiver: counted, logged at the drops' rate, nothing kept.
    report(DropReason::kUnknownVehicle, "vehicle '" + parsed.sample.vehicle + "' is not configured");
    return;
  }
  const std::size_t v = *vi;
  VehicleState& vs = vehicles_[v];
  if (!vs.allow.allows(peer_.address())) {
    vs.drops.record(DropReason::kNotAllowed, now);
    report(DropReason::kNotAllowed, "sender not in vehicle '" + parsed.sample.vehicle + "' allow");
    return;
  }
  const TruthRouter& vr = router_.router(v);
  const bool had_driver = vr.has_driver();
  const bool was_fresh = vr.driver_fresh(now);
  const time::GpsTime clock =
      cfg_.time.mode == config::TimeMode::kRealtime ? realtime_clock_gps() : lock_next_;
  const TruthRouter::Ingest in = router_.ingest(parsed.sample, clock, now).in;
  if (!in.accepted) {
    vs.drops.record(in.reason, now);
    report(in.reason, "vehicle '" + parsed.sample.vehicle + "'");
    return;
  }
  ++packets_ok_;
  ++vs.packets_ok;
  if (in.new_vehicle) {
    spdlog::info("truth: vehicle '{}' from {}:{}", parsed.sample.vehicle, peer_.address().to_string(), peer_.port());
  }
  if (!in.driving) note_other_vehicle(parsed.sample.vehicle);
  if (in.driving) vs.ever_driven = true;
  if (in.driving && in.step.jump()) note_jump(v, parsed.sample.vehicle, in.step, now);
  if (in.driving && !had_driver) {
    spdlog::info("truth: vehicle '{}' drives {}{}", vr.driver_id(), fleet_ ? "its receivers" : "the receiver",
                 cfg_.demo.enabled ? " (demo off for good)" : "");
  } else if (in.driving && !was_fresh) {
    spdlog::info("truth: vehicle '{}' is back", vr.driver_id());
  } else if (in.driving && in.reanchored) {
    spdlog::debug("truth: sim clock of '{}' re-anchored", vr.driver_id());
  }
  if (in.driving && parsed.sample.gps_time) align_to_packet_time(in.stamp);
  if (in.driving && cfg_.time.mode == config::TimeMode::kLockstep) {
    // Every driven vehicle must have reached an epoch before it is computed.
    if (const std::optional<time::GpsTime> reached = router_.reached(now)) lockstep_advance(*reached);
  }
}

void Daemon::note_jump(std::size_t v, const std::string& id, const VehicleTrack::Step& step, double now) {
  // Kept as sent: its receivers lose lock and reacquire where it now is.
  VehicleState& vs = vehicles_[v];
  ++vs.jumps;
  if (now - vs.jump_logged_s < kJumpLogPeriodS) return;
  const uint64_t unlogged = vs.jumps - vs.jumps_logged - 1;
  vs.jump_logged_s = now;
  vs.jumps_logged = vs.jumps;
  spdlog::warn("truth: vehicle '{}' jumped {:.3f} km in {:.3f} s ({:.3g} m/s, faster than any vehicle): kept as "
               "sent, its receivers lose lock and reacquire there; {} jump(s) in total{}",
               id, step.distance_m / 1000.0, step.dt_s, step.distance_m / std::max(step.dt_s, 1e-9),
               vs.jumps, unlogged > 0 ? fmt::format(" ({} not logged)", unlogged) : "");
}

void Daemon::align_to_packet_time(const time::GpsTime& stamp) {
  if (cfg_.time.mode == config::TimeMode::kRealtime) {
    // The epoch clock is not moved in realtime mode; say why there is no fix.
    const double off_s = stamp - realtime_clock_gps();
    if (std::abs(off_s) > 10.0 && !warned_gps_offset_) {
      warned_gps_offset_ = true;
      spdlog::warn("truth carries GPS time {} but the epoch clock is {} s away: truth cannot be used; "
                   "set [time] start or use_wall_clock_date to match the simulator",
                   gps_text(stamp), off_s);
    }
    return;
  }
  // Lockstep: the first packet with GPS time puts the epoch clock on it.
  if (gps_aligned_) return;
  gps_aligned_ = true;
  lock_grid_from(stamp);
  const time::GpsTime first = lock_next_;
  const bool served = constellation_.serves(first);
  // The run starts over at the packets' time: a receiver powered on there,
  // in the state [receiver.acquisition] start configures, with the chip's
  // configuration as hosts left it. So a lockstep run repeats gnssemu batch
  // on the same truth, byte for byte: the receiver, the chip's uptime, ttff
  // and rate count, and the scenario's time line start at the first packet.
  if (!served) redate_constellation(first);
  for (const auto& rp : rigs_) restart_receiver(*rp, rp->cfg.receiver.acquisition.start);
  restart_scenario();
  chip_origin_ = first;
  for (const auto& rp : rigs_) rp->device.power_on(0.0);
  spdlog::info("lockstep: epochs follow the packets' GPS time from {}", gps_text(first));
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
// Daemon: SIGHUP reload (docs/daemon.md §Reload). Everything that can fail
// (the file, new receivers, new ports) is built before anything running is
// touched; then the plan is applied. A fleet's vehicles are added, removed,
// kept untouched or changed per FleetReloadPlan.
#include <algorithm>
#include <memory>

#include <spdlog/spdlog.h>

#include "config/setup/device_setup.hpp"
#include "config/setup/pipeline_setup.hpp"
#include "config/receiver_config.hpp"
#include "core/common/error.hpp"
#include "daemon/daemon.hpp"
#include "daemon/fleet_reload_plan.hpp"
#include "daemon/scene_setup.hpp"
#include "daemon/service/state_file.hpp"

namespace gnssemu::daemon {
namespace {

bool fleet_form(const config::Config& c) { return !c.vehicles.empty() || c.fleet.has_value(); }

}  // namespace

void Daemon::prepare_rig_update(RigUpdate& u, const scene::Scene* scene) {
  if (u.plan.receiver || u.plan.scene) {
    // A reload is not a power cycle: the new receiver keeps what the
    // running one knew (a hot start, whatever start the file gives).
    config::Config hot = u.cfg;
    hot.receiver.acquisition.start = receiver::StartMode::kHot;
    u.receiver = config::make_pipeline(hot, store_, pipeline::broadcast_of(constellation_.nav), scene);
  }
  // New ports open before the old ones close: a port that cannot open
  // fails the reload with everything as it was.
  for (std::size_t i : u.plan.reopen) {
    validate_port(u.cfg.outputs[i]);
    u.reopened.push_back(open_port(u.cfg.outputs[i], io_));
  }
}

void Daemon::apply_rig_update(RigUpdate& u) {
  Rig& rig = *u.rig;
  for (std::size_t k = 0; k < u.plan.reopen.size(); ++k) {
    const std::size_t i = u.plan.reopen[k];
    rig.cfg.outputs[i] = u.cfg.outputs[i];
    open_channel(rig, i, std::move(u.reopened[k]));
    rig.channels[i]->start();
    spdlog::info("reload: {}output {} now on {}", who(rig), rig.cfg.outputs[i].name, rig.channels[i]->port().describe());
  }
  if (u.receiver) {
    rig.cfg.receiver = u.cfg.receiver;
    rig.cfg.world = u.cfg.world;
    for (const auto& c : rig.channels) c->set_link_seed(rig.cfg.world.seed);
    u.receiver->adopt_faults(rig.receiver->take_faults());  // the faults go on around the new receiver
    rig.receiver = std::move(u.receiver);
    rig.receiver->receiver().set_corrections(&rig.device.corrections());
    rig.device.set_coast_as_no_fix(config::coast_as_no_fix(rig.cfg));
    apply_chip_settings(rig);  // the chip's CFG-NAV5 (what a host set, what its polls read back) stays in force
  }
  if (u.lever_arm) rig.lever_arm_m = u.lever_arm_m;
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
    std::string vehicles;  // a fleet's: what happened to its vehicles
    std::vector<std::string> port_event_warnings;
    std::unique_ptr<scene::Scene> scene;
    RigUpdate single;
    if (fleet_ != fleet_form(loaded)) {
      // plan_reload named the change of form: the receivers run on as they are.
      plan.receiver = plan.scene = false;
      plan.reopen.clear();
    } else if (fleet_) {
      // Each vehicle's receivers hold the top level's [receiver] merged: they change per vehicle.
      plan.receiver = false;
      if (plan.scene) {
        plan.need_restart.emplace_back("[scene] (every receiver of a fleet runs in it)");
        plan.scene = false;
      }
      vehicles = reload_fleet(loaded, plan);  // throws before it touches anything
    } else {
      port_event_warnings = check_reload_port_events(loaded);
      if (plan.scene) scene = load_scene_logged(loaded);
      single.rig = &rig();
      single.cfg = loaded;
      single.plan = plan;
      prepare_rig_update(single, plan.scene ? scene.get() : scene_.get());
    }
    // Apply: nothing below throws.
    if (single.rig != nullptr) {
      for (std::size_t i : plan.reopen) cfg_.outputs[i] = loaded.outputs[i];
      if (plan.receiver || plan.scene) {
        cfg_.receiver = loaded.receiver;
        cfg_.world = loaded.world;
      }
      if (plan.scene) {
        cfg_.scene = loaded.scene;
        // The running receiver holds the old scene: its faults move first, then it goes.
        single.receiver->adopt_faults(rig().receiver->take_faults());
        rig().receiver.reset();
        scene_ = std::move(scene);
      }
      if (!rig().receiver) {
        rig().receiver = std::move(single.receiver);
        rig().receiver->receiver().set_corrections(&rig().device.corrections());
        rig().cfg.receiver = cfg_.receiver;
        rig().cfg.world = cfg_.world;
        rig().device.set_coast_as_no_fix(config::coast_as_no_fix(cfg_));
        apply_chip_settings(rig());
      }
      apply_rig_update(single);
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
    if (plan.log_level) cfg_.log = loaded.log;
    if (!fleet_) rig().cfg = cfg_;  // the single form's receiver runs the top level
    for (const std::string& what : plan.need_restart) {
      spdlog::warn("reload: {} changed: applies at the next restart; running on the old value", what);
    }
    for (const std::string& w : port_event_warnings) spdlog::warn("reload: {}", w);
    refresh_status_setup();  // mask, thresholds, reopened ports
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    const std::string what = plan.describe(cfg_) + (vehicles.empty() ? "" : "; " + vehicles);
    spdlog::info("reload: {} applied in {:.1f} ms ({})", cfg_.source, ms, what);
    notify_.ready("reloaded: " + what);
  } catch (const std::exception& e) {
    spdlog::error("reload failed, keeping the running configuration: {}", e.what());
    notify_.ready("reload failed: " + std::string(e.what()));
  }
}

std::string Daemon::reload_fleet(const config::Config& loaded, ReloadPlan& top) {
  const FleetReloadPlan fp = plan_fleet_reload(cfg_, loaded, top.need_restart);
  const std::vector<config::VehicleConfig> now = config::resolve_vehicles(loaded);
  auto removed = [&fp](const std::string& id) {
    return std::any_of(fp.removed.begin(), fp.removed.end(), [&id](const VehicleReload& v) { return v.id == id; });
  };
  // A --scenario event must still name a receiver: the next start would refuse it.
  for (const config::ScenarioEvent& e : scenario_) {
    if (e.target.empty()) continue;
    bool named = false;
    for (const config::VehicleConfig& v : now) {
      for (const config::VehicleReceiverConfig& r : v.receivers) named = named || config::target_matches(e.target, v.id, r.name);
    }
    if (!named) {
      throw Error(scenario_source_, e.event.line,
                  "target '" + e.target + "' names no vehicle or receiver in " + loaded.source +
                      ": the next start would refuse this --scenario event; give it a target anew and restart, or "
                      "keep its vehicle");
    }
  }

  // Prepare: what can fail, before anything running is touched.
  std::vector<RigUpdate> updates;
  for (const VehicleReload& vr : fp.changed) {
    const config::VehicleConfig& v = now[vr.loaded];
    for (const ReceiverReload& rr : vr.receivers) {
      RigUpdate u;
      for (const auto& rp : rigs_) {
        if (rp->vehicle == vr.id && rp->name == rr.name) u.rig = rp.get();
      }
      if (u.rig == nullptr) continue;  // the plan's receivers are the running ones: not reached
      u.cfg = config::receiver_config(cfg_, v, v.receivers[rr.loaded]);
      u.plan = rr.plan;
      u.lever_arm = rr.lever_arm;
      u.lever_arm_m = v.receivers[rr.loaded].lever_arm_m;
      prepare_rig_update(u, scene_.get());
      updates.push_back(std::move(u));
    }
  }
  struct Added {
    std::unique_ptr<Rig> rig;
    std::vector<std::unique_ptr<OutputPort>> ports;
  };
  std::vector<Added> added;
  const SystemSet nav_systems = orbit::systems_of(constellation_.nav);
  for (const VehicleReload& vr : fp.added) {
    const config::VehicleConfig& v = now[vr.loaded];
    for (const config::VehicleReceiverConfig& r : v.receivers) {
      Added a;
      a.rig = std::make_unique<Rig>(v.id, r.name, 0, config::receiver_config(cfg_, v, r), r.lever_arm_m, nav_systems);
      Rig& rig = *a.rig;
      if (const SystemSet off = rig.cfg.world.systems.minus(sky_.systems()); !off.empty()) {
        throw Error(loaded.source, 0, "vehicle '" + v.id + "' receiver " + r.name + ": constellations " +
                                          systems_text(off).data() +
                                          " are not in the running sky (the systems of the receivers at start): "
                                          "a vehicle with them is added at a restart");
      }
      if (const std::string& f = rig.cfg.state_file; !f.empty()) {
        auto same_file = [&f](const Rig& o) { return o.cfg.state_file == f; };
        for (const auto& o : rigs_) {
          if (!removed(o->vehicle) && same_file(*o)) {
            throw Error(loaded.source, 0, "receivers " + o->label() + " and " + rig.label() + " share state_file " + f);
          }
        }
        for (const Added& o : added) {
          if (same_file(*o.rig)) throw Error(loaded.source, 0, "receivers " + o.rig->label() + " and " + rig.label() + " share state_file " + f);
        }
        if (load_state_file(f, rig.device)) {
          spdlog::info("{}: receiver: saved configuration loaded from {}", rig.label(), f);
        }
      }
      restart_receiver(rig, rig.cfg.receiver.acquisition.start);
      for (const config::OutputPortConfig& o : rig.cfg.outputs) {
        validate_port(o);
        a.ports.push_back(open_port(o, io_));
      }
      added.push_back(std::move(a));
    }
  }

  // Removed vehicles: their receivers stop, their ports close (pty symlinks go).
  for (const VehicleReload& vr : fp.removed) {
    const std::optional<std::size_t> v = router_.find(vr.id);
    for (const auto& rp : rigs_) {
      if (rp->vehicle != vr.id) continue;
      log_fault_ends(*rp, "its vehicle left the configuration");
      log_port_summary(*rp);
      rp->channels.clear();
    }
    if (v) {
      const VehicleState& vs = vehicles_[*v];
      spdlog::info("reload: vehicle '{}' removed: its receivers stopped and its outputs closed ({} packets accepted, "
                   "{} dropped); its truth packets are dropped from now on (unknown_vehicle)",
                   vr.id, vs.packets_ok, vs.drops.total());
    }
  }
  std::erase_if(rigs_, [&removed](const std::unique_ptr<Rig>& r) { return removed(r->vehicle); });

  // The vehicles now: the running ones that stay, in their order, then the added ones.
  std::vector<std::string> ids;
  for (std::size_t v = 0; v < router_.size(); ++v) {
    if (!removed(router_.id(v))) ids.push_back(router_.id(v));
  }
  for (const VehicleReload& vr : fp.added) ids.push_back(vr.id);
  const std::vector<std::optional<std::size_t>> moved = router_.reshape(ids);
  std::vector<VehicleState> states(ids.size());
  for (std::size_t v = 0; v < moved.size(); ++v) {
    if (moved[v]) states[*moved[v]] = std::move(vehicles_[v]);
  }
  vehicles_ = std::move(states);
  for (const auto& rp : rigs_) rp->vehicle_index = *moved[rp->vehicle_index];

  // Added vehicles: powered on now, their ports as at start-up.
  for (Added& a : added) {
    Rig& rig = *a.rig;
    rig.vehicle_index = *router_.find(rig.vehicle);
    wire_rig(rig, std::move(a.ports), chip_clock_s(last_epoch_t_));
    print_ports(rig);
    for (const auto& c : rig.channels) {
      spdlog::info("reload: vehicle '{}' added: {} {} on {}", rig.vehicle, rig.label(), c->output_summary(),
                   c->port().describe());
    }
    if (!scenario_.empty() && !events_for(rig, scenario_).empty()) {
      spdlog::warn("reload: {}: the --scenario events run on the run's time line from the first epoch: an added "
                   "receiver gets none of them (ctl inject reaches it)",
                   rig.label());
    }
    rigs_.push_back(std::move(a.rig));
  }
  std::fflush(stdout);

  for (RigUpdate& u : updates) apply_rig_update(u);
  for (const VehicleReload& vr : fp.changed) {
    spdlog::info("reload: vehicle '{}' changed: applied live: {}", vr.id, vr.describe_live());
    if (const std::string r = vr.describe_restart(); r != "nothing") {
      spdlog::warn("reload: vehicle '{}' changed: needs a restart, running on the old values: {}", vr.id, r);
    }
  }
  if (!fp.kept.empty()) spdlog::info("reload: vehicle(s) unchanged, running on untouched: {}", FleetReloadPlan::ids(fp.kept));

  antennas_.reserve(rigs_.size() + (base_ ? 1 : 0));
  if (status_server_) status_server_->set_producer(rig().status);
  // The vehicles as they run now: the next reload compares with them.
  std::vector<config::VehicleConfig> running;
  for (const std::string& id : ids) {
    config::VehicleConfig v{id, {}, {}};
    for (const config::VehicleConfig& lv : loaded.vehicles) {
      if (lv.id == id) v.allow = lv.allow;  // applied live
    }
    for (const auto& rp : rigs_) {
      if (rp->vehicle != id) continue;
      v.receivers.push_back(config::VehicleReceiverConfig{rp->name, rp->lever_arm_m, config::receiver_settings(rp->cfg),
                                                          rp->cfg.outputs});
    }
    running.push_back(std::move(v));
  }
  cfg_.vehicles = std::move(running);
  cfg_.fleet.reset();
  refresh_vehicle_allows();
  return "vehicles added: " + FleetReloadPlan::ids(fp.added) + "; removed: " + FleetReloadPlan::ids(fp.removed) +
         "; changed: " + FleetReloadPlan::ids(fp.changed) + "; unchanged: " + FleetReloadPlan::ids(fp.kept);
}

}  // namespace gnssemu::daemon

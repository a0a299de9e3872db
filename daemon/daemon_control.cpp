// SPDX-License-Identifier: Apache-2.0
// The daemon's fault scenario and control socket (docs/faults.md, docs/daemon.md
// §Control socket): gnssemud --scenario, ctl status / inject / clear, and the
// fault list the status page and ctl status show.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <spdlog/spdlog.h>

#include "config/scenario_file.hpp"
#include "core/common/error.hpp"
#include "daemon/daemon.hpp"
#include "daemon/ports/link_faults.hpp"

namespace gnssemu::daemon {

namespace {

// The fault list is rebuilt for the status at most this often (it allocates
// strings; ramps change the text), s of run time.
constexpr double kFaultStatusPeriodS = 1.0;

}  // namespace

std::vector<faults::FaultEvent> Daemon::events_for(const Rig& rig, const std::vector<config::ScenarioEvent>& events) {
  std::vector<faults::FaultEvent> mine;
  for (const config::ScenarioEvent& e : events) {
    if (e.target.empty() || config::target_matches(e.target, rig.vehicle, rig.name)) mine.push_back(e.event);
  }
  return mine;
}

void Daemon::check_targets(const std::vector<config::ScenarioEvent>& events, const std::string& source) const {
  for (const config::ScenarioEvent& e : events) {
    if (e.target.empty()) continue;
    const bool any = std::any_of(rigs_.begin(), rigs_.end(), [&e](const std::unique_ptr<Rig>& r) {
      return config::target_matches(e.target, r->vehicle, r->name);
    });
    if (!any) {
      std::string names;
      for (const auto& r : rigs_) names += (names.empty() ? "" : ", ") + r->label();
      throw Error(source, e.event.line, "target '" + e.target + "' names no vehicle or receiver (receivers: " +
                                            names + ")");
    }
  }
  for (const auto& rp : rigs_) {
    if (const auto bad = check_port_events(events_for(*rp, events), rp->cfg.outputs.size(), source)) {
      throw Error(*bad);
    }
  }
}

void Daemon::set_scenario(std::vector<config::ScenarioEvent> events, const std::string& source) {
  check_targets(events, source);
  scenario_ = std::move(events);
  scenario_source_ = source;
  restart_scenario();
}

void Daemon::restart_scenario() {
  for (const auto& rp : rigs_) {
    Rig& rig = *rp;
    log_fault_ends(rig, "the scenario starts over");
    if (scenario_.empty()) {
      if (rig.receiver->faults() != nullptr) rig.receiver->set_faults({});  // injected events start over too
      continue;
    }
    rig.receiver->set_faults(events_for(rig, scenario_));
    rig.fault_status_s = -kFaultStatusPeriodS;
  }
}

void Daemon::start_control_socket() {
  if (cfg_.control.socket.empty()) return;
  control_ = std::make_unique<ControlServer>(io_, [this](std::string_view line) {
    return handle_control_request(line, *this);
  });
  control_->start(cfg_.control.socket);
  std::printf("gnssemud: control socket %s\n", control_->path().c_str());
}

std::vector<Rig*> Daemon::rigs_of(std::string_view target) const {
  std::vector<Rig*> out;
  for (const auto& rp : rigs_) {
    if (target.empty() || config::target_matches(target, rp->vehicle, rp->name)) out.push_back(rp.get());
  }
  if (out.empty()) {
    std::string names;
    for (const auto& r : rigs_) names += (names.empty() ? "" : ", ") + r->label();
    throw Error("target '" + std::string(target) + "' names no vehicle or receiver (receivers: " + names + ")");
  }
  return out;
}

void Daemon::write_status(std::string& out, std::string_view target) {
  const std::vector<Rig*> rigs = rigs_of(target);
  // One receiver named (or the single form): its status object as it always was.
  if (!fleet_ || target.find('/') != std::string_view::npos) {
    rigs.front()->status.write_json(out, 0);
    return;
  }
  out += "{\"receivers\":[";
  for (std::size_t i = 0; i < rigs.size(); ++i) {
    const Rig& r = *rigs[i];
    out += fmt::format("{}{{\"vehicle\":\"{}\",\"receiver\":\"{}\",\"status\":", i ? "," : "", r.vehicle, r.name);
    r.status.write_json(out, 0);
    out += '}';
  }
  out += "]}";
}

std::vector<std::string> Daemon::inject(std::string_view scenario, const std::string& source,
                                        std::string_view target) {
  std::vector<config::ScenarioEvent> targeted = config::parse_targeted_scenario(scenario, source);
  if (targeted.empty()) throw Error(source + ": no [[event]] to inject");
  if (!target.empty()) {
    (void)rigs_of(target);
    for (config::ScenarioEvent& e : targeted) {
      if (e.target.empty()) e.target = std::string(target);
    }
  }
  check_targets(targeted, source);
  for (const auto& rp : rigs_) {
    Rig& rig = *rp;
    const std::vector<faults::FaultEvent> mine = events_for(rig, targeted);
    if (mine.empty()) continue;
    if (rig.receiver->faults() == nullptr) rig.receiver->set_faults({});
    rig.receiver->faults()->inject(mine);  // all or nothing
    rig.fault_status_s = -kFaultStatusPeriodS;  // show them at the next epoch
  }
  std::vector<std::string> added;
  for (const config::ScenarioEvent& se : targeted) {
    const faults::FaultEvent& e = se.event;
    std::string line = std::string(faults::type_name(e.type)) + " " + faults::describe(e, e.start_s);
    char when[96];
    if (std::isfinite(e.duration_s)) {
      std::snprintf(when, sizeof when, " (in %.1f s, for %.1f s)", e.start_s, e.duration_s);
    } else {
      std::snprintf(when, sizeof when, " (in %.1f s, to the end)", e.start_s);
    }
    added.push_back(line + when + (se.target.empty() ? "" : " on " + se.target));
    spdlog::info("control: {} injected {}", source, added.back());
  }
  return added;
}

std::size_t Daemon::clear(std::string_view target) {
  std::size_t n = 0;
  for (Rig* rp : rigs_of(target)) {
    Rig& rig = *rp;
    log_fault_ends(rig, "cleared");
    if (faults::FaultStage* stage = rig.receiver->faults()) {
      n += stage->event_count();
      stage->clear();
    }
    rig.status.set_faults({});
  }
  spdlog::info("control: cleared {} fault(s)", n);
  return n;
}

std::size_t Daemon::fault_count() const {
  std::size_t n = 0;
  for (const auto& rp : rigs_) {
    const faults::FaultStage* stage = rp->receiver->faults();
    n += stage != nullptr ? stage->event_count() : 0;
  }
  return n;
}

void Daemon::record_faults(Rig& rig, double run_s) {
  faults::FaultStage* stage = rig.receiver->faults();
  if (stage == nullptr || run_s - rig.fault_status_s < kFaultStatusPeriodS) return;
  rig.fault_status_s = run_s;
  const auto st = stage->status();
  rig.faults_view.resize(st.size());
  for (std::size_t i = 0; i < st.size(); ++i) {
    const faults::FaultEvent& e = *st[i].event;
    FaultStatus& f = rig.faults_view[i];
    f.id = std::to_string(i + 1);
    f.type = faults::type_name(e.type);
    f.description = faults::describe(e, e.start_s + std::max(st[i].elapsed_s, 0.0));
    f.start_s = run_s - st[i].elapsed_s;
    f.end_s = std::isfinite(e.duration_s) ? f.start_s + e.duration_s : std::nan("");
    f.active = st[i].active;
  }
  rig.status.set_faults(rig.faults_view);
}

namespace {

std::vector<std::string> output_names(const std::vector<config::OutputPortConfig>& outputs) {
  std::vector<std::string> names;
  for (const config::OutputPortConfig& o : outputs) names.push_back(o.name);
  return names;
}

}  // namespace

void Daemon::log_fault_transitions(Rig& rig, std::span<const faults::FaultStatus> status, double run_s) {
  const std::span<const FaultTransition> changes = rig.fault_log.update(status);
  if (changes.empty()) return;  // every epoch but a transition's: nothing allocated
  const std::vector<std::string> names = output_names(rig.cfg.outputs);
  for (const FaultTransition& c : changes) {
    spdlog::info("{}fault {}: {} (run {:.1f} s)", who(rig), c.started ? "start" : "end",
                 fault_log_text(*status[c.index].event, names), run_s);
  }
}

void Daemon::log_fault_ends(Rig& rig, std::string_view why) {
  faults::FaultStage* stage = rig.receiver ? rig.receiver->faults() : nullptr;
  if (stage == nullptr) {
    rig.fault_log.end_all();
    return;
  }
  const auto status = stage->status();
  const std::vector<std::string> names = output_names(rig.cfg.outputs);
  for (const FaultTransition& c : rig.fault_log.end_all()) {
    if (c.index >= status.size()) continue;
    spdlog::info("{}fault end: {} (run {:.1f} s, {})", who(rig), fault_log_text(*status[c.index].event, names),
                 last_run_s_, why);
  }
}

std::vector<std::string> Daemon::check_reload_port_events(const config::Config& loaded) {
  // The running outputs stay until a restart (docs/daemon.md §Reload), so
  // every kept event still acts on its port. A --scenario event whose index
  // the file now gives no port or another one would be refused or moved by
  // the next start: the reload refuses the file now, while the rig runs.
  const std::vector<std::string> running = output_names(rig().cfg.outputs);
  const std::vector<std::string> reloaded = output_names(loaded.outputs);
  const std::vector<std::string> bad =
      check_port_events_on_reload(events_for(rig(), scenario_), running, reloaded, scenario_source_, loaded.source);
  if (!bad.empty()) {
    throw Error(bad.front() + "; with this [[output]] list the next start would refuse the --scenario event or put it "
                "on another output: give it its output anew in " + scenario_source_ +
                " and restart, or keep the [[output]] list");
  }
  // Injected events end at a restart: they keep acting on their running port.
  faults::FaultStage* stage = rig().receiver->faults();
  if (stage == nullptr) return {};
  std::vector<faults::FaultEvent> kept;
  for (const faults::FaultStatus& st : stage->status()) kept.push_back(*st.event);
  std::vector<std::string> warnings = check_port_events_on_reload(kept, running, reloaded, "ctl inject", loaded.source);
  for (std::string& w : warnings) w += ": it keeps acting on the running output until the restart, where it ends";
  return warnings;
}

}  // namespace gnssemu::daemon

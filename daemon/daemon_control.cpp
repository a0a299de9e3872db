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

void Daemon::set_scenario(std::vector<faults::FaultEvent> events, const std::string& source) {
  if (const auto bad = check_port_events(events, cfg_.outputs.size(), source)) throw Error(*bad);
  scenario_ = std::move(events);
  scenario_source_ = source;
  restart_scenario();
}

void Daemon::restart_scenario() {
  log_fault_ends("the scenario starts over");
  if (scenario_.empty()) {
    if (rig().receiver->faults() != nullptr) rig().receiver->set_faults({});  // injected events start over too
    return;
  }
  rig().receiver->set_faults(scenario_);
  fault_status_s_ = -kFaultStatusPeriodS;
}

void Daemon::start_control_socket() {
  if (cfg_.control.socket.empty()) return;
  control_ = std::make_unique<ControlServer>(io_, [this](std::string_view line) {
    return handle_control_request(line, *this);
  });
  control_->start(cfg_.control.socket);
  std::printf("gnssemud: control socket %s\n", control_->path().c_str());
}

void Daemon::write_status(std::string& out) { status_.write_json(out, 0); }

std::vector<std::string> Daemon::inject(std::string_view scenario, const std::string& source) {
  const std::vector<faults::FaultEvent> events = config::parse_scenario(scenario, source);
  if (events.empty()) throw Error(source + ": no [[event]] to inject");
  if (const auto bad = check_port_events(events, rig().channels.size(), source)) throw Error(*bad);
  if (rig().receiver->faults() == nullptr) rig().receiver->set_faults({});
  rig().receiver->faults()->inject(events);  // all or nothing
  std::vector<std::string> added;
  for (const faults::FaultEvent& e : events) {
    std::string line = std::string(faults::type_name(e.type)) + " " + faults::describe(e, e.start_s);
    char when[96];
    if (std::isfinite(e.duration_s)) {
      std::snprintf(when, sizeof when, " (in %.1f s, for %.1f s)", e.start_s, e.duration_s);
    } else {
      std::snprintf(when, sizeof when, " (in %.1f s, to the end)", e.start_s);
    }
    added.push_back(line + when);
    spdlog::info("control: {} injected {}", source, added.back());
  }
  fault_status_s_ = -kFaultStatusPeriodS;  // show them at the next epoch
  return added;
}

std::size_t Daemon::clear() {
  const std::size_t n = fault_count();
  log_fault_ends("cleared");
  if (faults::FaultStage* stage = rig().receiver->faults()) stage->clear();
  status_.set_faults({});
  spdlog::info("control: cleared {} fault(s)", n);
  return n;
}

std::size_t Daemon::fault_count() const {
  const faults::FaultStage* stage = rig().receiver->faults();
  return stage != nullptr ? stage->event_count() : 0;
}

void Daemon::record_faults(double run_s) {
  faults::FaultStage* stage = rig().receiver->faults();
  if (stage == nullptr || run_s - fault_status_s_ < kFaultStatusPeriodS) return;
  fault_status_s_ = run_s;
  const auto st = stage->status();
  faults_view_.resize(st.size());
  for (std::size_t i = 0; i < st.size(); ++i) {
    const faults::FaultEvent& e = *st[i].event;
    FaultStatus& f = faults_view_[i];
    f.id = std::to_string(i + 1);
    f.type = faults::type_name(e.type);
    f.description = faults::describe(e, e.start_s + std::max(st[i].elapsed_s, 0.0));
    f.start_s = run_s - st[i].elapsed_s;
    f.end_s = std::isfinite(e.duration_s) ? f.start_s + e.duration_s : std::nan("");
    f.active = st[i].active;
  }
  status_.set_faults(faults_view_);
}

namespace {

std::vector<std::string> output_names(const std::vector<config::OutputPortConfig>& outputs) {
  std::vector<std::string> names;
  for (const config::OutputPortConfig& o : outputs) names.push_back(o.name);
  return names;
}

}  // namespace

void Daemon::log_fault_transitions(std::span<const faults::FaultStatus> status, double run_s) {
  const std::span<const FaultTransition> changes = fault_log_.update(status);
  if (changes.empty()) return;  // every epoch but a transition's: nothing allocated
  const std::vector<std::string> names = output_names(cfg_.outputs);
  for (const FaultTransition& c : changes) {
    spdlog::info("fault {}: {} (run {:.1f} s)", c.started ? "start" : "end",
                 fault_log_text(*status[c.index].event, names), run_s);
  }
}

void Daemon::log_fault_ends(std::string_view why) {
  faults::FaultStage* stage = rig().receiver ? rig().receiver->faults() : nullptr;
  if (stage == nullptr) {
    fault_log_.end_all();
    return;
  }
  const auto status = stage->status();
  const std::vector<std::string> names = output_names(cfg_.outputs);
  for (const FaultTransition& c : fault_log_.end_all()) {
    if (c.index >= status.size()) continue;
    spdlog::info("fault end: {} (run {:.1f} s, {})", fault_log_text(*status[c.index].event, names), last_run_s_, why);
  }
}

std::vector<std::string> Daemon::check_reload_port_events(const config::Config& loaded) {
  // The running outputs stay until a restart (docs/daemon.md §Reload), so
  // every kept event still acts on its port. A --scenario event whose index
  // the file now gives no port or another one would be refused or moved by
  // the next start: the reload refuses the file now, while the rig runs.
  const std::vector<std::string> running = output_names(cfg_.outputs);
  const std::vector<std::string> reloaded = output_names(loaded.outputs);
  const std::vector<std::string> bad =
      check_port_events_on_reload(scenario_, running, reloaded, scenario_source_, loaded.source);
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

// SPDX-License-Identifier: Apache-2.0
#include "daemon/reload_plan.hpp"

namespace gnssemu::daemon {
namespace {

using config::Config;

// Configurations compare by their canonical TOML (every key written).
bool same(const Config& a, const Config& b) { return config::to_toml(a) == config::to_toml(b); }

// running with the part that set() copies from loaded differs from running.
template <class Set>
bool differs(const Config& running, const Config& loaded, Set set) {
  Config m = running;
  set(m, loaded);
  return !same(m, running);
}

}  // namespace

ReloadPlan plan_reload(const Config& running, const Config& loaded) {
  ReloadPlan p;
  p.log_level = running.log.level != loaded.log.level;
  p.demo = differs(running, loaded, [](Config& m, const Config& l) { m.demo = l.demo; });
  p.receiver = differs(running, loaded, [](Config& m, const Config& l) {
    m.receiver = l.receiver;
    m.world = l.world;
  });
  p.scene = differs(running, loaded, [](Config& m, const Config& l) { m.scene = l.scene; });
  p.truth = differs(running, loaded, [](Config& m, const Config& l) { take_live_truth(m.truth, l.truth); });

  auto restart_if = [&](const char* what, auto set) {
    if (differs(running, loaded, set)) p.need_restart.emplace_back(what);
  };
  restart_if("[origin]", [](Config& m, const Config& l) { m.origin = l.origin; });
  restart_if("[nav]", [](Config& m, const Config& l) {
    m.nav_file = l.nav_file;
    m.nav = l.nav;
  });
  restart_if("[time]", [](Config& m, const Config& l) { m.time = l.time; });
  restart_if("rate_hz", [](Config& m, const Config& l) { m.rate_hz = l.rate_hz; });
  restart_if("[receiver] generation", [](Config& m, const Config& l) { m.generation = l.generation; });
  restart_if("[truth] bind/port", [](Config& m, const Config& l) {
    m.truth.bind_address = l.truth.bind_address;
    m.truth.port = l.truth.port;
  });
  restart_if("[status]", [](Config& m, const Config& l) { m.status = l.status; });
  restart_if("[control]", [](Config& m, const Config& l) { m.control = l.control; });

  // The form (one receiver on the top level's [[output]], or vehicles) is the daemon's shape.
  const bool was_fleet = !running.vehicles.empty() || running.fleet.has_value();
  if (was_fleet != (!loaded.vehicles.empty() || loaded.fleet.has_value())) {
    p.need_restart.emplace_back(was_fleet ? "[[vehicle]]/[fleet] replaced by top-level [[output]]"
                                          : "top-level [[output]] replaced by [[vehicle]]/[fleet]");
    return p;
  }
  if (running.outputs.size() != loaded.outputs.size()) {
    p.need_restart.push_back("outputs added or removed (" + std::to_string(running.outputs.size()) + " -> " +
                             std::to_string(loaded.outputs.size()) + ")");
    return p;
  }
  for (std::size_t i = 0; i < running.outputs.size(); ++i) {
    const config::OutputPortConfig& a = running.outputs[i];
    config::OutputPortConfig b = loaded.outputs[i];
    const bool transport = !(a.transport == b.transport);
    b.transport = a.transport;
    const bool settings = differs(running, loaded, [&](Config& m, const Config&) { m.outputs[i] = b; });
    if (settings && a.name != b.name) {
      p.need_restart.push_back("output " + a.name + " name (\"" + b.name + "\" in the file)");
    } else if (settings) {
      p.need_restart.push_back("output " + a.name + " protocols/messages/baud");
    } else if (transport) {
      p.reopen.push_back(i);
    }
  }
  return p;
}

std::string ReloadPlan::describe(const config::Config& now) const {
  std::string out;
  auto add = [&](const std::string& s) { out += (out.empty() ? "" : ", ") + s; };
  if (log_level) add("log level " + now.log.level);
  if (truth) add("[truth] allow/vehicle/timeouts");
  if (demo) add("[demo]");
  if (receiver) add("receiver models (receiver restarted)");
  if (scene) add("[scene] (receiver restarted)");
  for (std::size_t i : reopen) add("output " + now.outputs[i].name + " reopened");
  return out.empty() ? "nothing" : out;
}

}  // namespace gnssemu::daemon

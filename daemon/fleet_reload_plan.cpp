// SPDX-License-Identifier: Apache-2.0
#include "daemon/fleet_reload_plan.hpp"

#include <algorithm>

#include "config/receiver_config.hpp"

namespace gnssemu::daemon {
namespace {

using config::Config;
using config::VehicleConfig;

std::string names_of(const VehicleConfig& v) {
  std::string out;
  for (const config::VehicleReceiverConfig& r : v.receivers) out += (out.empty() ? "" : ", ") + r.name;
  return out;
}

const VehicleConfig* find_vehicle(const std::vector<VehicleConfig>& list, const std::string& id, std::size_t& index) {
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (list[i].id == id) {
      index = i;
      return &list[i];
    }
  }
  return nullptr;
}

bool contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

}  // namespace

bool VehicleReload::applies() const noexcept {
  return std::any_of(receivers.begin(), receivers.end(),
                     [](const ReceiverReload& r) { return r.lever_arm || r.plan.applies(); });
}

std::string VehicleReload::describe_live() const {
  std::string out;
  for (const ReceiverReload& r : receivers) {
    std::string parts;
    auto add = [&parts](const std::string& s) { parts += (parts.empty() ? "" : ", ") + s; };
    if (r.plan.receiver) add("receiver models (receiver restarted, hot)");
    if (!r.plan.reopen.empty()) add(std::to_string(r.plan.reopen.size()) + " output(s) reopened");
    if (r.lever_arm) add("lever arm");
    if (!parts.empty()) out += (out.empty() ? "" : "; ") + r.name + ": " + parts;
  }
  return out.empty() ? "nothing" : out;
}

std::string VehicleReload::describe_restart() const {
  std::string out;
  for (const ReceiverReload& r : receivers) {
    std::string parts;
    for (const std::string& s : r.plan.need_restart) parts += (parts.empty() ? "" : ", ") + s;
    if (!parts.empty()) out += (out.empty() ? "" : "; ") + r.name + ": " + parts;
  }
  for (const std::string& s : need_restart) out += (out.empty() ? "" : "; ") + s;
  return out.empty() ? "nothing" : out;
}

std::string FleetReloadPlan::ids(const std::vector<VehicleReload>& list) {
  std::string out;
  for (const VehicleReload& v : list) out += (out.empty() ? "" : ", ") + v.id;
  return out.empty() ? "none" : out;
}

FleetReloadPlan plan_fleet_reload(const Config& running, const Config& loaded,
                                  const std::vector<std::string>& top_restart) {
  const std::vector<VehicleConfig> was = config::resolve_vehicles(running);
  const std::vector<VehicleConfig> now = config::resolve_vehicles(loaded);
  FleetReloadPlan p;
  for (std::size_t i = 0; i < was.size(); ++i) {
    const VehicleConfig& a = was[i];
    VehicleReload vr;
    vr.id = a.id;
    vr.running = i;
    const VehicleConfig* b = find_vehicle(now, a.id, vr.loaded);
    if (b == nullptr) {
      p.removed.push_back(std::move(vr));
      continue;
    }
    for (std::size_t ra = 0; ra < a.receivers.size(); ++ra) {
      const config::VehicleReceiverConfig& x = a.receivers[ra];
      for (std::size_t rb = 0; rb < b->receivers.size(); ++rb) {
        const config::VehicleReceiverConfig& y = b->receivers[rb];
        if (y.name != x.name) continue;
        ReceiverReload rr;
        rr.name = x.name;
        rr.running = ra;
        rr.loaded = rb;
        rr.lever_arm = !(x.lever_arm_m == y.lever_arm_m);
        // Both on the running top level: what the top level changes is its plan's.
        rr.plan = plan_reload(config::receiver_config(running, a, x), config::receiver_config(running, *b, y));
        std::erase_if(rr.plan.need_restart, [&](const std::string& s) { return contains(top_restart, s); });
        if (rr.lever_arm || rr.plan.applies() || !rr.plan.need_restart.empty()) vr.receivers.push_back(std::move(rr));
      }
    }
    if (names_of(a) != names_of(*b)) {
      vr.need_restart.push_back("receivers added or removed (" + names_of(a) + " -> " + names_of(*b) + ")");
    }
    if (vr.receivers.empty() && vr.need_restart.empty()) {
      p.kept.push_back(std::move(vr));
    } else {
      p.changed.push_back(std::move(vr));
    }
  }
  for (std::size_t i = 0; i < now.size(); ++i) {
    std::size_t unused = 0;
    if (find_vehicle(was, now[i].id, unused) != nullptr) continue;
    VehicleReload vr;
    vr.id = now[i].id;
    vr.loaded = i;
    p.added.push_back(std::move(vr));
  }
  return p;
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#include "daemon/control/control_commands.hpp"

#include <exception>

#include <nlohmann/json.hpp>

namespace gnssemu::daemon {

namespace {

using json = nlohmann::ordered_json;

constexpr std::string_view kCommands = "status, inject, clear";

std::string error_reply(const std::string& why) { return json{{"ok", false}, {"error", why}}.dump(); }

// A member of the request other than the ones the command takes.
std::string unknown_member(const json& req, std::initializer_list<std::string_view> known) {
  for (const auto& [k, v] : req.items()) {
    bool ok = k == "cmd";
    for (const std::string_view n : known) ok = ok || k == n;
    if (!ok) return k;
  }
  return {};
}

}  // namespace

std::string handle_control_request(std::string_view request, ControlTarget& target) noexcept {
  try {
    const json req = json::parse(request, nullptr, false);
    if (req.is_discarded() || !req.is_object()) {
      return error_reply("not a JSON object: a request is one line of JSON, e.g. {\"cmd\":\"status\"}");
    }
    const auto cmd = req.find("cmd");
    if (cmd == req.end() || !cmd->is_string()) {
      return error_reply("\"cmd\" (a string) is required: one of " + std::string(kCommands));
    }
    const std::string name = cmd->get<std::string>();
    std::string who;  // "target": the receivers a command acts on
    if (const auto t = req.find("target"); t != req.end()) {
      if (!t->is_string() || t->get<std::string>().empty()) {
        return error_reply(name + ": \"target\" must be \"vehicle\" or \"vehicle/receiver\"");
      }
      who = t->get<std::string>();
    }
    if (name == "status") {
      if (const std::string k = unknown_member(req, {"target"}); !k.empty()) {
        return error_reply("status: unknown member '" + k + "' (known: target)");
      }
      std::string out = R"({"ok":true,"cmd":"status","status":)";
      target.write_status(out, who);
      out += '}';
      return out;
    }
    if (name == "clear") {
      if (const std::string k = unknown_member(req, {"target"}); !k.empty()) {
        return error_reply("clear: unknown member '" + k + "' (known: target)");
      }
      const std::size_t n = target.clear(who);
      return json{{"ok", true}, {"cmd", "clear"}, {"cleared", n}}.dump();
    }
    if (name == "inject") {
      if (const std::string k = unknown_member(req, {"scenario", "source", "target"}); !k.empty()) {
        return error_reply("inject: unknown member '" + k + "' (known: scenario, source, target)");
      }
      const auto sc = req.find("scenario");
      if (sc == req.end() || !sc->is_string()) return error_reply("inject: \"scenario\" (the scenario file's text) is required");
      std::string source = "control socket";
      if (const auto s = req.find("source"); s != req.end()) {
        if (!s->is_string() || s->get<std::string>().empty()) return error_reply("inject: \"source\" must be a non-empty string");
        source = s->get<std::string>();
      }
      const std::vector<std::string> added = target.inject(sc->get<std::string>(), source, who);
      return json{{"ok", true}, {"cmd", "inject"}, {"injected", added}, {"faults", target.fault_count()}}.dump();
    }
    return error_reply("unknown cmd '" + name + "' (known: " + std::string(kCommands) + ")");
  } catch (const std::exception& e) {
    return error_reply(e.what());
  }
}

}  // namespace gnssemu::daemon

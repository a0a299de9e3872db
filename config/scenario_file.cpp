// SPDX-License-Identifier: Apache-2.0
#include "config/scenario_file.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <toml++/toml.h>

#include "config/toml/toml_reader.hpp"
#include "core/common/error.hpp"
#include "core/common/sat_id.hpp"

namespace gnssemu::config {

namespace {

using detail::line_of;
using faults::FaultEvent;
using faults::FaultType;
using faults::Param;

std::string known_types() {
  std::string s;
  for (int i = 0; i < faults::kFaultTypeCount; ++i) {
    if (i > 0) s += ", ";
    s += faults::type_name(static_cast<FaultType>(i));
  }
  return s;
}

std::string known_keys(FaultType t) {
  std::string s = "start_s, duration_s, type";
  if (!faults::mode_key(t).empty()) s += ", " + std::string(faults::mode_key(t));
  for (const faults::ParamSpec& p : faults::param_specs())
    if (faults::find_param(t, p.name) == &p) s += ", " + std::string(p.name);
  return s;
}

double number_of(const toml::node& n, const std::string& file, const std::string& where, bool allow_bool) {
  if (allow_bool && n.is_boolean()) return n.as_boolean()->get() ? 1.0 : 0.0;
  const auto v = n.value<double>();
  if (!v || n.is_boolean() || n.is_string()) {
    throw Error(file, line_of(n), where + ": expected a number, got " + std::string(detail::type_name(n)));
  }
  if (!std::isfinite(*v)) throw Error(file, line_of(n), where + ": must be finite");
  return *v;
}

/// A parameter value: a number (true/false when allow_bool), or for a
/// satellite parameter also a RINEX name ("G05", "E11").
double value_of(const toml::node& n, const std::string& file, const std::string& where, const faults::ParamSpec& spec) {
  if (spec.satellite && n.is_string()) {
    const std::string& text = n.as_string()->get();
    const auto sat = parse_sat(text);
    if (!sat) {
      throw Error(file, line_of(n), where + ": unknown satellite '" + text +
                                        "' (a GPS PRN or a RINEX name: G05, R12, E30, C19, J02, S23)");
    }
    return faults::sat_param(*sat);
  }
  if (spec.systems) {
    const auto* text = n.as_string();
    const auto set = text != nullptr ? parse_systems(text->get()) : std::nullopt;
    if (!set) {
      throw Error(file, line_of(n), where + ": expected systems as RINEX letters in a string, such as \"G\" or "
                                            "\"G,R,E,C\"");
    }
    return static_cast<double>(set->bits());
  }
  return number_of(n, file, where, spec.boolean);
}

bool id_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
         c == '.';
}

// "id" or "id/name", each of letters, digits, '_', '-', '.'.
bool valid_target(std::string_view t) {
  const std::size_t slash = t.find('/');
  const std::string_view id = t.substr(0, slash);
  const std::string_view name = slash == std::string_view::npos ? std::string_view("x") : t.substr(slash + 1);
  auto ok = [](std::string_view p) { return !p.empty() && p.size() <= 64 && std::all_of(p.begin(), p.end(), id_char); };
  return ok(id) && ok(name);
}

FaultEvent read_event(const toml::table& t, const std::string& file, const std::string& where, std::string& target) {
  FaultEvent e;
  e.line = line_of(t);
  const toml::node* type_node = t.get("type");
  if (type_node == nullptr) throw Error(file, e.line, where + ": type is required (" + known_types() + ")");
  const auto* type_str = type_node->as_string();
  if (type_str == nullptr) throw Error(file, line_of(*type_node), where + ".type: expected a string");
  const auto type = faults::type_from_name(type_str->get());
  if (!type) {
    throw Error(file, line_of(*type_node),
                where + ".type: unknown type '" + type_str->get() + "' (known: " + known_types() + ")");
  }
  e.type = *type;
  const toml::node* start = t.get("start_s");
  if (start == nullptr) throw Error(file, e.line, where + ": start_s is required");
  e.start_s = number_of(*start, file, where + ".start_s", false);
  if (e.start_s < 0.0) throw Error(file, line_of(*start), where + ".start_s: must be >= 0");
  if (const toml::node* d = t.get("duration_s")) {
    e.duration_s = number_of(*d, file, where + ".duration_s", false);
    if (!(e.duration_s > 0.0)) throw Error(file, line_of(*d), where + ".duration_s: must be > 0");
  }
  const std::string_view mkey = faults::mode_key(e.type);
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    const std::string at = where + "." + key;
    if (key == "type" || key == "start_s" || key == "duration_s") continue;
    if (key == "target") {
      const auto* s = v.as_string();
      if (s == nullptr || !valid_target(s->get())) {
        throw Error(file, line_of(v), at + ": expected \"vehicle\" or \"vehicle/receiver\" (letters, digits, "
                                           "'_', '-', '.')");
      }
      target = s->get();
      continue;
    }
    if (!mkey.empty() && key == mkey) {
      const auto* s = v.as_string();
      if (s == nullptr) throw Error(file, line_of(v), at + ": expected a string");
      const auto names = faults::mode_names(e.type);
      std::string list;
      bool found = false;
      for (std::size_t i = 0; i < names.size(); ++i) {
        list += (i ? ", " : "") + std::string(names[i]);
        if (names[i] == s->get()) {
          e.mode = static_cast<std::uint8_t>(i);
          found = true;
        }
      }
      if (!found) throw Error(file, line_of(v), at + ": unknown value '" + s->get() + "' (known: " + list + ")");
      continue;
    }
    const faults::ParamSpec* spec = faults::find_param(e.type, key);
    if (spec == nullptr) {
      throw Error(file, line_of(v), where + ": unknown key '" + key + "' for type " +
                                         std::string(faults::type_name(e.type)) + " (known: " + known_keys(e.type) +
                                         ")");
    }
    faults::Ramp r;
    if (const auto* a = v.as_array(); a != nullptr && !spec->systems) {
      if (a->size() != 2) throw Error(file, line_of(v), at + ": a ramp is [from, to]");
      r.from = value_of(*a->get(0), file, at, *spec);
      r.to = value_of(*a->get(1), file, at, *spec);
    } else {
      r.from = r.to = value_of(v, file, at, *spec);
    }
    e.put(spec->id, r);
  }
  // Range and cross-field rules once every key is in (a key's companion may
  // come after it: eirp_dbw before lat_deg), at the line of the key named.
  if (const auto problem = faults::check_event(e)) {
    const std::string named = problem->substr(0, problem->find(':'));
    if (const toml::node* n = t.get(named)) throw Error(file, line_of(*n), where + "." + *problem);
    throw Error(file, e.line, where + ": " + *problem);
  }
  return e;
}

std::vector<ScenarioEvent> read_doc(const toml::table& doc, const std::string& file) {
  for (const auto& [k, v] : doc) {
    if (k.str() != "event") {
      throw Error(file, line_of(v), "unknown key '" + std::string(k.str()) + "': a scenario is a list of [[event]] tables");
    }
  }
  std::vector<ScenarioEvent> events;
  const toml::node* arr = doc.get("event");
  if (arr == nullptr) return events;
  const auto* a = arr->as_array();
  if (a == nullptr) throw Error(file, line_of(*arr), "event: expected [[event]] tables");
  int i = 0;
  for (const toml::node& n : *a) {
    const std::string where = "event[" + std::to_string(i++) + "]";
    const auto* t = n.as_table();
    if (t == nullptr) throw Error(file, line_of(n), where + ": expected a table");
    ScenarioEvent se;
    se.event = read_event(*t, file, where, se.target);
    events.push_back(std::move(se));
  }
  return events;
}

toml::table parse_doc(std::string_view text, const std::string& name) {
  try {
    return toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw Error(name, static_cast<int>(e.source().begin.line), "TOML syntax error: " + std::string(e.description()));
  }
}

toml::table parse_file(const std::string& path) {
  try {
    return toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw Error(path, static_cast<int>(e.source().begin.line), "TOML syntax error: " + std::string(e.description()));
  }
}

// The events of a file of one receiver: a target has nothing to pick.
std::vector<FaultEvent> untargeted(const std::vector<ScenarioEvent>& events, const std::string& file) {
  std::vector<FaultEvent> out;
  for (const ScenarioEvent& e : events) {
    if (!e.target.empty()) {
      throw Error(file, e.event.line, "target '" + e.target + "': only gnssemud with [[vehicle]] or [fleet] runs "
                                      "several receivers");
    }
    out.push_back(e.event);
  }
  return out;
}

}  // namespace

bool target_matches(std::string_view target, std::string_view vehicle, std::string_view receiver) noexcept {
  const std::size_t slash = target.find('/');
  if (slash == std::string_view::npos) return target == vehicle;
  return target.substr(0, slash) == vehicle && target.substr(slash + 1) == receiver;
}

std::vector<ScenarioEvent> read_targeted_scenario(const std::string& path) { return read_doc(parse_file(path), path); }

std::vector<ScenarioEvent> parse_targeted_scenario(std::string_view text, const std::string& name) {
  return read_doc(parse_doc(text, name), name);
}

std::vector<FaultEvent> read_scenario(const std::string& path) {
  return untargeted(read_targeted_scenario(path), path);
}

std::vector<FaultEvent> parse_scenario(std::string_view text, const std::string& name) {
  return untargeted(parse_targeted_scenario(text, name), name);
}

}  // namespace gnssemu::config

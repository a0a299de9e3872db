// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/plan/sweep_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "config/scenario_file.hpp"
#include "core/common/error.hpp"
#include "tools/gnssemu/sweep/plan/input_hash.hpp"
#include "tools/gnssemu/sweep/plan/truth_generator.hpp"

namespace gnssemu::cli::sweep {

namespace {

namespace fs = std::filesystem;

// A range form expands to at most this many values: a typo such as
// step = 0.0001 is an error, not a million tasks.
constexpr long kMaxRangeValues = 100000;

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

/// TOML text of a value (inline tables on one line).
std::string toml_text(const toml::node& n) {
  std::ostringstream os;
  if (const toml::table* t = n.as_table()) {
    toml::table copy = *t;
    copy.is_inline(true);
    toml::table wrap;
    wrap.insert("v", copy);
    os << toml::toml_formatter(wrap, toml::format_flags::none);
    std::string s = os.str();
    return s.substr(s.find('=') + 2);
  }
  toml::table wrap;
  wrap.insert("v", n);
  os << toml::toml_formatter(wrap, toml::format_flags::none);
  std::string s = os.str();
  return s.substr(s.find('=') + 2);
}

class Reader {
public:
  Reader(std::string name, std::string dir) : name_(std::move(name)), dir_(std::move(dir)) {}

  [[noreturn]] void fail(const toml::node& n, const std::string& what) const { throw Error(name_, line_of(n), what); }

  std::string path_of(const toml::node& n, const std::string& what) const {
    const auto* s = n.as_string();
    if (s == nullptr) fail(n, what + ": expected a file name (string)");
    fs::path p(s->get());
    if (p.is_relative()) p = fs::path(dir_) / p;
    p = p.lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) fail(n, what + " not found: " + p.string());
    return p.string();
  }

  /// The elements of an axis: an array's items, or the one value.
  static std::vector<const toml::node*> items(const toml::node& n) {
    std::vector<const toml::node*> out;
    if (const toml::array* a = n.as_array()) {
      for (const toml::node& e : *a) out.push_back(&e);
    } else {
      out.push_back(&n);
    }
    return out;
  }

  Axis axis(const std::string& key, const toml::node& n) const {
    Axis a;
    a.key = key;
    a.line = line_of(n);
    if (key == "truth") {
      for (const toml::node* e : items(n)) {
        if (e->is_table()) {
          const std::string text = toml_text(*e);
          (void)parse_generator(text, name_, line_of(*e));
          a.values.push_back({text, line_of(*e)});
        } else {
          a.values.push_back({path_of(*e, "truth file"), line_of(*e)});
        }
      }
    } else if (key == "scenario") {
      for (const toml::node* e : items(n)) {
        if (const auto* s = e->as_string(); s != nullptr && s->get() == kNoScenario) {
          a.values.push_back({kNoScenario, line_of(*e)});
          continue;
        }
        const std::string p = path_of(*e, "scenario file");
        (void)config::read_scenario(p);  // its own file:line errors
        a.values.push_back({p, line_of(*e)});
      }
    } else if (key == "seed" || key == "start_h") {
      const bool seed = key == "seed";
      if (const toml::table* t = n.as_table()) {
        range(key, *t, seed, a);
      } else {
        for (const toml::node* e : items(n)) a.values.push_back({number_text(key, *e, seed), line_of(*e)});
      }
    } else if (is_override_key(key)) {
      for (const toml::node* e : items(n)) {
        if (e->is_table()) fail(*e, key + ": a config override is a value (use a dotted key for a table's key)");
        const auto* s = e->as_string();
        a.values.push_back({s != nullptr ? s->get() : toml_text(*e), line_of(*e)});
      }
    } else {
      fail(n, "unknown axis key '" + key +
                  "' (truth, scenario, seed, start_h, or a dotted config key such as \"receiver.profile\")");
    }
    if (a.values.empty()) fail(n, "axis '" + key + "' has no values: the product would be empty");
    return a;
  }

  std::string number_text(const std::string& key, const toml::node& e, bool seed) const {
    if (seed) {
      const auto v = e.value_exact<int64_t>();
      if (!v || *v < 0) fail(e, key + ": expected a non-negative integer");
      return std::to_string(*v);
    }
    const auto v = e.value<double>();
    if (!v || !std::isfinite(*v) || *v < 0.0 || *v >= 24.0) fail(e, key + ": expected an hour of the GPS day in [0, 24)");
    return fmt::format("{}", *v);
  }

  void range(const std::string& key, const toml::table& t, bool seed, Axis& a) const {
    for (const auto& [k, v] : t) {
      if (k.str() != "from" && k.str() != "to" && k.str() != "step") {
        fail(v, fmt::format("{}: unknown range key '{}' (from, to, step)", key, k.str()));
      }
    }
    const toml::node* from = t.get("from");
    const toml::node* to = t.get("to");
    if (from == nullptr || to == nullptr) fail(t, key + ": a range needs from and to");
    const toml::node* step = t.get("step");
    const double f = std::stod(number_text(key, *from, seed));
    const double l = std::stod(number_text(key, *to, seed));
    const double s = step != nullptr ? step->value<double>().value_or(-1.0) : 1.0;
    if (!(s > 0.0) || (seed && s != std::floor(s))) fail(step != nullptr ? *step : t, key + ": step must be positive" + (seed ? std::string(" and whole") : ""));
    if (l < f) fail(t, fmt::format("{}: from {} > to {}: the product would be empty", key, f, l));
    const long n = static_cast<long>(std::floor((l - f) / s + 1e-9)) + 1;
    if (n > kMaxRangeValues) fail(t, fmt::format("{}: {} values (at most {})", key, n, kMaxRangeValues));
    for (long i = 0; i < n; ++i) {
      const double v = f + static_cast<double>(i) * s;
      a.values.push_back({seed ? std::to_string(static_cast<int64_t>(v)) : fmt::format("{}", v), line_of(t)});
    }
  }

  std::vector<Axis> axes(const toml::table& t) const {
    std::vector<Axis> out;
    for (const auto& [k, v] : t) out.push_back(axis(std::string(k.str()), v));
    // toml++ keeps keys sorted; the file's order is the product's order.
    std::stable_sort(out.begin(), out.end(), [](const Axis& a, const Axis& b) { return a.line < b.line; });
    return out;
  }

  const std::string& name() const { return name_; }
  const std::string& dir() const { return dir_; }

private:
  std::string name_, dir_;
};

}  // namespace

bool is_override_key(const std::string& key) { return key.find('.') != std::string::npos; }

SweepSpec parse_sweep(const std::string& text, const std::string& name, const std::string& dir) {
  toml::table doc;
  try {
    doc = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw Error(name, static_cast<int>(e.source().begin.line), std::string(e.description()));
  }
  const Reader r(name, dir);
  SweepSpec spec;
  spec.path = name;
  for (const auto& [k, v] : doc) {
    const std::string key(k.str());
    if (key != "config" && key != "outputs" && key != "hacc_k" && key != "axes" && key != "case") {
      r.fail(v, "unknown key '" + key + "' (config, outputs, hacc_k, [axes], [[case]])");
    }
  }
  const toml::node* cfg = doc.get("config");
  if (cfg == nullptr) throw Error(name, 1, "config = \"FILE\" (the base config) is required");
  spec.config_path = r.path_of(*cfg, "config file");
  if (const toml::node* o = doc.get("outputs")) {
    const toml::array* a = o->as_array();
    if (a == nullptr) r.fail(*o, "outputs: expected an array of \"errors\", \"nmea\", \"ubx\"");
    for (const toml::node& e : *a) {
      const auto* s = e.as_string();
      const std::string v = s != nullptr ? s->get() : "";
      if (v == "errors") spec.outputs.errors = true;
      else if (v == "nmea") spec.outputs.nmea = true;
      else if (v == "ubx") spec.outputs.ubx = true;
      else r.fail(e, "outputs: unknown output '" + v + "' (errors, nmea, ubx)");
    }
  }
  if (const toml::node* k = doc.get("hacc_k")) {
    const auto v = k->value<double>();
    if (!v || !(*v > 0.0) || *v > 100.0) r.fail(*k, "hacc_k: expected a number in (0, 100]");
    spec.hacc_k = *v;
  }
  if (const toml::node* a = doc.get("axes")) {
    const toml::table* t = a->as_table();
    if (t == nullptr) r.fail(*a, "axes: expected a table [axes]");
    spec.axes = r.axes(*t);
  }
  if (const toml::node* c = doc.get("case")) {
    const toml::array* arr = c->as_array();
    if (arr == nullptr || !arr->is_array_of_tables()) r.fail(*c, "case: expected [[case]] tables");
    for (const toml::node& e : *arr) {
      spec.cases.push_back({line_of(e), r.axes(*e.as_table())});
    }
  }
  if (spec.axes.empty() && spec.cases.empty()) {
    throw Error(name, 1, "no [axes] and no [[case]]: the product would be empty");
  }
  return spec;
}

SweepSpec read_sweep_file(const std::string& path) {
  const fs::path abs = fs::absolute(path).lexically_normal();
  std::error_code ec;
  if (!fs::is_regular_file(abs, ec)) throw Error(path, 0, "sweep file not found");
  SweepSpec spec = parse_sweep(read_file_bytes(abs.string()), path, abs.parent_path().string());
  spec.path = abs.string();
  return spec;
}

}  // namespace gnssemu::cli::sweep

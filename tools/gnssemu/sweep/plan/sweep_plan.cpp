// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/plan/sweep_plan.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <filesystem>
#include <map>
#include <sstream>

#include "config/setup/nav_setup.hpp"
#include "core/common/error.hpp"
#include "tools/gnssemu/sweep/collect/csv_row.hpp"
#include "tools/gnssemu/sweep/plan/input_hash.hpp"
#include "tools/gnssemu/sweep/plan/truth_generator.hpp"

namespace gnssemu::cli::sweep {

namespace {

namespace fs = std::filesystem;

constexpr const char* kHashColumns[] = {"config_hash", "nav_hash", "truth_hash", "scenario_hash"};

/// One axis set to multiply out, with the line that introduced it.
struct Product {
  std::vector<const Axis*> axes;
  int line = 0;
};

std::vector<Product> products(const SweepSpec& spec) {
  std::vector<Product> out;
  if (spec.cases.empty()) {
    Product p;
    for (const Axis& a : spec.axes) p.axes.push_back(&a);
    p.line = spec.axes.front().line;
    out.push_back(p);
    return out;
  }
  for (const SweepSpec::Case& c : spec.cases) {
    Product p;
    p.line = c.line;
    for (const Axis& a : spec.axes) {
      const Axis* use = &a;
      for (const Axis& ca : c.axes) {
        if (ca.key == a.key) use = &ca;
      }
      p.axes.push_back(use);
    }
    for (const Axis& ca : c.axes) {
      bool in_axes = false;
      for (const Axis& a : spec.axes) in_axes = in_axes || a.key == ca.key;
      if (!in_axes) p.axes.push_back(&ca);
    }
    out.push_back(p);
  }
  return out;
}

std::string settings_toml(const Plan& p) {
  toml::table t;
  t.insert("sweep", p.sweep_path);
  t.insert("config", p.config_path);
  toml::array outs;
  if (p.outputs.errors) outs.push_back("errors");
  if (p.outputs.nmea) outs.push_back("nmea");
  if (p.outputs.ubx) outs.push_back("ubx");
  t.insert("outputs", outs);
  t.insert("hacc_k", p.hacc_k);
  t.insert("tasks", static_cast<int64_t>(p.tasks.size()));
  std::ostringstream os;
  os << toml::toml_formatter(t, toml::format_flags::none);
  return "# What the tasks of tasks.csv share; written by gnssemu sweep plan.\n" + os.str() + "\n";
}

std::string plan_hash(const Plan& p) { return hex64(fnv1a64(tasks_csv_text(p) + settings_toml(p))); }

}  // namespace

const std::string& Plan::value(const Task& task, const std::string& key) const {
  static const std::string kEmpty;
  for (std::size_t i = 0; i < axis_keys.size(); ++i) {
    if (axis_keys[i] == key) return task.values[i];
  }
  return kEmpty;
}

std::vector<Override> Plan::overrides(const Task& task) const {
  std::vector<Override> out;
  for (std::size_t i = 0; i < axis_keys.size(); ++i) {
    if (task.values[i].empty()) continue;
    if (axis_keys[i] == "seed") out.emplace_back("receiver.seed", task.values[i]);
    if (is_override_key(axis_keys[i])) out.emplace_back(axis_keys[i], task.values[i]);
  }
  return out;
}

Plan make_plan(const SweepSpec& spec) {
  Plan plan;
  plan.sweep_path = spec.path;
  plan.config_path = spec.config_path;
  plan.outputs = spec.outputs;
  plan.hacc_k = spec.hacc_k;
  const std::vector<Product> prods = products(spec);
  for (const Product& p : prods) {
    for (const Axis* a : p.axes) {
      bool known = false;
      for (const std::string& k : plan.axis_keys) known = known || k == a->key;
      if (!known) plan.axis_keys.push_back(a->key);
    }
  }
  (void)config::load_config(spec.config_path);  // the base's own errors first
  const std::string config_hash = file_hash(spec.config_path);
  std::map<std::string, std::string> file_hashes, nav_hashes;
  const auto hash_of = [&](const std::string& path) -> const std::string& {
    auto it = file_hashes.find(path);
    if (it == file_hashes.end()) it = file_hashes.emplace(path, file_hash(path)).first;
    return it->second;
  };
  std::map<std::string, int> seen;  // axis values -> task id
  for (const Product& p : prods) {
    std::vector<std::size_t> idx(p.axes.size(), 0);
    for (bool done = false; !done;) {
      Task task;
      task.id = static_cast<int>(plan.tasks.size());
      task.values.assign(plan.axis_keys.size(), "");
      std::vector<int> lines(plan.axis_keys.size(), p.line);
      for (std::size_t i = 0; i < p.axes.size(); ++i) {
        for (std::size_t k = 0; k < plan.axis_keys.size(); ++k) {
          if (plan.axis_keys[k] != p.axes[i]->key) continue;
          task.values[k] = p.axes[i]->values[idx[i]].text;
          lines[k] = p.axes[i]->values[idx[i]].line;
        }
      }
      const std::string key = csv_row(task.values);
      if (const auto it = seen.find(key); it != seen.end()) {
        throw Error(spec.path, p.line,
                    fmt::format("duplicate task: these axis values repeat task {} (every task id must be unique)",
                                it->second));
      }
      seen.emplace(key, task.id);
      const std::string& truth = plan.value(task, "truth");
      if (truth.empty()) throw Error(spec.path, p.line, "no truth: set the truth axis in [axes] or in this case");
      task.config_hash = config_hash;
      task.truth_hash = is_generator_text(truth) ? hex64(fnv1a64(truth)) : hash_of(truth);
      const std::string& scenario = plan.value(task, "scenario");
      if (!scenario.empty() && scenario != kNoScenario) task.scenario_hash = hash_of(scenario);
      const std::vector<Override> ov = plan.overrides(task);
      std::string ov_key;
      for (const auto& [k, v] : ov) ov_key += k + '\x1f' + v + '\x1e';
      auto nav = nav_hashes.find(ov_key);
      if (nav == nav_hashes.end()) {
        config::Config cfg;
        try {
          cfg = config_with_overrides(spec.config_path, ov);
        } catch (const Error& e) {
          int line = p.line;
          for (std::size_t k = 0; k < plan.axis_keys.size(); ++k) {
            if (is_override_key(plan.axis_keys[k]) || plan.axis_keys[k] == "seed") line = lines[k];
          }
          throw Error(spec.path, line, e.what());
        }
        std::string all;
        for (const std::string& path : config::nav_paths(cfg)) all += hash_of(path);
        nav = nav_hashes.emplace(ov_key, hex64(fnv1a64(all))).first;
      }
      task.nav_hash = nav->second;
      plan.tasks.push_back(std::move(task));
      // Odometer: the last axis fastest.
      done = true;
      for (std::size_t i = p.axes.size(); i-- > 0;) {
        if (++idx[i] < p.axes[i]->values.size()) {
          done = false;
          break;
        }
        idx[i] = 0;
      }
    }
  }
  plan.hash = plan_hash(plan);
  return plan;
}

std::string tasks_csv_text(const Plan& plan) {
  std::vector<std::string> head{"task_id"};
  head.insert(head.end(), plan.axis_keys.begin(), plan.axis_keys.end());
  head.insert(head.end(), std::begin(kHashColumns), std::end(kHashColumns));
  std::string out = csv_row(head);
  for (const Task& t : plan.tasks) {
    std::vector<std::string> row{std::to_string(t.id)};
    row.insert(row.end(), t.values.begin(), t.values.end());
    for (const std::string* h : {&t.config_hash, &t.nav_hash, &t.truth_hash, &t.scenario_hash}) row.push_back(*h);
    out += csv_row(row);
  }
  return out;
}

void write_plan(const Plan& plan, const std::string& dir) {
  const fs::path d(dir);
  std::error_code ec;
  if (fs::exists(d / "plan.toml", ec)) {
    const std::string old = read_file_bytes((d / "plan.toml").string());
    const std::string mark = "plan_hash = \"";
    const std::size_t at = old.find(mark);
    const std::string old_hash = at == std::string::npos ? "" : old.substr(at + mark.size(), 16);
    bool has_results = false;
    if (fs::is_directory(d / "tasks", ec)) has_results = fs::directory_iterator(d / "tasks", ec) != fs::directory_iterator();
    if (old_hash != plan.hash && has_results) {
      throw Error((d / "plan.toml").string(), 0,
                  fmt::format("{} holds the results of a different plan ({}; this plan is {}): plan into a new "
                              "--out, or remove {}/tasks first",
                              dir, old_hash, plan.hash, dir));
    }
  }
  fs::create_directories(d / "tasks", ec);
  if (ec) throw Error(dir, 0, "cannot create the plan folder: " + ec.message());
  write_file_atomic((d / "tasks.csv").string(), tasks_csv_text(plan));
  write_file_atomic((d / "plan.toml").string(), settings_toml(plan) + "plan_hash = \"" + plan.hash + "\"\n");
}

Plan read_plan(const std::string& dir) {
  const fs::path d(dir);
  const std::string plan_path = (d / "plan.toml").string();
  std::error_code ec;
  if (!fs::is_regular_file(plan_path, ec)) throw Error(plan_path, 0, "not a sweep folder (run gnssemu sweep plan FILE --out DIR)");
  toml::table t;
  try {
    t = toml::parse_file(plan_path);
  } catch (const toml::parse_error& e) {
    throw Error(plan_path, static_cast<int>(e.source().begin.line), std::string(e.description()));
  }
  Plan p;
  p.sweep_path = t["sweep"].value_or(std::string());
  p.config_path = t["config"].value_or(std::string());
  p.hacc_k = t["hacc_k"].value_or(3.0);
  if (const toml::array* outs = t["outputs"].as_array()) {
    for (const toml::node& o : *outs) {
      const std::string v = o.value_or(std::string());
      p.outputs.errors = p.outputs.errors || v == "errors";
      p.outputs.nmea = p.outputs.nmea || v == "nmea";
      p.outputs.ubx = p.outputs.ubx || v == "ubx";
    }
  }
  const std::string tasks_path = (d / "tasks.csv").string();
  const CsvTable csv = parse_csv(read_file_bytes(tasks_path), tasks_path);
  const std::size_t n_hash = std::size(kHashColumns);
  if (csv.header.size() < 1 + n_hash || csv.header.front() != "task_id") throw Error(tasks_path, 1, "not a tasks.csv header");
  p.axis_keys.assign(csv.header.begin() + 1, csv.header.end() - static_cast<long>(n_hash));
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const std::vector<std::string>& row = csv.rows[r];
    Task task;
    task.id = static_cast<int>(r);
    if (row.front() != std::to_string(r)) throw Error(tasks_path, static_cast<int>(r) + 2, "task ids must run 0, 1, 2, ...");
    task.values.assign(row.begin() + 1, row.end() - static_cast<long>(n_hash));
    const std::size_t h = row.size() - n_hash;
    task.config_hash = row[h];
    task.nav_hash = row[h + 1];
    task.truth_hash = row[h + 2];
    task.scenario_hash = row[h + 3];
    p.tasks.push_back(std::move(task));
  }
  p.hash = plan_hash(p);
  const std::string written = t["plan_hash"].value_or(std::string());
  if (written != p.hash) {
    throw Error(plan_path, 0, fmt::format("plan_hash {} does not match tasks.csv and plan.toml ({}): edited by hand?",
                                          written, p.hash));
  }
  return p;
}

}  // namespace gnssemu::cli::sweep

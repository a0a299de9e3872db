// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/run/sweep_task.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/scenario_file.hpp"
#include "config/setup/nav_setup.hpp"
#include "core/common/error.hpp"
#include "core/orbit/constellation.hpp"
#include "tools/gnssemu/batch/truth_csv.hpp"
#include "tools/gnssemu/sweep/plan/input_hash.hpp"
#include "tools/gnssemu/sweep/plan/truth_generator.hpp"

namespace gnssemu::cli::sweep {

namespace {

namespace fs = std::filesystem;

void check_hash(const std::string& path, const std::string& want, const char* what) {
  const std::string got = file_hash(path);
  if (got != want) {
    throw Error(path, 0, fmt::format("{} changed since the plan (hash {}, planned {}): plan again", what, got, want));
  }
}

/// Where the task reads its truth: the file itself, or its own truth.csv.
std::string truth_path(const Plan& plan, const std::string& dir, const Task& task) {
  const std::string& truth = plan.value(task, "truth");
  if (is_generator_text(truth) || !plan.value(task, "start_h").empty()) {
    return (fs::path(task_dir(dir, task.id)) / "truth.csv").string();
  }
  return truth;
}

/// A path as one shell word.
std::string shell_word(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./-+=:,@%") ==
                        std::string::npos) {
    return s;
  }
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string task_dir(const std::string& dir, int id) { return (fs::path(dir) / "tasks" / std::to_string(id)).string(); }

void mark_failed(const std::string& dir, int id, const std::string& why) noexcept {
  try {
    write_file_atomic((fs::path(task_dir(dir, id)) / kFailedFile).string(), why + '\n');
  } catch (...) {
  }
}

TaskSummary run_task(const Plan& plan, const std::string& dir, int id, std::ostream& log) {
  if (id < 0 || id >= static_cast<int>(plan.tasks.size())) {
    throw Error(fmt::format("task {}: the plan has tasks 0 to {}", id, static_cast<int>(plan.tasks.size()) - 1));
  }
  const Task& task = plan.tasks[static_cast<std::size_t>(id)];
  const fs::path out(task_dir(dir, id));
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw Error(out.string(), 0, "cannot create the task folder: " + ec.message());
  // Not done until the new summary is in place.
  fs::remove(out / kSummaryFile, ec);
  fs::remove(out / kFailedFile, ec);

  check_hash(plan.config_path, task.config_hash, "config file");
  const std::string& truth = plan.value(task, "truth");
  if (!is_generator_text(truth)) check_hash(truth, task.truth_hash, "truth file");
  const std::string& scenario = plan.value(task, "scenario");
  const bool faults = !scenario.empty() && scenario != kNoScenario;
  if (faults) check_hash(scenario, task.scenario_hash, "scenario file");

  // The config as the reproduce command loads it: every key explicit.
  const config::Config planned = config_with_overrides(plan.config_path, plan.overrides(task));
  std::string nav_all;
  for (const std::string& p : config::nav_paths(planned)) nav_all += file_hash(p);
  if (hex64(fnv1a64(nav_all)) != task.nav_hash) {
    throw Error(plan.config_path, 0, "nav files changed since the plan: plan again");
  }
  const std::string config_path = (out / "config.toml").string();
  const std::string config_text = config::to_toml(planned);
  write_file_atomic(config_path, config_text);
  const config::Config cfg = config::parse_config(config_text, config_path, out.string());

  const std::string tpath = truth_path(plan, dir, task);
  if (tpath != truth) {
    std::vector<world::TruthSample> samples =
        is_generator_text(truth) ? generate_truth(parse_generator(truth, "tasks.csv", id + 2)) : read_truth_csv(truth);
    if (const std::string& h = plan.value(task, "start_h"); !h.empty()) shift_to_hour(samples, std::stod(h));
    write_file_atomic(tpath, truth_csv_text(samples));
  }
  const world::TruthTrack track(read_truth_csv(tpath));
  std::vector<faults::FaultEvent> events;
  if (faults) events = config::read_scenario(scenario);
  const orbit::Constellation c = config::make_constellation(cfg, config::load_nav(cfg), track.first());
  log << "task " << id << ": satellites: " << c.describe() << '\n';

  std::ostringstream errors, nmea, ubx;
  SummaryObserver summary(events, plan.hacc_k);
  BatchObserver* observers[] = {&summary};
  const BatchSummary sum = run_batch(cfg, c.nav, track, plan.outputs.nmea ? &nmea : nullptr,
                                     plan.outputs.errors ? &errors : nullptr, plan.outputs.ubx ? &ubx : nullptr,
                                     c.store_options(), observers, faults ? &events : nullptr);
  write_summary(sum, log);
  if (plan.outputs.errors) write_file_atomic((out / "errors.csv").string(), errors.str());
  if (plan.outputs.nmea) write_file_atomic((out / "out.nmea").string(), nmea.str());
  if (plan.outputs.ubx) write_file_atomic((out / "out.ubx").string(), ubx.str());
  const TaskSummary s = summary.summary();
  write_file_atomic((out / kSummaryFile).string(), summary_csv_text(s, id, plan.hash));
  return s;
}

std::string reproduce_command(const Plan& plan, const std::string& dir, const Task& task) {
  const std::string abs_dir = fs::absolute(dir).lexically_normal().string();
  std::string cmd = fmt::format("gnssemu batch --config {} --truth {}",
                                shell_word((fs::path(task_dir(abs_dir, task.id)) / "config.toml").string()),
                                shell_word(truth_path(plan, abs_dir, task)));
  const std::string& scenario = plan.value(task, "scenario");
  if (!scenario.empty() && scenario != kNoScenario) cmd += " --scenario " + shell_word(scenario);
  return cmd + " --errors errors.csv";
}

}  // namespace gnssemu::cli::sweep

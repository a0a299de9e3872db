// SPDX-License-Identifier: Apache-2.0
#pragma once
// The plan: a sweep file expanded into tasks, each with a stable id (its
// row in DIR/tasks.csv, also the Slurm array index), its axis values and the
// hash of every input it reads. DIR/plan.toml records the rest (base config,
// outputs, k) and the plan's own hash, which each task's result carries.
#include <string>
#include <vector>

#include "tools/gnssemu/sweep/plan/config_override.hpp"
#include "tools/gnssemu/sweep/plan/sweep_file.hpp"

namespace gnssemu::cli::sweep {

struct Task {
  int id = 0;                       ///< 0..N-1, the row of tasks.csv
  std::vector<std::string> values;  ///< per Plan::axis_keys; "" = axis not set for this task
  std::string config_hash, nav_hash, truth_hash, scenario_hash;  ///< hex64 of the files' bytes ("" none)
};

struct Plan {
  std::string sweep_path;   ///< the sweep file, absolute
  std::string config_path;  ///< base config, absolute
  TaskOutputs outputs;
  double hacc_k = 3.0;
  std::vector<std::string> axis_keys;  ///< [axes] keys, then keys only cases name, in file order
  std::vector<Task> tasks;
  std::string hash;         ///< hex64 of tasks.csv and plan.toml's settings

  /// Value of key for task ("" when the axis is absent).
  const std::string& value(const Task& task, const std::string& key) const;
  /// The task's config overrides: dotted axes, and seed as receiver.seed.
  std::vector<Override> overrides(const Task& task) const;
};

/// Expand spec: [axes] as a product (first axis slowest), or each [[case]]
/// as the product of [axes] with the case's keys replacing them. Applies
/// every distinct override set (an override the config reader rejects is an
/// error at its sweep-file line) and hashes every input. Throws
/// gnssemu::Error(sweep file, line, ...) for a task without truth and for a
/// task that repeats another's values (duplicate task id).
Plan make_plan(const SweepSpec& spec);

/// Text of DIR/tasks.csv: task_id, the axis keys, config_hash, nav_hash, truth_hash, scenario_hash.
std::string tasks_csv_text(const Plan& plan);

/// Write DIR/tasks.csv and DIR/plan.toml (DIR created). Throws
/// gnssemu::Error when DIR already holds a different plan: its tasks' results
/// would belong to other inputs.
void write_plan(const Plan& plan, const std::string& dir);

/// Read DIR/plan.toml and DIR/tasks.csv back; checks the plan hash. Throws
/// gnssemu::Error naming the file.
Plan read_plan(const std::string& dir);

}  // namespace gnssemu::cli::sweep

// SPDX-License-Identifier: Apache-2.0
#pragma once
// What became of each task: done (its summary.csv of this plan is in
// place), failed (a failed marker, or Slurm's own state), pending or running
// (Slurm), or missing (never run, or lost).
#include <map>
#include <string>
#include <vector>

#include "tools/gnssemu/sweep/plan/sweep_plan.hpp"

namespace gnssemu::cli::sweep {

enum class TaskState { kMissing, kPending, kRunning, kDone, kFailed };

/// "missing", "pending", "running", "done", "failed".
const char* state_name(TaskState s) noexcept;

struct TaskStatus {
  TaskState state = TaskState::kMissing;
  std::string detail;  ///< failed: exit status / scheduler state and the last lines of the log
};

/// Scheduler states by task id (from slurm_status), consulted for tasks
/// without a result.
using SchedulerStates = std::map<int, TaskStatus>;

/// Every task's state from its folder, then from sched. Throws
/// gnssemu::Error when a task's summary belongs to a different plan.
std::vector<TaskStatus> task_states(const Plan& plan, const std::string& dir, const SchedulerStates& sched = {});

/// The last n lines of a task's log ("" when there is none).
std::string log_tail(const std::string& dir, int id, int n = 5);

/// "tasks N: done a, failed b, running c, pending d, missing e".
std::string state_counts(const std::vector<TaskStatus>& states);

}  // namespace gnssemu::cli::sweep

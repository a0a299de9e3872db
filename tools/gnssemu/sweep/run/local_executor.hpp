// SPDX-License-Identifier: Apache-2.0
#pragma once
// The local executor: up to N tasks at a time, each in a forked child of
// this process (a crash or abort takes down one task, not the sweep, and
// its memory goes back when it exits), stdout/stderr to the task's log.
#include <ostream>
#include <vector>

#include "tools/gnssemu/sweep/plan/sweep_plan.hpp"

namespace gnssemu::cli::sweep {

struct LocalRunOptions {
  int jobs = 0;              ///< tasks at a time; 0: every core (hardware_concurrency)
  double task_timeout_s = 0; ///< a task running longer is killed and failed; 0: no limit
  bool progress_bar = false; ///< redraw one line (a terminal); else a line per minute
};

struct LocalRunResult {
  int done = 0, failed = 0;
  double wall_s = 0.0;
};

/// Run the given task ids of plan in dir. A failed task (non-zero exit, a
/// signal, the timeout) gets a failed marker and a line on err with its id,
/// exit status and the tail of its log; the others carry on.
LocalRunResult run_local(const Plan& plan, const std::string& dir, const std::vector<int>& ids,
                         const LocalRunOptions& options, std::ostream& err);

}  // namespace gnssemu::cli::sweep

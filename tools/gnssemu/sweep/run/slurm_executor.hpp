// SPDX-License-Identifier: Apache-2.0
#pragma once
// The Slurm executor: one sbatch array script per submission (array index =
// task id, each element runs `gnssemu sweep task DIR $SLURM_ARRAY_TASK_ID`,
// its log in DIR/tasks/%a/task.log), job ids recorded in DIR/slurm/jobs.csv,
// and each task's state read back from Slurm (`scontrol -o show job`), not
// from files the tasks might not have written.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "tools/gnssemu/sweep/plan/sweep_plan.hpp"
#include "tools/gnssemu/sweep/run/task_state.hpp"

namespace gnssemu::cli::sweep {

struct SlurmOptions {
  int array_limit = 0;    ///< --array-limit: tasks running at once (%K); 0: no limit
  std::string partition;  ///< --partition; "": the cluster's default
  std::string time;       ///< --time (Slurm's forms: "10", "1:00:00", "1-0"); "": the partition's limit
  std::string gnssemu;    ///< the gnssemu binary every node runs, absolute
  int per_element = 1;    ///< consecutive tasks per array element (>= 1)
};

/// The directory of program on PATH, or nullopt (no Slurm here).
std::optional<std::string> find_program(const std::string& program);

/// Slurm's array spec of ids: ranges "0-39", lists "3,7,10-12"; "%K" appended for a limit.
std::string array_spec(const std::vector<int>& ids, int limit);

/// The sbatch script for ids (absolute dir). With per_element > 1 the
/// array runs over elements and ids_file lists each element's task ids (a line each).
std::string sbatch_script(const std::string& dir, const std::vector<int>& ids, const SlurmOptions& options,
                          const std::string& ids_file = {});

/// Write DIR/slurm/array-<n>.sh, submit it with sbatch --parsable and record
/// the job id in DIR/slurm/jobs.csv. Returns the job id. Throws
/// gnssemu::Error with sbatch's own message when it refuses.
std::string submit_array(const std::string& dir, const std::vector<int>& ids, const SlurmOptions& options,
                         std::ostream& err);

/// Every recorded job's tasks as Slurm reports them now (the newest
/// submission of a task wins). Tasks of jobs Slurm no longer knows are left out.
SchedulerStates slurm_states(const std::string& dir);

/// Parse `scontrol -o show job` lines into states by array task id (the
/// array element when elements run several tasks).
SchedulerStates parse_scontrol(const std::string& text);

/// Wait until none of the recorded jobs is pending or running (squeue),
/// polling every poll_s; prints a line when the counts change.
void wait_for_jobs(const std::string& dir, double poll_s, std::ostream& err);

/// Run a command, return its stdout; exit status in *status.
std::string capture(const std::vector<std::string>& argv, int* status);

}  // namespace gnssemu::cli::sweep

// SPDX-License-Identifier: Apache-2.0
#pragma once
// One task of a plan: one `gnssemu batch` run, in this process, from the
// task's row of tasks.csv. Both executors run it (`gnssemu sweep task DIR ID`
// on Slurm, a forked child locally), so its files are the same bytes
// wherever it runs.
#include <ostream>
#include <string>

#include "tools/gnssemu/sweep/collect/task_summary.hpp"
#include "tools/gnssemu/sweep/plan/sweep_plan.hpp"

namespace gnssemu::cli::sweep {

/// DIR/tasks/<id>.
std::string task_dir(const std::string& dir, int id);

/// Result file names inside a task's folder.
inline constexpr const char* kSummaryFile = "summary.csv";  ///< written last: its presence means done
inline constexpr const char* kFailedFile = "failed";        ///< why the task failed (exit status, error)
inline constexpr const char* kLogFile = "task.log";         ///< stderr of the task (not compared)

/// Run task id: verify its inputs' hashes, write DIR/tasks/<id>/config.toml
/// (the base with the overrides, every key explicit), truth.csv when the
/// truth is generated or shifted, the plan's outputs (errors.csv, out.nmea,
/// out.ubx) and summary.csv, each atomically. Messages go to log. Throws
/// gnssemu::Error (inputs changed since the plan, bad input); the summary is
/// then absent.
TaskSummary run_task(const Plan& plan, const std::string& dir, int id, std::ostream& log);

/// `gnssemu batch ...` that writes the task's errors.csv again from its
/// config.toml, truth and scenario (dir made absolute).
std::string reproduce_command(const Plan& plan, const std::string& dir, const Task& task);

/// Record why a task failed in its folder (kFailedFile), best effort.
void mark_failed(const std::string& dir, int id, const std::string& why) noexcept;

}  // namespace gnssemu::cli::sweep

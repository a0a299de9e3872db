// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/sweep_cli.hpp"

#include <unistd.h>

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/common/error.hpp"
#include "tools/gnssemu/sweep/collect/csv_row.hpp"
#include "tools/gnssemu/sweep/collect/sweep_collect.hpp"
#include "tools/gnssemu/sweep/plan/sweep_file.hpp"
#include "tools/gnssemu/sweep/plan/sweep_plan.hpp"
#include "tools/gnssemu/sweep/run/sweep_task.hpp"
#include "tools/gnssemu/sweep/run/task_state.hpp"

namespace gnssemu::cli::sweep {

namespace {

namespace fs = std::filesystem;

constexpr int kExitTaskFailed = 1;
constexpr int kExitNoSlurm = 2;

std::string duration_text(double s) {
  if (s < 120.0) return fmt::format("{:.1f} s", s);
  if (s < 7200.0) return fmt::format("{:.1f} min", s / 60.0);
  return fmt::format("{:.1f} h", s / 3600.0);
}

/// This program, for Slurm's nodes (a shared path on a real cluster).
std::string self_exe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("sweep: cannot find this program's path (/proc/self/exe); give --gnssemu PATH");
  return p.string();
}

}  // namespace

SweepCommand::SweepCommand(CLI::App& app) {
  sweep_ = app.add_subcommand("sweep", "campaigns: many batch runs over scenarios, seeds, times, truths (docs/sweep.md)");
  sweep_->require_subcommand(1);
  plan_ = sweep_->add_subcommand("plan", "expand a sweep file into DIR/tasks.csv and estimate the CPU time");
  plan_->add_option("file", file_, "sweep file (TOML)")->required();
  plan_->add_option("--out", dir_, "sweep folder (tasks.csv, plan.toml, tasks/<id>/)")->required();
  plan_->add_flag("!--no-calibrate", calibrate_, "skip the calibration run of task 0");
  run_ = sweep_->add_subcommand("run", "run the tasks of a planned sweep folder");
  run_->add_option("dir", dir_, "sweep folder")->required();
  run_->add_option("--executor", executor_, "local (this machine) or slurm (an sbatch array)")
      ->check(CLI::IsMember({"local", "slurm"}))
      ->capture_default_str();
  run_->add_flag("--resume", resume_, "run only missing and failed tasks");
  run_->add_option("--jobs", local_.jobs, "local: tasks at a time (default: every core)")->check(CLI::Range(1, 4096));
  run_->add_option("--task-timeout", local_.task_timeout_s, "local: kill and fail a task after this many seconds")
      ->check(CLI::Range(0.0, 1e7));
  run_->add_option("--array-limit", slurm_.array_limit, "slurm: tasks running at once (--array=...%K)")
      ->check(CLI::Range(1, 1000000));
  run_->add_option("--partition", slurm_.partition, "slurm: partition");
  run_->add_option("--time", slurm_.time, "slurm: time limit per task (Slurm's forms: MM, HH:MM:SS, D-HH)");
  run_->add_option("--gnssemu", slurm_.gnssemu, "slurm: the gnssemu binary every node runs (default: this one)");
  run_->add_option("--tasks-per-element", slurm_.per_element,
                   "slurm: consecutive tasks each array element runs (amortises Slurm's launch cost on short tasks)")
      ->check(CLI::Range(1, 100000));
  run_->add_flag("--wait", wait_, "slurm: return when no task is pending or running");
  status_ = sweep_->add_subcommand("status", "pending/running/done/failed per task (Slurm's own job state)");
  status_->add_option("dir", dir_, "sweep folder")->required();
  status_->add_flag("--list", list_, "print task_id,state,detail for every task on stdout");
  collect_ = sweep_->add_subcommand("collect", "DIR/results.csv and DIR/report.html from the tasks' summaries");
  collect_->add_option("dir", dir_, "sweep folder")->required();
  task_ = sweep_->add_subcommand("task", "run one task of DIR (what each executor runs)");
  task_->add_option("dir", dir_, "sweep folder")->required();
  task_->add_option("id", task_ids_, "task ids (rows of tasks.csv); several: each logs to its own task.log")
      ->required();
}

int SweepCommand::run(std::ostream& out, std::ostream& err) {
  if (plan_->parsed()) return plan(out, err);
  if (run_->parsed()) return run_tasks(out, err);
  if (status_->parsed()) return status(out, err);
  if (task_->parsed()) return task(err);
  const CollectResult r = collect(dir_, err);
  if (r.worst_task >= 0) {
    out << fmt::format("worst: task {}, h_max_fix_m {}\nreproduce: {}\n", r.worst_task, r.worst_value, r.worst_command);
  }
  return 0;
}

int SweepCommand::plan(std::ostream& out, std::ostream& err) {
  const SweepSpec spec = read_sweep_file(file_);
  const Plan p = make_plan(spec);
  write_plan(p, dir_);
  out << fmt::format("tasks: {}\nplan: {}\n", p.tasks.size(), p.hash);
  if (calibrate_ && !p.tasks.empty()) {
    // Task 0 for real: its result counts, its time estimates the rest.
    std::ostringstream log;
    const auto t0 = std::chrono::steady_clock::now();
    run_task(p, dir_, 0, log);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out << fmt::format("calibration: task 0 took {:.3f} s\nestimated CPU time: {} ({} tasks)\n", s,
                       duration_text(s * static_cast<double>(p.tasks.size())), p.tasks.size());
  }
  err << "gnssemu sweep plan: wrote " << (fs::path(dir_) / "tasks.csv").string() << '\n';
  return 0;
}

int SweepCommand::run_tasks(std::ostream& out, std::ostream& err) {
  const bool slurm = executor_ == "slurm";
  if (slurm && !find_program("sbatch")) {
    err << "gnssemu sweep run: --executor slurm: no Slurm on this machine (sbatch is not on PATH); "
           "use --executor local, or start one with tools/slurm-local.sh start\n";
    return kExitNoSlurm;
  }
  const Plan p = read_plan(dir_);
  std::vector<int> ids;
  if (resume_) {
    const std::vector<TaskStatus> states = task_states(p, dir_, slurm ? slurm_states(dir_) : SchedulerStates{});
    for (const Task& t : p.tasks) {
      const TaskState s = states[static_cast<std::size_t>(t.id)].state;
      if (s == TaskState::kFailed || s == TaskState::kMissing) ids.push_back(t.id);
    }
  } else {
    for (const Task& t : p.tasks) ids.push_back(t.id);
  }
  if (ids.empty()) {
    out << "sweep: nothing to run (every task done, pending or running)\n";
    return 0;
  }
  if (!slurm) {
    local_.progress_bar = ::isatty(STDERR_FILENO) != 0;
    const LocalRunResult r = run_local(p, dir_, ids, local_, err);
    out << fmt::format("sweep: {} done, {} failed in {:.2f} s\n", r.done, r.failed, r.wall_s);
    return r.failed > 0 ? kExitTaskFailed : 0;
  }
  SlurmOptions o = slurm_;
  if (o.gnssemu.empty()) o.gnssemu = self_exe();
  const std::string abs_dir = fs::absolute(dir_).lexically_normal().string();
  for (const int id : ids) {
    std::error_code ec;
    fs::create_directories(task_dir(abs_dir, id), ec);
    fs::remove(fs::path(task_dir(abs_dir, id)) / kFailedFile, ec);
  }
  const std::string job = submit_array(abs_dir, ids, o, err);
  out << "job: " << job << '\n';
  if (!wait_) return 0;
  wait_for_jobs(abs_dir, poll_s_, err);
  const std::vector<TaskStatus> states = task_states(p, dir_, slurm_states(abs_dir));
  out << state_counts(states) << '\n';
  for (const int id : ids) {
    if (states[static_cast<std::size_t>(id)].state != TaskState::kDone) return kExitTaskFailed;
  }
  return 0;
}

int SweepCommand::status(std::ostream& out, std::ostream& err) {
  const Plan p = read_plan(dir_);
  SchedulerStates sched;
  if (find_program("scontrol")) sched = slurm_states(dir_);
  const std::vector<TaskStatus> states = task_states(p, dir_, sched);
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (states[i].state == TaskState::kFailed) err << fmt::format("failed: task {}: {}\n", i, states[i].detail);
  }
  if (list_) {
    out << "task_id,state,detail\n";
    for (std::size_t i = 0; i < states.size(); ++i) {
      out << csv_row({std::to_string(i), state_name(states[i].state), states[i].detail});
    }
  } else {
    out << state_counts(states) << '\n';
  }
  return 0;
}

int SweepCommand::task(std::ostream& err) {
  const Plan p = read_plan(dir_);
  int status = 0;
  for (const int id : task_ids_) {
    // One id: the log is stderr (Slurm's --output). Several: each its own.
    std::ofstream own;
    if (task_ids_.size() > 1) {
      std::error_code ec;
      fs::create_directories(task_dir(dir_, id), ec);
      own.open(fs::path(task_dir(dir_, id)) / kLogFile, std::ios::trunc);
    }
    std::ostream& log = task_ids_.size() > 1 ? static_cast<std::ostream&>(own) : err;
    try {
      run_task(p, dir_, id, log);
    } catch (const Error& e) {
      mark_failed(dir_, id, fmt::format("exit status {}: {}", kExitTaskFailed, e.what()));
      if (task_ids_.size() == 1) throw;
      log << "gnssemu: " << e.what() << '\n';
      err << fmt::format("gnssemu sweep task {}: {}\n", id, e.what());
      status = kExitTaskFailed;
    }
  }
  return status;
}

}  // namespace gnssemu::cli::sweep

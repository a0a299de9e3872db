// SPDX-License-Identifier: Apache-2.0
#pragma once
// The `gnssemu sweep` command line (docs/sweep.md): plan, run, status,
// collect, and task (what each executor runs for one task).
#include <CLI/CLI.hpp>

#include <ostream>
#include <string>
#include <vector>

#include "tools/gnssemu/sweep/run/local_executor.hpp"
#include "tools/gnssemu/sweep/run/slurm_executor.hpp"

namespace gnssemu::cli::sweep {

class SweepCommand {
public:
  /// Adds "sweep" and its subcommands to app.
  explicit SweepCommand(CLI::App& app);
  SweepCommand(const SweepCommand&) = delete;
  SweepCommand& operator=(const SweepCommand&) = delete;

  /// The CLI11 subcommand ("sweep").
  CLI::App* app() const noexcept { return sweep_; }
  /// True when the command line chose sweep.
  bool parsed() const { return sweep_->parsed(); }
  /// Run the chosen subcommand. Throws gnssemu::Error for bad input; returns
  /// the exit status otherwise (1 when a task failed, 2 without Slurm).
  int run(std::ostream& out, std::ostream& err);

private:
  int plan(std::ostream& out, std::ostream& err);
  int run_tasks(std::ostream& out, std::ostream& err);
  int status(std::ostream& out, std::ostream& err);
  int task(std::ostream& err);

  CLI::App* sweep_ = nullptr;
  CLI::App *plan_ = nullptr, *run_ = nullptr, *status_ = nullptr, *collect_ = nullptr, *task_ = nullptr;
  std::string file_, dir_, executor_ = "local";
  bool resume_ = false, wait_ = false, list_ = false, calibrate_ = true;
  std::vector<int> task_ids_;
  LocalRunOptions local_;
  SlurmOptions slurm_;
  double poll_s_ = 1.0;
};

}  // namespace gnssemu::cli::sweep

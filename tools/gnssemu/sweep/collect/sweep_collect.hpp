// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu sweep collect DIR`: every task's summary beside its axis values
// in DIR/results.csv (one row per task, in task order), and DIR/report.html:
// each metric against each axis, and the worst cases with the command that
// reproduces each. Same results, same bytes.
#include <ostream>
#include <string>

namespace gnssemu::cli::sweep {

struct CollectResult {
  int tasks = 0, done = 0;
  int worst_task = -1;          ///< the task with the largest h_max_fix_m (-1: none)
  std::string worst_value;      ///< its h_max_fix_m
  std::string worst_command;    ///< its reproduce command
};

/// How many worst cases the report lists.
inline constexpr int kWorstCases = 10;

/// Write DIR/results.csv and DIR/report.html. Tasks without a result are
/// rows with their state and empty metrics. Throws gnssemu::Error.
CollectResult collect(const std::string& dir, std::ostream& err);

}  // namespace gnssemu::cli::sweep

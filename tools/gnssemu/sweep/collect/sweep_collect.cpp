// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/collect/sweep_collect.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <numeric>

#include "core/common/error.hpp"
#include "daemon/status/json_writer.hpp"
#include "tools/gnssemu/report/report.hpp"
#include "tools/gnssemu/sweep/collect/csv_row.hpp"
#include "tools/gnssemu/sweep/collect/task_summary.hpp"
#include "tools/gnssemu/sweep/plan/input_hash.hpp"
#include "tools/gnssemu/sweep/plan/sweep_plan.hpp"
#include "tools/gnssemu/sweep/plan/truth_generator.hpp"
#include "tools/gnssemu/sweep/run/sweep_task.hpp"
#include "tools/gnssemu/sweep/run/task_state.hpp"

namespace gnssemu::cli::sweep {

namespace {

namespace fs = std::filesystem;

/// Metrics the report plots against each axis.
const std::vector<std::string> kPlotted{"h95_m",  "h_max_fix_m",   "v95_m",        "avail_3d",     "h_over_k_hacc",
                                        "refix_s", "spoof_detect_s", "jam_detect_s", "raim_detect_s"};

/// A short label for a file axis value: the file name.
std::string label(const std::string& key, const std::string& v) {
  if (key == "truth" && is_generator_text(v)) return parse_generator(v, "tasks.csv", 0).name;
  if ((key == "truth" || key == "scenario") && v.find('/') != std::string::npos && v.front() != '{') {
    return fs::path(v).filename().string();
  }
  return v;
}

}  // namespace

CollectResult collect(const std::string& dir, std::ostream& err) {
  const Plan plan = read_plan(dir);
  const std::vector<TaskStatus> states = task_states(plan, dir);
  std::vector<std::string> head{"task_id"};
  head.insert(head.end(), plan.axis_keys.begin(), plan.axis_keys.end());
  head.push_back("state");
  head.insert(head.end(), summary_columns().begin(), summary_columns().end());
  head.push_back("reproduce");
  std::vector<std::vector<std::string>> rows;
  CollectResult r;
  r.tasks = static_cast<int>(plan.tasks.size());
  for (const Task& t : plan.tasks) {
    std::vector<std::string> row{std::to_string(t.id)};
    row.insert(row.end(), t.values.begin(), t.values.end());
    const TaskStatus& s = states[static_cast<std::size_t>(t.id)];
    row.push_back(state_name(s.state));
    if (s.state == TaskState::kDone) {
      ++r.done;
      const std::string path = (fs::path(task_dir(dir, t.id)) / kSummaryFile).string();
      const CsvTable sum = parse_csv(read_file_bytes(path), path);
      if (sum.rows.size() != 1) throw Error(path, 0, "expected one summary row");
      for (const std::string& c : summary_columns()) {
        const int k = sum.column(c);
        if (k < 0) throw Error(path, 1, "no column " + c);
        row.push_back(sum.rows[0][static_cast<std::size_t>(k)]);
      }
    } else {
      row.insert(row.end(), summary_columns().size(), "");
    }
    row.push_back(reproduce_command(plan, dir, t));
    rows.push_back(std::move(row));
  }
  std::string csv = csv_row(head);
  for (const auto& row : rows) csv += csv_row(row);
  write_file_atomic((fs::path(dir) / "results.csv").string(), csv);

  // Worst: largest error while a fix was reported; ties by task id.
  const auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(head.begin(), head.end(), name) - head.begin());
  };
  const std::size_t hmax = col("h_max_fix_m");
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i][hmax].empty()) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return std::stod(rows[a][hmax]) > std::stod(rows[b][hmax]); });
  if (order.size() > static_cast<std::size_t>(kWorstCases)) order.resize(kWorstCases);
  if (!order.empty()) {
    r.worst_task = static_cast<int>(order.front());
    r.worst_value = rows[order.front()][hmax];
    r.worst_command = rows[order.front()].back();
  }

  std::string json;
  daemon::JsonWriter w(json);
  w.begin_object();
  w.field_string("title", "gnssemu sweep: " + fs::path(plan.sweep_path).filename().string());
  w.key("inputs");
  w.begin_array();
  w.string("sweep: " + plan.sweep_path);
  w.string("base config: " + plan.config_path);
  w.string(fmt::format("plan {}: {} tasks; {}", plan.hash, plan.tasks.size(), state_counts(states)));
  w.end_array();
  w.key("axes");
  w.begin_array();
  for (const std::string& k : plan.axis_keys) w.string(k);
  w.end_array();
  w.key("metrics");
  w.begin_array();
  for (const std::string& m : kPlotted) w.string(m);
  w.end_array();
  w.key("columns");
  w.begin_array();
  for (const std::string& h : head) w.string(h);
  w.end_array();
  w.key("rows");
  w.begin_array();
  for (const auto& row : rows) {
    w.begin_array();
    for (std::size_t i = 0; i < row.size(); ++i) {
      const bool axis = i >= 1 && i <= plan.axis_keys.size();
      w.string(axis ? label(plan.axis_keys[i - 1], row[i]) : row[i]);
    }
    w.end_array();
  }
  w.end_array();
  w.key("worst");
  w.begin_array();
  for (const std::size_t i : order) w.number(static_cast<double>(i), 0);
  w.end_array();
  w.end_object();
  const std::string page = write_html_page(dir, "gnssemu sweep: " + fs::path(plan.sweep_path).filename().string(), json,
                                           "/sweep_report.js");
  err << fmt::format("sweep collect: {} of {} tasks done; {} and {}\n", r.done, r.tasks,
                     (fs::path(dir) / "results.csv").string(), page);
  return r;
}

}  // namespace gnssemu::cli::sweep

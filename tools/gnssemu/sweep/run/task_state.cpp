// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/run/task_state.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "core/common/error.hpp"
#include "tools/gnssemu/sweep/plan/input_hash.hpp"
#include "tools/gnssemu/sweep/run/sweep_task.hpp"

namespace gnssemu::cli::sweep {

namespace fs = std::filesystem;

const char* state_name(TaskState s) noexcept {
  switch (s) {
    case TaskState::kPending: return "pending";
    case TaskState::kRunning: return "running";
    case TaskState::kDone: return "done";
    case TaskState::kFailed: return "failed";
    case TaskState::kMissing: break;
  }
  return "missing";
}

std::string log_tail(const std::string& dir, int id, int n) {
  const fs::path p = fs::path(task_dir(dir, id)) / kLogFile;
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) return {};
  std::string text;
  try {
    text = read_file_bytes(p.string());
  } catch (const Error&) {
    return {};
  }
  while (!text.empty() && text.back() == '\n') text.pop_back();
  // Start of the n-th line from the end.
  std::size_t start = text.size();
  for (int i = 0; i < n && start > 0; ++i) {
    const std::size_t nl = text.rfind('\n', start - 1);
    start = nl == std::string::npos ? 0 : nl;
    if (nl == std::string::npos) break;
  }
  if (start < text.size() && text[start] == '\n') ++start;
  return text.substr(start);
}

std::vector<TaskStatus> task_states(const Plan& plan, const std::string& dir, const SchedulerStates& sched) {
  std::vector<TaskStatus> out(plan.tasks.size());
  const std::string mark = plan.hash + "," ;
  for (const Task& t : plan.tasks) {
    TaskStatus& s = out[static_cast<std::size_t>(t.id)];
    const fs::path folder(task_dir(dir, t.id));
    std::error_code ec;
    if (fs::is_regular_file(folder / kSummaryFile, ec)) {
      const std::string text = read_file_bytes((folder / kSummaryFile).string());
      const std::size_t row = text.find('\n');
      if (row == std::string::npos || text.compare(row + 1, mark.size(), mark) != 0) {
        throw Error((folder / kSummaryFile).string(), 2,
                    fmt::format("a result of a different plan (this plan is {}): remove {} or plan into a new folder",
                                plan.hash, folder.string()));
      }
      s.state = TaskState::kDone;
      continue;
    }
    if (const auto it = sched.find(t.id); it != sched.end()) s = it->second;
    if (s.state == TaskState::kMissing && fs::is_regular_file(folder / kFailedFile, ec)) {
      s.state = TaskState::kFailed;
      std::string why = read_file_bytes((folder / kFailedFile).string());
      while (!why.empty() && why.back() == '\n') why.pop_back();
      s.detail = why;
    }
    if (s.state == TaskState::kFailed) {
      const std::string tail = log_tail(dir, t.id);
      if (!tail.empty()) s.detail += (s.detail.empty() ? "" : "; ") + std::string("log: ") + tail;
    }
  }
  return out;
}

std::string state_counts(const std::vector<TaskStatus>& states) {
  int n[5] = {0, 0, 0, 0, 0};
  for (const TaskStatus& s : states) ++n[static_cast<int>(s.state)];
  return fmt::format("tasks {}: done {}, failed {}, running {}, pending {}, missing {}", states.size(),
                     n[static_cast<int>(TaskState::kDone)], n[static_cast<int>(TaskState::kFailed)],
                     n[static_cast<int>(TaskState::kRunning)], n[static_cast<int>(TaskState::kPending)],
                     n[static_cast<int>(TaskState::kMissing)]);
}

}  // namespace gnssemu::cli::sweep

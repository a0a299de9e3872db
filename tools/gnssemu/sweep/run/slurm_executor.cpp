// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/run/slurm_executor.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <thread>

#include "core/common/error.hpp"
#include "tools/gnssemu/sweep/collect/csv_row.hpp"
#include "tools/gnssemu/sweep/plan/input_hash.hpp"

namespace gnssemu::cli::sweep {

namespace {

namespace fs = std::filesystem;

std::string jobs_csv(const std::string& dir) { return (fs::path(dir) / "slurm" / "jobs.csv").string(); }

struct Job {
  std::string id;
  std::string ids_file;  ///< "" when array index = task id
};

/// Jobs recorded for dir, oldest first.
std::vector<Job> recorded_job_list(const std::string& dir) {
  std::vector<Job> out;
  std::error_code ec;
  if (!fs::is_regular_file(jobs_csv(dir), ec)) return out;
  const CsvTable t = parse_csv(read_file_bytes(jobs_csv(dir)), jobs_csv(dir));
  const int col = t.column("job_id"), ids = t.column("ids_file");
  for (const auto& row : t.rows) {
    out.push_back({row[static_cast<std::size_t>(col)], ids < 0 ? std::string() : row[static_cast<std::size_t>(ids)]});
  }
  return out;
}

std::vector<std::string> recorded_jobs(const std::string& dir) {
  std::vector<std::string> out;
  for (const Job& j : recorded_job_list(dir)) out.push_back(j.id);
  return out;
}

/// Task ids per array element, from an ids file.
std::vector<std::vector<int>> element_ids(const std::string& ids_file) {
  std::vector<std::vector<int>> out;
  std::stringstream ss(read_file_bytes(ids_file));
  std::string line;
  while (std::getline(ss, line)) {
    std::stringstream ls(line);
    out.emplace_back();
    for (int id = 0; ls >> id;) out.back().push_back(id);
  }
  return out;
}

std::string field(const std::string& line, const std::string& key) {
  const std::string k = " " + key + "=";
  std::size_t at = line.find(k);
  if (at == std::string::npos) {
    if (line.rfind(key + "=", 0) != 0) return {};
    at = 0;
  } else {
    at += 1;
  }
  at += key.size() + 1;
  const std::size_t end = line.find(' ', at);
  return line.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

/// "3", "2-9", "2-9%2", "1,3,5-7", "0-10:2" -> ids.
std::vector<int> expand_ids(std::string spec) {
  std::vector<int> out;
  if (const std::size_t pct = spec.find('%'); pct != std::string::npos) spec.resize(pct);
  std::stringstream ss(spec);
  std::string part;
  while (std::getline(ss, part, ',')) {
    int step = 1;
    if (const std::size_t c = part.find(':'); c != std::string::npos) {
      step = std::max(1, std::atoi(part.c_str() + c + 1));
      part.resize(c);
    }
    const std::size_t dash = part.find('-');
    const int a = std::atoi(part.c_str());
    const int b = dash == std::string::npos ? a : std::atoi(part.c_str() + dash + 1);
    for (int i = a; i <= b; i += step) out.push_back(i);
  }
  return out;
}

TaskStatus status_of(const std::string& job_state, const std::string& exit_code, const std::string& job_id) {
  TaskStatus s;
  if (job_state == "PENDING" || job_state == "REQUEUED" || job_state == "REQUEUE_HOLD" || job_state == "RESV_DEL_HOLD" ||
      job_state == "REQUEUE_FED") {
    s.state = TaskState::kPending;
  } else if (job_state == "RUNNING" || job_state == "COMPLETING" || job_state == "CONFIGURING" ||
             job_state == "SUSPENDED" || job_state == "STAGE_OUT" || job_state == "SIGNALING") {
    s.state = TaskState::kRunning;
  } else {
    // COMPLETED without a summary, FAILED, TIMEOUT, CANCELLED, NODE_FAIL, OUT_OF_MEMORY, ...
    s.state = TaskState::kFailed;
    s.detail = fmt::format("Slurm job {} {}, exit code {}", job_id, job_state, exit_code);
  }
  return s;
}

}  // namespace

std::optional<std::string> find_program(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::stringstream ss(path);
  std::string d;
  while (std::getline(ss, d, ':')) {
    if (d.empty()) continue;
    const fs::path p = fs::path(d) / program;
    if (::access(p.c_str(), X_OK) == 0) return d;
  }
  return std::nullopt;
}

std::string capture(const std::vector<std::string>& argv, int* status) {
  int fds[2];
  if (::pipe(fds) != 0) throw Error("sweep: pipe failed");
  const pid_t pid = ::fork();
  if (pid < 0) throw Error("sweep: fork failed");
  if (pid == 0) {
    ::dup2(fds[1], STDOUT_FILENO);
    ::dup2(fds[1], STDERR_FILENO);
    ::close(fds[0]);
    ::close(fds[1]);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execvp(args[0], args.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  std::string out;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n > 0) {
      out.append(buf, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(fds[0]);
  int ws = 0;
  while (::waitpid(pid, &ws, 0) < 0 && errno == EINTR) {
  }
  if (status != nullptr) *status = WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + WTERMSIG(ws);
  return out;
}

std::string array_spec(const std::vector<int>& ids, int limit) {
  std::string out;
  for (std::size_t i = 0; i < ids.size();) {
    std::size_t j = i;
    while (j + 1 < ids.size() && ids[j + 1] == ids[j] + 1) ++j;
    if (!out.empty()) out += ',';
    out += j == i ? std::to_string(ids[i]) : fmt::format("{}-{}", ids[i], ids[j]);
    i = j + 1;
  }
  if (limit > 0) out += fmt::format("%{}", limit);
  return out;
}

std::string sbatch_script(const std::string& dir, const std::vector<int>& ids, const SlurmOptions& o,
                          const std::string& ids_file) {
  const bool packed = !ids_file.empty();
  std::vector<int> elements;
  if (packed) {
    const int n = (static_cast<int>(ids.size()) + o.per_element - 1) / o.per_element;
    for (int e = 0; e < n; ++e) elements.push_back(e);
  }
  std::string s = "#!/bin/sh\n# gnssemu sweep: tasks of " + dir + "/tasks.csv (written by gnssemu sweep run)\n";
  s += "#SBATCH --job-name=gnssemu-sweep\n";
  s += "#SBATCH --array=" + array_spec(packed ? elements : ids, o.array_limit) + "\n";
  s += "#SBATCH --output=" + (packed ? ids_file.substr(0, ids_file.size() - 4) + "-%a.log" : dir + "/tasks/%a/task.log") + "\n";
  s += "#SBATCH --chdir=" + dir + "\n";
  s += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  if (!o.partition.empty()) s += "#SBATCH --partition=" + o.partition + "\n";
  if (!o.time.empty()) s += "#SBATCH --time=" + o.time + "\n";
  if (packed) {
    s += "# Element i runs the task ids on line i + 1 of " + ids_file + "\n";
    s += "exec " + o.gnssemu + " sweep task " + dir + " $(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" " + ids_file + ")\n";
  } else {
    s += "exec " + o.gnssemu + " sweep task " + dir + " \"$SLURM_ARRAY_TASK_ID\"\n";
  }
  return s;
}

std::string submit_array(const std::string& dir, const std::vector<int>& ids, const SlurmOptions& options,
                         std::ostream& err) {
  const fs::path sdir = fs::path(dir) / "slurm";
  std::error_code ec;
  fs::create_directories(sdir, ec);
  if (ec) throw Error(sdir.string(), 0, "cannot create: " + ec.message());
  const std::vector<std::string> jobs = recorded_jobs(dir);
  const std::string script = (sdir / fmt::format("array-{}.sh", jobs.size())).string();
  std::string ids_file;
  if (options.per_element > 1) {
    ids_file = (sdir / fmt::format("array-{}.ids", jobs.size())).string();
    std::string lines;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      lines += std::to_string(ids[i]);
      lines += (i + 1) % static_cast<std::size_t>(options.per_element) == 0 || i + 1 == ids.size() ? '\n' : ' ';
    }
    write_file_atomic(ids_file, lines);
  }
  write_file_atomic(script, sbatch_script(dir, ids, options, ids_file));
  int status = 0;
  std::string out = capture({"sbatch", "--parsable", script}, &status);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  if (status != 0) throw Error(script, 0, "sbatch refused it (exit status " + std::to_string(status) + "): " + out);
  // --parsable prints "jobid" or "jobid;cluster"; warnings may come first.
  std::string job = out.substr(out.rfind('\n') == std::string::npos ? 0 : out.rfind('\n') + 1);
  job = job.substr(0, job.find(';'));
  std::string csv = jobs.empty() ? std::string("job_id,array,script,ids_file\n") : read_file_bytes(jobs_csv(dir));
  csv += csv_row({job, array_spec(ids, options.array_limit), script, ids_file});
  write_file_atomic(jobs_csv(dir), csv);
  err << fmt::format("sweep: submitted {} task{} as Slurm job {} ({})\n", ids.size(), ids.size() == 1 ? "" : "s", job,
                     script);
  return job;
}

SchedulerStates parse_scontrol(const std::string& text) {
  SchedulerStates out;
  std::stringstream ss(text);
  std::string line;
  while (std::getline(ss, line)) {
    const std::string tasks = field(line, "ArrayTaskId");
    const std::string state = field(line, "JobState");
    if (tasks.empty() || state.empty()) continue;
    const TaskStatus s = status_of(state, field(line, "ExitCode"), field(line, "JobId"));
    for (const int id : expand_ids(tasks)) out[id] = s;
  }
  return out;
}

SchedulerStates slurm_states(const std::string& dir) {
  SchedulerStates out;
  for (const Job& job : recorded_job_list(dir)) {
    int status = 0;
    const std::string text = capture({"scontrol", "-o", "show", "job", job.id}, &status);
    if (status != 0) continue;  // purged (MinJobAge) or unknown: the files speak
    const std::vector<std::vector<int>> elements = job.ids_file.empty() ? std::vector<std::vector<int>>{} : element_ids(job.ids_file);
    for (const auto& [index, s] : parse_scontrol(text)) {
      if (job.ids_file.empty()) {
        out[index] = s;
      } else if (index >= 0 && static_cast<std::size_t>(index) < elements.size()) {
        for (const int id : elements[static_cast<std::size_t>(index)]) out[id] = s;
      }
    }
  }
  return out;
}

void wait_for_jobs(const std::string& dir, double poll_s, std::ostream& err) {
  const std::vector<std::string> jobs = recorded_jobs(dir);
  if (jobs.empty()) return;
  std::string ids;
  for (const std::string& j : jobs) ids += (ids.empty() ? "" : ",") + j;
  std::string last;
  for (;;) {
    int status = 0;
    const std::string out = capture({"squeue", "-h", "-r", "-j", ids, "-o", "%T"}, &status);
    int pending = 0, running = 0;
    std::stringstream ss(out);
    std::string st;
    while (std::getline(ss, st)) {
      if (st == "PENDING") ++pending;
      else if (!st.empty()) ++running;
    }
    if (status != 0 && out.find("Invalid job id") == std::string::npos) {
      throw Error("squeue failed (exit status " + std::to_string(status) + "): " + out);
    }
    const std::string line = fmt::format("sweep: Slurm: {} pending, {} running", pending, running);
    if (line != last) err << line << '\n' << std::flush;
    last = line;
    if (pending + running == 0) return;
    std::this_thread::sleep_for(std::chrono::duration<double>(poll_s));
  }
}

}  // namespace gnssemu::cli::sweep

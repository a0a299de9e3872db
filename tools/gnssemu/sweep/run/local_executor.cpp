// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/run/local_executor.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <thread>

#include "core/common/error.hpp"
#include "tools/gnssemu/sweep/run/sweep_task.hpp"
#include "tools/gnssemu/sweep/run/task_state.hpp"

namespace gnssemu::cli::sweep {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kExitTaskError = 3;  ///< the task threw (bad or changed input)
constexpr int kExitTaskCrash = 4;  ///< the task threw something unexpected

/// The child: run one task with stdout and stderr on its log, then _exit.
[[noreturn]] void child(const Plan& plan, const std::string& dir, int id) {
  const std::string log = (std::filesystem::path(task_dir(dir, id)) / kLogFile).string();
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd >= 0) {
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    ::close(fd);
  }
  int status = 0;
  try {
    run_task(plan, dir, id, std::cerr);
  } catch (const Error& e) {
    std::cerr << "gnssemu sweep task " << id << ": " << e.what() << '\n';
    mark_failed(dir, id, fmt::format("exit status {}: {}", kExitTaskError, e.what()));
    status = kExitTaskError;
  } catch (const std::exception& e) {
    std::cerr << "gnssemu sweep task " << id << ": " << e.what() << '\n';
    status = kExitTaskCrash;
  }
  std::cerr.flush();
  std::cout.flush();
  ::_exit(status);
}

std::string how_it_ended(int wstatus) {
  if (WIFEXITED(wstatus)) return fmt::format("exit status {}", WEXITSTATUS(wstatus));
  if (WIFSIGNALED(wstatus)) return fmt::format("killed by signal {} ({})", WTERMSIG(wstatus), ::strsignal(WTERMSIG(wstatus)));
  return "ended abnormally";
}

std::string clock_text(double s) {
  if (!(s >= 0.0)) return "--:--";
  const auto t = static_cast<long>(s + 0.5);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60) : fmt::format("{}:{:02}", t / 60, t % 60);
}

}  // namespace

LocalRunResult run_local(const Plan& plan, const std::string& dir, const std::vector<int>& ids,
                         const LocalRunOptions& options, std::ostream& err) {
  const int jobs = options.jobs > 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  for (const int id : ids) {
    std::error_code ec;
    std::filesystem::create_directories(task_dir(dir, id), ec);
    if (ec) throw Error(task_dir(dir, id), 0, "cannot create the task folder: " + ec.message());
  }
  err.flush();
  std::cout.flush();
  std::cerr.flush();
  struct Running {
    int id;
    Clock::time_point start;
  };
  std::map<pid_t, Running> running;
  LocalRunResult r;
  const Clock::time_point start = Clock::now();
  Clock::time_point last_line = start;
  std::size_t next = 0;
  const auto progress = [&](bool final) {
    const int finished = r.done + r.failed;
    const double el = std::chrono::duration<double>(Clock::now() - start).count();
    const double eta = finished > 0 ? el / finished * static_cast<double>(ids.size() - static_cast<std::size_t>(finished)) : -1.0;
    const std::string line = fmt::format("sweep: {}/{} done, {} failed, {} running, elapsed {}, ETA {}", r.done,
                                         ids.size(), r.failed, running.size(), clock_text(el), clock_text(eta));
    if (options.progress_bar) {
      err << '\r' << line << "\x1b[K" << (final ? "\n" : "") << std::flush;
    } else if (final || Clock::now() - last_line >= std::chrono::minutes(1)) {
      err << line << '\n' << std::flush;
      last_line = Clock::now();
    }
  };
  while (next < ids.size() || !running.empty()) {
    while (next < ids.size() && static_cast<int>(running.size()) < jobs) {
      const int id = ids[next++];
      const pid_t pid = ::fork();
      if (pid < 0) throw Error("sweep: fork failed");
      if (pid == 0) child(plan, dir, id);
      running.emplace(pid, Running{id, Clock::now()});
    }
    int wstatus = 0;
    const pid_t pid = ::waitpid(-1, &wstatus, options.task_timeout_s > 0.0 ? WNOHANG : 0);
    if (pid == 0) {
      // Poll for timeouts.
      for (const auto& [p, run] : running) {
        if (std::chrono::duration<double>(Clock::now() - run.start).count() > options.task_timeout_s) ::kill(p, SIGKILL);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw Error("sweep: waitpid failed");
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Running run = it->second;
    running.erase(it);
    const bool timed_out = options.task_timeout_s > 0.0 &&
                           std::chrono::duration<double>(Clock::now() - run.start).count() > options.task_timeout_s;
    const bool ok = WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0;
    if (ok) {
      ++r.done;
    } else {
      ++r.failed;
      const std::string why = timed_out ? fmt::format("timed out after {} s ({})", options.task_timeout_s, how_it_ended(wstatus))
                                        : how_it_ended(wstatus);
      if (!(WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == kExitTaskError)) mark_failed(dir, run.id, why);
      if (options.progress_bar) err << "\r\x1b[K";
      err << fmt::format("sweep: task {} failed ({}): {}\n", run.id, why, log_tail(dir, run.id, 3));
    }
    progress(false);
  }
  progress(true);
  r.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

}  // namespace gnssemu::cli::sweep

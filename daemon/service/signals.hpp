// SPDX-License-Identifier: Apache-2.0
#pragma once
// SignalDispatch: what gnssemud does on each signal (docs/daemon.md
// §Signals). Every signal whose default action ends the process is caught, so
// it leaves through the normal shutdown (ptys closed, symlinks removed,
// sockets closed, per-reason counts logged): SIGINT, SIGTERM, SIGQUIT and the
// rarer ones (SIGALRM, SIGVTALRM, SIGPROF, SIGIO, SIGPWR, SIGXCPU, SIGXFSZ).
// SIGHUP reloads the configuration, SIGUSR1 and SIGUSR2 log a status line
// and SIGPIPE is ignored (a reader that went away is a write error).
#include <functional>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>

namespace gnssemu::daemon {

enum class SignalAction {
  kTerminate,  ///< shut down cleanly, exit 0
  kReload,     ///< reload the configuration
  kStatus,     ///< log a status line
  kIgnore,
};

/// What gnssemud does on sig (a signal number); kIgnore for signals it does not catch.
SignalAction signal_action(int sig) noexcept;

class SignalDispatch {
public:
  using Handler = std::function<void(SignalAction action, int sig)>;

  /// Catches the signals of signal_action on io (SIGPIPE: SIG_IGN) and calls
  /// handler on the event loop; waits again after every action but kTerminate.
  SignalDispatch(boost::asio::io_context& io, Handler handler);

  /// Stop waiting (shutdown).
  void cancel() noexcept;

private:
  void wait();

  boost::asio::signal_set set_;
  Handler handler_;
};

}  // namespace gnssemu::daemon

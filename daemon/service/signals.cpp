// SPDX-License-Identifier: Apache-2.0
#include "daemon/service/signals.hpp"

#include <csignal>

#include <array>

namespace gnssemu::daemon {
namespace {

// Default action "terminate" or "core" (signal(7)), async ones only: a
// SIGSEGV or SIGBUS handler cannot clean up safely.
constexpr std::array kTerminating = {SIGINT,    SIGTERM, SIGQUIT, SIGALRM, SIGVTALRM,
                                     SIGPROF,   SIGIO,   SIGPWR,  SIGXCPU, SIGXFSZ};

}  // namespace

SignalAction signal_action(int sig) noexcept {
  if (sig == SIGHUP) return SignalAction::kReload;
  if (sig == SIGUSR1 || sig == SIGUSR2) return SignalAction::kStatus;
  for (int s : kTerminating) {
    if (s == sig) return SignalAction::kTerminate;
  }
  return SignalAction::kIgnore;
}

SignalDispatch::SignalDispatch(boost::asio::io_context& io, Handler handler) : set_(io), handler_(std::move(handler)) {
  std::signal(SIGPIPE, SIG_IGN);
  for (int s : kTerminating) set_.add(s);
  set_.add(SIGHUP);
  set_.add(SIGUSR1);
  set_.add(SIGUSR2);
  wait();
}

void SignalDispatch::cancel() noexcept {
  boost::system::error_code ec;
  set_.cancel(ec);
}

void SignalDispatch::wait() {
  set_.async_wait([this](const boost::system::error_code& ec, int sig) {
    if (ec) return;
    const SignalAction a = signal_action(sig);
    if (a != SignalAction::kTerminate) wait();
    handler_(a, sig);
  });
}

}  // namespace gnssemu::daemon

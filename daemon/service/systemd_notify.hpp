// SPDX-License-Identifier: Apache-2.0
#pragma once
// SystemdNotify: the sd_notify(3) protocol for Type=notify units — READY=1
// once ports and the truth socket are open, STATUS= lines, RELOADING=1 /
// READY=1 around a reload, STOPPING=1, and WATCHDOG=1 at half of
// WatchdogSec from the event loop (a stuck loop stops the pings and systemd
// restarts the service). Inactive without NOTIFY_SOCKET (not under systemd).
#include <string>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

namespace gnssemu::daemon {

class SystemdNotify {
public:
  explicit SystemdNotify(boost::asio::io_context& io);

  /// READY=1 with a status line; starts the watchdog pings.
  void ready(const std::string& status);
  void status(const std::string& status);
  void reloading();
  void stopping();

private:
  void send(const std::string& state);
  void ping();

  bool active_ = false;     ///< NOTIFY_SOCKET is set
  bool stopping_ = false;   ///< a ping queued before stopping() must not re-arm
  double watchdog_s_ = 0.0;  ///< WATCHDOG_USEC as s; 0: none
  boost::asio::steady_timer timer_;
};

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#include "daemon/service/systemd_notify.hpp"

#include <systemd/sd-daemon.h>

#include <chrono>
#include <cstdlib>
#include <cstring>

#include <spdlog/spdlog.h>

namespace gnssemu::daemon {

SystemdNotify::SystemdNotify(boost::asio::io_context& io) : timer_(io) {
  const char* sock = std::getenv("NOTIFY_SOCKET");
  active_ = sock != nullptr && *sock != '\0';
  uint64_t usec = 0;
  if (active_ && sd_watchdog_enabled(0, &usec) > 0) watchdog_s_ = static_cast<double>(usec) * 1e-6;
}

void SystemdNotify::send(const std::string& state) {
  if (!active_) return;
  const int r = sd_notify(0, state.c_str());
  if (r < 0) spdlog::warn("systemd: sd_notify failed: {}", std::strerror(-r));
}

void SystemdNotify::ready(const std::string& status) {
  send("READY=1\nSTATUS=" + status);
  if (watchdog_s_ > 0.0) {
    spdlog::info("systemd: watchdog every {:.1f} s", watchdog_s_ / 2);
    ping();
  }
}

void SystemdNotify::status(const std::string& status) { send("STATUS=" + status); }

void SystemdNotify::reloading() {
  // MONOTONIC_USEC goes with RELOADING=1 for Type=notify-reload (systemd 253);
  // older managers ignore it.
  const auto now_us = std::chrono::duration_cast<std::chrono::microseconds>(
                          std::chrono::steady_clock::now().time_since_epoch())
                          .count();
  send("RELOADING=1\nMONOTONIC_USEC=" + std::to_string(now_us));
}

void SystemdNotify::stopping() {
  stopping_ = true;
  timer_.cancel();
  send("STOPPING=1");
}

void SystemdNotify::ping() {
  send("WATCHDOG=1");
  timer_.expires_after(std::chrono::microseconds(static_cast<int64_t>(watchdog_s_ * 0.5e6)));
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec && !stopping_) ping();
  });
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#pragma once
// A fixture whose io_context runs on a thread of its own, as the daemon's
// does: servers are built, queried and stopped on it through on_io().
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <optional>
#include <thread>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio.hpp>

namespace gnssemu::daemon::test {

class IoThreadTest : public ::testing::Test {
protected:
  /// Run f on the io thread and wait for its result.
  template <class F>
  auto on_io(F f) {
    std::packaged_task<decltype(f())()> task(std::move(f));
    auto fut = task.get_future();
    boost::asio::post(io_, [&task] { task(); });
    return fut.get();
  }
  /// Poll pred (run on the io thread) until it holds or limit_ms passes;
  /// what a server does after a client's move is asynchronous and a loaded
  /// machine can take far longer than usual.
  template <class Pred>
  bool eventually_on_io(Pred pred, int limit_ms = 5000) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(limit_ms);
    for (;;) {
      if (on_io(pred)) return true;
      if (std::chrono::steady_clock::now() >= end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  void start_io() {
    work_.emplace(boost::asio::make_work_guard(io_));
    thread_ = std::thread([this] { io_.run(); });
  }
  void stop_io() {
    work_.reset();
    io_.stop();
    thread_.join();
  }

  boost::asio::io_context io_;

private:
  std::optional<boost::asio::executor_work_guard<boost::asio::io_context::executor_type>> work_;
  std::thread thread_;
};

}  // namespace gnssemu::daemon::test

#pragma once
// A fixture whose io_context runs on a thread of its own, as the daemon's
// does: servers are built, queried and stopped on it through on_io().
#include <gtest/gtest.h>

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

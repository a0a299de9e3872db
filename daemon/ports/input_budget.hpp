// SPDX-License-Identifier: Apache-2.0
#pragma once
// How much host input a port takes before its next read waits: a token
// bucket of bytes. A host flooding one port (garbage into a UBX decoder at
// megabytes a second) then waits in the kernel's buffer (TCP's window, the
// pty's and tty's queues) instead of holding the daemon's one thread, so
// the other ports and the truth socket keep their share. InputBudget is
// pure; InputPacer puts the wait on an Asio timer.
#include <chrono>
#include <cstddef>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

namespace gnssemu::daemon {

/// Input bytes per second a port takes at most: above a 921600-baud line's
/// 92 kB/s, and about 0.3 % of a core of worst-case decoding.
inline constexpr double kInputBytesPerS = 128.0 * 1024.0;
/// What a port may take at once after a quiet spell, bytes.
inline constexpr double kInputBurstBytes = 16.0 * 1024.0;

class InputBudget {
public:
  /// bytes_per_s: sustained rate, B/s (> 0); burst_bytes: bucket size, B (> 0).
  explicit InputBudget(double bytes_per_s = kInputBytesPerS, double burst_bytes = kInputBurstBytes) noexcept
      : rate_(bytes_per_s), burst_(burst_bytes), level_(burst_bytes) {}

  /// Take n bytes read at now_s (monotonic, s). Returns how long the next
  /// read waits, s: 0 while the bucket holds some, else until it refills to
  /// one read's worth.
  double spend(std::size_t n, double now_s) noexcept;

private:
  double rate_, burst_, level_;
  double last_s_ = 0.0;
  bool started_ = false;
};

/// An InputBudget for one reader of a port on io's clock.
class InputPacer {
public:
  explicit InputPacer(boost::asio::io_context& io) : timer_(io) {}
  /// n bytes were just read: call read() now, or after the budget's wait.
  template <class Read>
  void next(std::size_t n, Read read) {
    const double wait_s = budget_.spend(n, std::chrono::duration<double>(Clock::now().time_since_epoch()).count());
    if (wait_s <= 0.0) {
      read();
      return;
    }
    ++waits_;
    timer_.expires_after(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(wait_s)));
    timer_.async_wait([read = std::move(read)](const boost::system::error_code& ec) {
      if (!ec) read();
    });
  }
  /// Stop a pending wait (the reader is going away).
  void cancel() noexcept { timer_.cancel(); }
  /// Reads that had to wait so far.
  unsigned long waits() const noexcept { return waits_; }

private:
  using Clock = std::chrono::steady_clock;
  boost::asio::steady_timer timer_;
  InputBudget budget_;
  unsigned long waits_ = 0;
};

}  // namespace gnssemu::daemon

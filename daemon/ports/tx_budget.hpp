// SPDX-License-Identifier: Apache-2.0
#pragma once
// Transmit-side model of a u-blox UART: messages enter a finite TX buffer
// that the line drains at baud / 10 bytes per second (8N1: start + 8 data +
// stop bits). A message that does not fit whole in the free space is dropped,
// as a u-blox drops messages it cannot buffer (u-blox ANTARIS 4 System
// Integration Manual §4.4.1: "If the baud rate is insufficient to transmit all
// enabled messages, some messages may be discarded"). Pure, no clock: callers
// pass monotonic time.
#include <cstddef>
#include <cstdint>

namespace gnssemu::daemon {

/// TX buffer per port. u-blox does not publish the M8's size; CFG-PRT's
/// txReady threshold counts up to 511 x 8 = 4088 bytes of pending output, so
/// the buffer holds at least that much. Assumption: 4 KiB (docs/ports.md).
inline constexpr std::size_t kTxBufferBytes = 4096;

/// Bits on the line per byte, 8N1.
inline constexpr double kBitsPerByte = 10.0;

class TxBudget {
public:
  /// baud_bps: line rate, bit/s; 0 = no line (everything admitted).
  /// capacity_bytes: TX buffer size.
  explicit TxBudget(uint32_t baud_bps = 0, std::size_t capacity_bytes = kTxBufferBytes) noexcept
      : baud_bps_(baud_bps), capacity_bytes_(capacity_bytes) {}

  /// Drain what the line carried since the last call; now_s: monotonic time, s.
  void advance(double now_s) noexcept;
  /// Queue a whole message of n bytes at now_s. False (dropped) when it does
  /// not fit in the free space.
  bool admit(std::size_t n, double now_s) noexcept;
  /// Change the line rate at now_s (the queued bytes drain at the new rate).
  void set_baud(uint32_t baud_bps, double now_s) noexcept;

  bool limited() const noexcept { return baud_bps_ != 0; }
  uint32_t baud_bps() const noexcept { return baud_bps_; }
  std::size_t capacity_bytes() const noexcept { return capacity_bytes_; }
  /// Bytes queued and not yet on the line (after the last advance).
  double level_bytes() const noexcept { return level_bytes_; }
  /// Line capacity, bytes per second.
  double line_bytes_per_s() const noexcept { return baud_bps_ / kBitsPerByte; }

private:
  uint32_t baud_bps_;
  std::size_t capacity_bytes_;
  double level_bytes_ = 0.0;
  double last_s_ = 0.0;
  bool started_ = false;
};

}  // namespace gnssemu::daemon

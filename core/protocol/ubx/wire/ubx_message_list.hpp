// SPDX-License-Identifier: Apache-2.0
#pragma once
// MessageList: the messages one port sends in an epoch, framed and in send
// order, in one buffer, each with the name logs and drop counts use. Lets a
// transport admit or drop whole messages without parsing its bytes again.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gnssemu::protocol::ubx {

enum class Protocol : std::uint8_t { kUbx, kNmea, kRtcm3 };

class MessageList {
public:
  struct Message {
    std::size_t begin = 0, end = 0;  ///< bytes [begin, end) of the list's buffer
    std::string_view label;          ///< "NAV-PVT", "GGA" (static storage)
    Protocol protocol = Protocol::kUbx;
  };
  /// Largest epoch: every periodic UBX message (24), NMEA sentence (7 plus
  /// the GSV parts of every system), an RXM-SFRBX per satellite in view
  /// and the F9P's RTCM 3 output (11).
  static constexpr std::size_t kMaxMessages = 240;
  /// Bytes of the largest epoch (UBX kMaxEpochBytes + nmea::kMaxEpochBytes,
  /// RXM-RAWX of every measurement (6.2 KB) and an SFRBX per satellite in
  /// view (5.4 KB), the F9P's RTCM 3 output (8 KB), rounded up).
  static constexpr std::size_t kMaxBytes = 40960;

  /// Reserves for the largest epoch: filling it never allocates.
  MessageList() {
    bytes_.reserve(kMaxBytes);
    messages_.reserve(kMaxMessages);
  }

  void clear() noexcept {
    bytes_.clear();
    messages_.clear();
  }
  std::span<const Message> messages() const noexcept { return messages_; }
  std::string_view bytes(const Message& m) const noexcept {
    return std::string_view(bytes_).substr(m.begin, m.end - m.begin);
  }
  std::string_view bytes() const noexcept { return bytes_; }

  /// For composers: append a message's bytes to buffer(), then close() it.
  std::string& buffer() noexcept { return bytes_; }
  /// The bytes appended since the last close() are one message.
  void close(std::string_view label, Protocol protocol) {
    const std::size_t begin = messages_.empty() ? 0 : messages_.back().end;
    messages_.push_back({begin, bytes_.size(), label, protocol});
  }

private:
  std::string bytes_;
  std::vector<Message> messages_;
};

}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
#pragma once
// MSB-first bit fields of RTCM 3 payloads (RTCM 10403.3 §3.3: every data
// field is sent most significant bit first; signed fields are two's
// complement, the "intS" of DF020-style fields sign-magnitude). The writer
// fills a caller's fixed buffer and flags an overflow instead of writing past
// it; the reader returns 0 past the end and flags it.
#include <cstddef>
#include <cstdint>
#include <span>

namespace gnssemu::protocol::rtcm {

class BitWriter {
public:
  /// buf: the payload buffer (not the frame); its size bounds the bits written.
  explicit BitWriter(std::span<std::uint8_t> buf) noexcept : buf_(buf) {
    for (auto& b : buf_) b = 0;
  }
  /// Unsigned field of bits (1..64) bits: the low bits of value.
  void u(int bits, std::uint64_t value) noexcept {
    if (pos_ + static_cast<std::size_t>(bits) > buf_.size() * 8) {
      overflow_ = true;
      return;
    }
    for (int i = bits - 1; i >= 0; --i, ++pos_) {
      if ((value >> i) & 1u) buf_[pos_ >> 3] |= static_cast<std::uint8_t>(0x80u >> (pos_ & 7));
    }
  }
  /// Two's-complement field of bits bits.
  void s(int bits, std::int64_t value) noexcept { u(bits, static_cast<std::uint64_t>(value)); }
  /// Sign-magnitude field (sign bit, then bits-1 bits of |value|): GLONASS DF (intS).
  void sm(int bits, std::int64_t value) noexcept {
    u(1, value < 0 ? 1u : 0u);
    u(bits - 1, static_cast<std::uint64_t>(value < 0 ? -value : value));
  }
  std::size_t bits() const noexcept { return pos_; }
  std::size_t bytes() const noexcept { return (pos_ + 7) / 8; }
  bool overflow() const noexcept { return overflow_; }

private:
  std::span<std::uint8_t> buf_;
  std::size_t pos_ = 0;
  bool overflow_ = false;
};

class BitReader {
public:
  explicit BitReader(std::span<const std::uint8_t> buf) noexcept : buf_(buf) {}
  std::uint64_t u(int bits) noexcept {
    if (pos_ + static_cast<std::size_t>(bits) > buf_.size() * 8) {
      overrun_ = true;
      pos_ = buf_.size() * 8;
      return 0;
    }
    std::uint64_t v = 0;
    for (int i = 0; i < bits; ++i, ++pos_) v = (v << 1) | ((buf_[pos_ >> 3] >> (7 - (pos_ & 7))) & 1u);
    return v;
  }
  std::int64_t s(int bits) noexcept {
    const std::uint64_t v = u(bits);
    const std::uint64_t sign = std::uint64_t{1} << (bits - 1);
    return static_cast<std::int64_t>(v ^ sign) - static_cast<std::int64_t>(sign);
  }
  std::int64_t sm(int bits) noexcept {
    const bool neg = u(1) != 0;
    const auto mag = static_cast<std::int64_t>(u(bits - 1));
    return neg ? -mag : mag;
  }
  std::size_t bits() const noexcept { return pos_; }
  bool overrun() const noexcept { return overrun_; }

private:
  std::span<const std::uint8_t> buf_;
  std::size_t pos_ = 0;
  bool overrun_ = false;
};

}  // namespace gnssemu::protocol::rtcm

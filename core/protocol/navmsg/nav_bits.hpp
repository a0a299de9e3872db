// SPDX-License-Identifier: Apache-2.0
#pragma once
// Bit packing for broadcast navigation messages: fields written MSB first
// into a bit string, values quantized to a field's scale factor (two's
// complement for signed fields), as the ICDs lay them out.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace gnssemu::protocol::navmsg {

/// A bit string of up to Bits bits, written in order.
template <std::size_t Bits>
class BitString {
public:
  /// Append the low n (<= 32) bits of value, MSB first.
  constexpr void put(std::uint32_t value, int n) noexcept {
    for (int i = n - 1; i >= 0; --i) set_bit(pos_++, (value >> i) & 1u);
  }
  /// Skip n bits (left 0).
  constexpr void skip(int n) noexcept { pos_ += static_cast<std::size_t>(n); }
  constexpr void set_bit(std::size_t at, std::uint32_t bit) noexcept {
    if (at >= Bits) return;
    if (bit) bytes_[at / 8] = static_cast<std::uint8_t>(bytes_[at / 8] | (0x80u >> (at % 8)));
  }
  /// n (<= 32) bits from position at, MSB first.
  constexpr std::uint32_t get(std::size_t at, int n) const noexcept {
    std::uint32_t v = 0;
    for (int i = 0; i < n; ++i) {
      const std::size_t b = at + static_cast<std::size_t>(i);
      v = v << 1 | (b < Bits ? (bytes_[b / 8] >> (7 - b % 8)) & 1u : 0u);
    }
    return v;
  }
  constexpr std::size_t size() const noexcept { return pos_; }
  constexpr void seek(std::size_t pos) noexcept { pos_ = pos; }
  constexpr const std::array<std::uint8_t, (Bits + 7) / 8>& bytes() const noexcept { return bytes_; }

private:
  std::array<std::uint8_t, (Bits + 7) / 8> bytes_{};
  std::size_t pos_ = 0;
};

/// value / scale rounded, as an n-bit two's complement field (saturated
/// to the field's range; NaN gives 0).
inline std::uint32_t quantize_signed(double value, double scale, int n) noexcept {
  const double q = value / scale;
  const double hi = std::ldexp(1.0, n - 1) - 1.0;
  const double v = std::isfinite(q) ? std::clamp(std::round(q), -hi - 1.0, hi) : 0.0;
  const std::int64_t i = static_cast<std::int64_t>(v);
  return static_cast<std::uint32_t>(static_cast<std::uint64_t>(i) & ((std::uint64_t{1} << n) - 1));
}

/// value / scale rounded, as an n-bit unsigned field (saturated; NaN gives 0).
inline std::uint32_t quantize_unsigned(double value, double scale, int n) noexcept {
  const double q = value / scale;
  const double hi = std::ldexp(1.0, n) - 1.0;
  return static_cast<std::uint32_t>(std::isfinite(q) ? std::clamp(std::round(q), 0.0, hi) : 0.0);
}

/// Sign-magnitude n-bit field (GLONASS): sign bit then magnitude.
inline std::uint32_t quantize_sign_magnitude(double value, double scale, int n) noexcept {
  const std::uint32_t mag = quantize_unsigned(std::fabs(value), scale, n - 1);
  return (value < 0.0 && mag != 0 ? 1u << (n - 1) : 0u) | mag;
}

/// Two's complement n-bit field back to an integer (for decoders and tests).
constexpr std::int64_t sign_extend(std::uint32_t v, int n) noexcept {
  return (v >> (n - 1)) & 1u ? static_cast<std::int64_t>(v) - (std::int64_t{1} << n) : static_cast<std::int64_t>(v);
}

/// Klobuchar alpha_n and beta_n scales, 2^exp s/semicircle^n: the same in
/// GPS LNAV (IS-GPS-200 Table 20-X) and BeiDou D1/D2 (BDS ICD §5.2.4.7).
inline constexpr std::array<int, 4> kKlobucharAlphaExp{-30, -27, -24, -24};
inline constexpr std::array<int, 4> kKlobucharBetaExp{11, 14, 16, 16};

inline constexpr double kSemicircle_rad = 3.1415926535898;  ///< pi as IS-GPS-200 §20.3.3.3.3 fixes it

}  // namespace gnssemu::protocol::navmsg

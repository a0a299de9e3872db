// SPDX-License-Identifier: Apache-2.0
#pragma once
// The field layout of MSM4 to MSM7 (RTCM 10403.3 §3.5.6, Tables 3.5-78 to
// 3.5-91; shared/reference/rtk-raw.md §2.3-2.4): which satellite fields a
// kind carries, the width and unit of each signal field, and the lock-time
// indicators both ways. One table for the encoder and the decoder.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/common/constants.hpp"

namespace gnssemu::protocol::rtcm {

/// The MSM range unit: one millisecond of light travel, m.
inline constexpr double kMsmRangeMs_m = kSpeedOfLight_m_s * 1e-3;
/// Bits of the MSM header up to the satellite mask (DF002 .. DF418).
inline constexpr int kMsmHeaderBits = 12 + 12 + 30 + 1 + 3 + 7 + 2 + 2 + 1 + 3;
/// Most cells of one MSM (the cell mask is at most 64 bits).
inline constexpr int kMsmMaxCells = 64;

struct MsmFields {
  int kind;                ///< 4..7
  bool ext_info;           ///< 4-bit extended satellite info (GLONASS FCN + 7)
  bool rates;              ///< DF399 rough and DF404 fine phase-range rate
  int psr_bits;            ///< fine pseudorange DF400 / DF405
  double psr_unit_ms;
  int phr_bits;            ///< fine phase-range DF401 / DF406
  double phr_unit_ms;
  int lock_bits;           ///< lock-time indicator DF402 / DF407
  int cnr_bits;            ///< CNR DF403 / DF408
  double cnr_unit_dbhz;
  /// Bits per satellite and per cell after the masks.
  constexpr int sat_bits() const noexcept { return 8 + (ext_info ? 4 : 0) + 10 + (rates ? 14 : 0); }
  constexpr int cell_bits() const noexcept { return psr_bits + phr_bits + lock_bits + 1 + cnr_bits + (rates ? 15 : 0); }
  /// The value a signed field of bits bits sends for "invalid": its most negative.
  static constexpr std::int64_t invalid(int bits) noexcept { return -(std::int64_t{1} << (bits - 1)); }
  constexpr bool high_resolution() const noexcept { return lock_bits == 10; }
};

inline constexpr double kP2_24 = 1.0 / 16777216.0;
inline constexpr double kP2_29 = 1.0 / 536870912.0;
inline constexpr double kP2_31 = 1.0 / 2147483648.0;

inline constexpr std::array<MsmFields, 4> kMsmFields{{
    {4, false, false, 15, kP2_24, 22, kP2_29, 4, 6, 1.0},
    {5, true, true, 15, kP2_24, 22, kP2_29, 4, 6, 1.0},
    {6, true, false, 20, kP2_29, 24, kP2_31, 10, 10, 0.0625},
    {7, true, true, 20, kP2_29, 24, kP2_31, 10, 10, 0.0625},
}};

/// Fields of MSM kind (4..7); MSM4's for anything else.
constexpr const MsmFields& msm_fields(int kind) noexcept {
  return kMsmFields[kind >= 4 && kind <= 7 ? static_cast<std::size_t>(kind - 4) : 0];
}

/// Lock time, s, at the start of the range a DF402 (4-bit) indicator
/// stands for (RTCM 10403.3 Table 3.5-74): 0 below 32 ms, 2^(i+4) ms.
inline double msm4_lock_time_s(int indicator) noexcept {
  if (indicator <= 0) return 0.0;
  return std::ldexp(1.0, std::min(indicator, 15) + 4) * 1e-3;
}

/// Lock time, s, a DF407 (10-bit) indicator stands for (Table 3.5-76):
/// i ms up to 63, then 2^n i - n 2^(n+5) ms for i in [32(n+1), 32(n+2)).
inline double msm7_lock_time_s(int indicator) noexcept {
  if (indicator <= 0) return 0.0;
  if (indicator < 64) return indicator * 1e-3;
  const int i = std::min(indicator, 704);
  const int n = i / 32 - 1;
  return (std::ldexp(1.0, n) * i - n * std::ldexp(1.0, n + 5)) * 1e-3;
}

}  // namespace gnssemu::protocol::rtcm

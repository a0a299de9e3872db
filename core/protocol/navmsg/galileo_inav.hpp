// SPDX-License-Identifier: Apache-2.0
#pragma once
// Galileo I/NAV word types 0-6 on E1-B re-encoded from a broadcast
// ephemeris (Galileo OS SIS ICD 2.0 §4.3.5 word layouts and scales, §4.3.2
// nominal page: even part = even/odd 0, page type 0, data 1-112, tail;
// odd part = even/odd 1, page type 0, data 113-128, reserved 1 (40),
// SAR (22), spare (2), CRC-24Q over both parts' first 114 + 82 bits,
// reserved 2 (8), tail). In RXM-SFRBX form (ZED-F9P IM R08 §3.13.1.5,
// shared/reference/rtk-raw.md §1.3): eight words, the 120-bit even part
// MSB first in words 0-3 and the odd part in words 4-7, 8 pad bits each.
// Word types 7-10 (almanac) and 16-20 are not produced.
#include <array>
#include <cstdint>
#include <optional>

#include "core/orbit/ephemeris.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::protocol::navmsg {

/// One nominal page pair (even + odd part) in the eight SFRBX words.
using InavPagePair = std::array<std::uint32_t, 8>;

/// A page pair lasts 2 s; 15 make the 30-s subframe (OS SIS ICD §4.3.2).
inline constexpr double kInavPagePair_s = 2.0;
inline constexpr double kInavSubframe_s = 30.0;

/// Broadcast parameters of word types 5 (NeQuick) and 6 (GST-UTC): GST is
/// GPST in the emulated world, so GST - UTC is the GPS UTC set.
struct InavIonoUtc {
  const orbit::NequickParams* nequick = nullptr;
  const orbit::UtcParams* utc = nullptr;
  int leap_seconds = 18;
};

/// Word type of the E1-B page pair that ends at GST tow_end_s (a multiple
/// of 2 s), by its place in the 30-s subframe: 2, 4, 6, 7, 8, 0, 0, 0, 0,
/// 0, 1, 3, 5, 0, 0 (⚠ our order, not checked against the ICD table; each
/// ephemeris word once per subframe as the ICD has it).
int inav_e1b_word_type(double tow_end_s) noexcept;

/// Word types this encoder produces: 0-6.
constexpr bool inav_word_produced(int type) noexcept { return type >= 0 && type <= 6; }

/// CRC-24Q (polynomial 0x1864CFB, initial 0) of the first n bits of bytes, MSB first.
std::uint32_t crc24q_bits(const std::uint8_t* bytes, std::size_t n_bits) noexcept;

/// The page pair carrying word type `type` (0-6) of eph's satellite that
/// starts at GPS time t_start (word types 0, 5 and 6 carry its GST WN and TOW).
InavPagePair galileo_inav_page_pair(const orbit::Ephemeris& eph, int type, const time::GpsTime& t_start,
                                    const InavIonoUtc& iono);

/// What word types 0-6 give back, for tests and tools; nullopt when a
/// page fails its even/odd, page type or CRC check, a word type is not its
/// index, or the four ephemeris words differ in IODnav.
struct InavDecoded {
  orbit::Ephemeris eph;  ///< sat (SVID), toe, toc, Keplerian set, clock, BGDs, SISA, health, IODnav
  int wn = 0;            ///< GST week of word type 0
  int tow_s = 0;         ///< GST TOW of word type 0
  std::array<double, 3> ai{};
  double a0_s = 0.0, a1_s_s = 0.0;
  int leap_s = 0;
};
std::optional<InavDecoded> decode_galileo_inav(const std::array<InavPagePair, 7>& pairs);

/// SISA index (OS SIS ICD §5.1.12) whose value is nearest accuracy_m; 255 (no accuracy predicted) when <= 0 or > 6 m.
int sisa_index(double accuracy_m) noexcept;
/// The accuracy of a SISA index, m; 0 for 255 or spare values.
double sisa_m(int index) noexcept;

}  // namespace gnssemu::protocol::navmsg

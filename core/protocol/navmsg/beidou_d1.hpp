// SPDX-License-Identifier: Apache-2.0
#pragma once
// BeiDou D1 subframes 1-3 (MEO/IGSO ephemeris, B1I) re-encoded from a
// broadcast ephemeris: BDS-SIS-ICD-B1I 3.0 §5.2 field order and scales,
// §5.1.3 BCH(15,11) with g(X) = X^4 + X + 1 on word 1's bits 16-26 and on
// each 11-bit half of words 2-10. In RXM-SFRBX form (ZED-F9P IM R02
// §4.7.4, shared/reference/rtk-raw.md §1.3): ten words, the 30 bits in
// bits 29-0 (the 2 MSBs padding), de-interleaved: word 1 = 26 data bits,
// 4 parity; words 2-10 = 22 data bits then the 4 parity bits of each half
// (⚠ the parity order is ours; RTKLIB reads only the data bits).
// Subframes 4-5 (almanac) are not produced; the GEOs' D2 is beidou_d2.hpp.
#include <array>
#include <cstdint>
#include <optional>

#include "core/orbit/ephemeris.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/protocol/navmsg/nav_bits.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::protocol::navmsg {

/// A D1 subframe or a D2 page in RXM-SFRBX form: ten 30-bit words.
using D1Subframe = std::array<std::uint32_t, 10>;

/// The data bits of a subframe: 26 of word 1, then 22 of each of words 2-10.
using BeidouInfo = BitString<224>;

/// Data bits to words with their BCH parity, and back (false: a parity fails).
D1Subframe beidou_words(const BeidouInfo& info) noexcept;
bool beidou_info(const D1Subframe& words, BeidouInfo& info) noexcept;

/// D1 subframe length, s; subframes count from the BDT week (BDT = GPST - 14 s).
inline constexpr double kD1Subframe_s = 6.0;

/// BCH(15,11) parity (4 bits) of 11 data bits, MSB first.
std::uint32_t bch15_11_parity(std::uint32_t data11) noexcept;

/// Subframe id (1-5) of the D1 subframe that starts at GPS time t_start.
int d1_subframe_id(const time::GpsTime& t_start) noexcept;

/// Subframe id (1-3) of eph's satellite starting at GPS time t_start (its
/// SOW), ionosphere in subframe 1 from klobuchar (zeros when null).
D1Subframe beidou_d1_subframe(const orbit::Ephemeris& eph, int id, const time::GpsTime& t_start,
                              const orbit::KlobucharParams* klobuchar) noexcept;

/// What a D1 frame or the D2 pages give back, for tests and tools.
struct BeidouDecoded {
  orbit::Ephemeris eph;  ///< Keplerian set, clock, TGD1/2, URA, SatH1, AODE/AODC; toe/toc GPST
  int sow_s = 0;         ///< SOW of subframe 1 (BDT)
  int week = 0;          ///< BDT week (13 bits)
  std::array<double, 4> alpha{}, beta{};
};
/// nullopt when a preamble, parity, subframe id or the SOW sequence fails.
std::optional<BeidouDecoded> decode_beidou_d1(const std::array<D1Subframe, 3>& subframes, int prn);

}  // namespace gnssemu::protocol::navmsg

// SPDX-License-Identifier: Apache-2.0
#pragma once
// GPS and QZSS LNAV subframes re-encoded from a broadcast ephemeris
// (IS-GPS-200N §20.3.2 word layout, §20.3.3.3 Table 20-III scales,
// §20.3.5.2 parity; IS-QZSS-PNT §5.2 uses the same layout), in the form
// u-blox RXM-SFRBX carries them (shared/reference/rtk-raw.md §1.3): per
// word, data bits 29-6 de-inverted, parity bits 5-0, bit 30 clear and bit
// 31 = D29 xor D30 of the previous word, so the parity checks with
// D29* = bit 31 and D30* = 0 (what gpsd's check assumes).
#include <array>
#include <cstdint>

#include "core/orbit/ephemeris.hpp"
#include "core/orbit/nav_data.hpp"

namespace gnssemu::protocol::navmsg {

/// Ten 30-bit words (plus the SFRBX bit 30/31 convention).
using LnavSubframe = std::array<std::uint32_t, 10>;

/// LNAV subframe length, s.
inline constexpr double kLnavSubframe_s = 6.0;

/// The six parity bits D25..D30 of a word whose bits 31 and 30 hold D29*
/// and D30* of the previous word and bits 29-6 the source data d1..d24
/// (IS-GPS-200N Table 20-XIV).
std::uint32_t lnav_parity(std::uint32_t word) noexcept;

/// The GPS/QZSS URA index (0..15) whose nominal accuracy covers accuracy_m
/// (IS-GPS-200N §20.3.3.3.1.3).
int ura_index(double accuracy_m) noexcept;

/// The accuracy a URA index stands for, m (its upper bound; 0 for 15, no prediction).
double ura_accuracy_m(int index) noexcept;

/// Broadcast ionosphere and UTC for subframe 4 page 18 (IS-GPS-200N §20.3.3.5.1.6-7).
struct LnavIonoUtc {
  const orbit::KlobucharParams* klobuchar = nullptr;
  const orbit::UtcParams* utc = nullptr;
  int leap_seconds = 18;  ///< delta t_LS and delta t_LSF, s
};

/// Subframe id (1-5) of eph's satellite ending at GPS time of week
/// tow_end_s (a multiple of 6 s): the HOW's TOW count is tow_end_s / 6,
/// subframe 1 starts each 30 s frame. week: GPS week of the subframe
/// (sent mod 1024). Subframes 1-3 carry eph, subframe 4 page 18
/// (ionosphere and UTC from iono); the other pages of subframes 4 and 5
/// (almanac, health) are not produced (lnav_page_produced).
LnavSubframe gps_lnav_subframe(const orbit::Ephemeris& eph, int subframe_id, int week, double tow_end_s,
                               const LnavIonoUtc& iono) noexcept;

/// Subframe id (1-5) whose transmission ends at tow_end_s (a multiple of 6 s).
constexpr int lnav_subframe_id(double tow_end_s) noexcept {
  const long k = static_cast<long>(tow_end_s / kLnavSubframe_s + 0.5) - 1;  // subframes since the week began
  return static_cast<int>(((k % 5) + 5) % 5) + 1;
}

/// Page (1-25) of subframes 4 and 5 in the 12.5-min cycle that ends at tow_end_s.
constexpr int lnav_page(double tow_end_s) noexcept {
  const long frame = static_cast<long>((tow_end_s - kLnavSubframe_s) / 30.0 + 1e-9);  // frames since the week began
  return static_cast<int>(frame % 25) + 1;
}

/// Page of subframe 4 with the ionosphere and UTC parameters (IS-GPS-200N Table 20-V: SV id 56).
inline constexpr int kLnavIonoUtcPage = 18;

/// gps_lnav_subframe produces the subframe ending at tow_end_s: 1-3, and 4 on page 18.
constexpr bool lnav_page_produced(double tow_end_s) noexcept {
  const int id = lnav_subframe_id(tow_end_s);
  return id <= 3 || (id == 4 && lnav_page(tow_end_s) == kLnavIonoUtcPage);
}

}  // namespace gnssemu::protocol::navmsg

// SPDX-License-Identifier: Apache-2.0
#pragma once
// GLONASS L1OF navigation strings 1-5 (the immediate data of every frame)
// re-encoded from a broadcast ephemeris: ICD GLONASS Ed. 5.1 §4.4 Table
// 4.5 layout and scales, sign-magnitude fields, §4.7 Hamming (85,77) check
// bits. In RXM-SFRBX form (ZED-F9P IM R02 §4.7.3, shared/reference/
// rtk-raw.md §1.3): the 85 bits from b85 (idle, 0) down to b1 over words
// 0-2 MSB first (the time mark is not included), word 3 the frame number
// (bits 7-0) and the superframe number (bits 31-16) the receiver deduced.
// Strings 6-15 (almanac) are not produced.
#include <array>
#include <cstdint>
#include <optional>

#include "core/orbit/ephemeris.hpp"
#include "core/time/glonass_time.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::protocol::navmsg {

/// Four SFRBX words of one string.
using GlonassString = std::array<std::uint32_t, 4>;

/// String length including the 0.3 s time mark, s; frame and superframe lengths, s.
inline constexpr double kGlonassString_s = 2.0;
inline constexpr double kGlonassFrame_s = 30.0;
inline constexpr double kGlonassSuperframe_s = 150.0;
/// Strings per frame; the ones produced (immediate data).
inline constexpr int kGlonassStringsPerFrame = 15;
inline constexpr int kGlonassStringsProduced = 5;

/// Where a string stands: frames start with the GLONASST day (ICD §4.4:
/// tk counts 30-s frames from 00:00 GLONASST).
struct GlonassStringSlot {
  int string = 0;                 ///< 1..15
  int frame = 0;                  ///< 1..5 within the superframe
  int superframe = 0;             ///< 1..576 within the GLONASST day
  time::GlonassTime frame_start;  ///< GLONASST of the frame's start (tk)
};

/// The slot of the string whose transmission ends at GPS time t_end (on the
/// 2-s grid of the GLONASST day). leap_s: GPS - UTC, s.
GlonassStringSlot glonass_string_slot(const time::GpsTime& t_end, int leap_s);

/// The eight check bits b8..b1 = beta8..beta1 (ICD §4.7; b1 the LSB) of the 85-bit string in
/// words 0-2 (b85 at bit 31 of word 0); the data bits b9..b85 are those
/// of the words, the check-bit positions b8..b1 are ignored.
std::uint32_t glonass_hamming(const GlonassString& s) noexcept;

/// String slot.string (1..5) of eph's satellite. leap_s: GPS - UTC, s.
/// Fields the run's ephemeris does not carry: P1 = 0, P4 = 0, delta tau_n = 0;
/// tau_c = tau_GPS = 0, as in the emulated world (UTC(SU) = GLONASST - 3 h,
/// GPST - GLONASST whole seconds); FT from sv_accuracy_m (15 when none).
GlonassString glonass_string(const orbit::Ephemeris& eph, const GlonassStringSlot& slot, int leap_s);

/// FT, the accuracy index whose value covers accuracy_m (ICD Table 4.4); 15 when accuracy_m <= 0.
int glonass_ft_index(double accuracy_m) noexcept;

/// The ephemeris strings 1-5 of one frame give back, for tests and tools:
/// nullopt when a check bit fails or a string number is not its index + 1.
struct GlonassDecoded {
  orbit::Ephemeris eph;  ///< sat (slot n), toe = toc from tb on day NT of N4, state, clock, Bn, E, tb index
  double tk_s = 0.0;     ///< frame time tk, s of the GLONASST day
  int nt = 0;            ///< day within the four-year interval
  int n4 = 0;            ///< four-year interval
  int ft = 0;            ///< accuracy index
  int m = 0;             ///< satellite type (1: GLONASS-M)
};
std::optional<GlonassDecoded> decode_glonass_strings(const std::array<GlonassString, 5>& strings, int channel,
                                                     int leap_s);

}  // namespace gnssemu::protocol::navmsg

// SPDX-License-Identifier: Apache-2.0
#pragma once
// u-blox's proprietary message 4072: a 12-bit sub-type after the message
// number; 4072.0 "reference station PVT" and 4072.1 "additional reference
// station information" (gpsd driver_rtcm3.c names; shared/reference/rtk-raw.md
// §2.6). u-blox does not publish the payload, and RTKLIB, pyrtcm and gpsd do
// not decode it. A real F9P's 4072 is recognised by its sub-type and counted;
// the position of a 4072.0 is read only from gnssemu's own layout
// (docs/rtk.md "4072"): DF002, sub-type U12, DF003 U12, GPS TOW U30 ms, ARP
// X/Y/Z int38 at 0.1 mm, 23 bytes in all.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "core/common/vec3.hpp"

namespace gnssemu::protocol::rtcm {

inline constexpr int kUbloxMessage = 4072;
/// Payload bytes of gnssemu's 4072.0.
inline constexpr std::size_t kReferencePvtBytes = 23;

/// What gnssemu's 4072.0 carries.
struct ReferencePvt {
  int station_id = 0;          ///< DF003, 0..4095
  std::uint32_t tow_ms = 0;    ///< GPS time of week of the position, ms (< 604800000)
  Ecef arp_ecef_m;             ///< the moving base's antenna, ECEF m
};

/// Sub-type of a 4072 payload (the 12 bits after the message number); -1
/// for another message or a payload too short to hold it.
int ublox_subtype(std::span<const std::uint8_t> payload) noexcept;

/// Appends a framed 4072.0 in gnssemu's layout.
void append_reference_pvt(const ReferencePvt& pvt, std::string& out);

/// The position of a 4072.0 in gnssemu's layout; nullopt for another
/// sub-type or length (a real F9P's, whose layout is not public).
std::optional<ReferencePvt> decode_reference_pvt(std::span<const std::uint8_t> payload) noexcept;

}  // namespace gnssemu::protocol::rtcm

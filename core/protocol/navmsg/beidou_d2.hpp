// SPDX-License-Identifier: Apache-2.0
#pragma once
// BeiDou D2 (the GEOs' B1I message, 500 bps) subframe 1, pages 1-10: the
// fundamental navigation information re-encoded from a broadcast
// ephemeris, BDS-SIS-ICD-B1I 3.0 §5.3.3.1 field order and scales (the
// fields of D1's subframes 1-3, several split across two pages). A frame
// is five 0.6-s subframes (3 s); subframe 1 carries page (SOW/3 mod 10) + 1,
// so the ten pages take 30 s. Words, parity and the RXM-SFRBX form as D1
// (beidou_d1.hpp). Page 2 carries the Klobuchar terms; subframes 2-5
// (integrity, differential corrections, almanac) are not produced.
#include <array>
#include <optional>

#include "core/orbit/ephemeris.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/protocol/navmsg/beidou_d1.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::protocol::navmsg {

/// D2 frame and subframe lengths, s; frames count from the BDT week.
inline constexpr double kD2Frame_s = 3.0;
inline constexpr double kD2Subframe_s = 0.6;
inline constexpr int kD2Pages = 10;

/// Page (1-10) of subframe 1 in the D2 frame that starts at GPS time t_start.
int d2_page(const time::GpsTime& t_start) noexcept;

/// Subframe 1, page `page` (1-10), of eph's GEO in the frame starting at t_start.
D1Subframe beidou_d2_page(const orbit::Ephemeris& eph, int page, const time::GpsTime& t_start,
                          const orbit::KlobucharParams* klobuchar) noexcept;

/// Pages 1-10 back to an ephemeris; nullopt when a preamble, parity,
/// subframe id, page number or the SOW sequence (+3 s a page) fails.
std::optional<BeidouDecoded> decode_beidou_d2(const std::array<D1Subframe, kD2Pages>& pages, int prn);

}  // namespace gnssemu::protocol::navmsg

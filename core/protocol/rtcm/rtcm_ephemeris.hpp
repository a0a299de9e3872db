// SPDX-License-Identifier: Apache-2.0
#pragma once
// Broadcast ephemerides as RTCM 3 messages: 1019 (GPS LNAV), 1020 (GLONASS),
// 1042 (BeiDou D1/D2), 1046 (Galileo I/NAV). Field order, widths and scales
// follow RTCM 10403.3 as RTKLIB's encoders and pyrtcm lay them out
// (shared/reference/rtk-raw.md §2.6); the values are the orbit::Ephemeris
// the run uses, scaled back to the broadcast units (semicircles, 2^-n).
#include <string>

#include "core/common/sat_id.hpp"
#include "core/orbit/ephemeris.hpp"

namespace gnssemu::protocol::rtcm {

/// Message number carrying ephemerides of sys (1019, 1020, 1042, 1046); 0 when none is encoded here.
int ephemeris_message_number(GnssSystem sys) noexcept;

/// Appends the framed ephemeris message of eph. leap_s: GPS - UTC, s (GLONASS
/// times are UTC(SU) + 3 h). False (nothing appended) for a system without one.
bool append_ephemeris(const orbit::Ephemeris& eph, int leap_s, std::string& out);

/// GPS URA index (IS-GPS-200 §20.3.3.3.1.3) of an accuracy in metres: the
/// smallest index whose upper bound holds it; 15 beyond 6144 m.
int gps_ura_index(double accuracy_m) noexcept;

/// Galileo SISA index (Galileo OS SIS ICD §5.1.12) of an accuracy in metres; 255 = no accuracy prediction.
int galileo_sisa_index(double accuracy_m) noexcept;

}  // namespace gnssemu::protocol::rtcm

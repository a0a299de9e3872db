// SPDX-License-Identifier: Apache-2.0
#pragma once
// What the emulated chip's RF front end and its monitors report, derived
// once from the Fix for MON-HW (M8, M9), MON-RF and SEC-SIG (M9): noise
// level, AGC, the CW jamming indicator, the antenna supervisor and the
// jamming/interference monitor's state. Model and sources: docs/ubx.md
// §Jamming and interference.
#include <cstdint>

#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::ubx {

/// jammingState of MON-HW flags b2-3, MON-RF flags b0-1 and SEC-SIG jamFlags
/// b1-2 (u-blox integration manuals, "Jamming/interference monitor").
enum class JammingState : std::uint8_t {
  kUnknown = 0,   ///< monitor disabled, no good first fix yet, or antenna disconnected
  kOk = 1,        ///< no significant interference
  kWarning = 2,   ///< interference above the thresholds, fix OK
  kCritical = 3,  ///< interference above the thresholds and no fix
};

struct FrontEnd {
  std::uint16_t noise_per_ms = 0;  ///< noise level measured by the GNSS core (quiet sky ~85)
  std::uint16_t agc_cnt = 0;       ///< AGC monitor, 0..8191 = 0..100 % gain
  std::uint8_t jam_ind = 0;        ///< CW jamming indicator, 0 none .. 255 strong
  std::uint8_t mag_iq = 0;         ///< magnitude of the I and Q parts at the ADC, 0..255
  std::uint8_t ant_status = 2;     ///< 0 INIT, 1 DONTKNOW, 2 OK, 3 SHORT, 4 OPEN
  std::uint8_t ant_power = 1;      ///< 0 OFF, 1 ON, 2 DONTKNOW
  JammingState jamming_state = JammingState::kUnknown;
};

/// The front end at fix (noise_rise_db, cw_jam_to_noise, antenna_status) with
/// the monitor as info configures it (itfm_*) and the fix state the port
/// reports (info.reported_fix, else the Fix's). Never throws.
FrontEnd front_end(const receiver::Fix& fix, const EpochInfo& info) noexcept;

/// spoofDetState of NAV-STATUS flags2 b3-4 and spoofingState of SEC-SIG
/// spfFlags b1-3 (0 deactivated, 1 none, 2 indicated, 3 multiple indications).
std::uint8_t spoof_det_state(const receiver::Fix& fix) noexcept;

}  // namespace gnssemu::protocol::ubx

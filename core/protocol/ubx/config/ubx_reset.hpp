// SPDX-License-Identifier: Apache-2.0
#pragma once
// CFG-RST (UBX-13003221 CFG-RST): which reset a host asked for and what it
// means for the emulated chip. The one place reset modes are interpreted.
#include <cstdint>
#include <optional>
#include <string_view>

#include "core/protocol/ubx/wire/ubx_messages.hpp"

namespace gnssemu::protocol::ubx {

/// CFG-RST resetMode.
enum class ResetMode : std::uint8_t {
  kHardware = 0,               ///< hardware reset (watchdog), immediately
  kSoftware = 1,               ///< controlled software reset
  kGnssOnly = 2,               ///< controlled software reset, GNSS only
  kHardwareAfterShutdown = 4,  ///< hardware reset after shutdown
  kGnssStop = 8,               ///< controlled GNSS stop
  kGnssStart = 9,              ///< controlled GNSS start
};

/// What navBbrMask clears: nothing (hot), everything (cold), or some of the
/// navigation data (warm, 0x0001 and any other mask).
enum class StartKind : std::uint8_t { kHot, kWarm, kCold };

struct Reset {
  std::uint16_t nav_bbr_mask = 0;  ///< 0x0000 hot, 0x0001 warm, 0xFFFF cold
  ResetMode mode = ResetMode::kHardware;

  /// The reset of a CFG-RST payload, or nullopt for a resetMode an M8 lacks.
  static constexpr std::optional<Reset> from_wire(const wire::CfgRst& w) noexcept {
    switch (w.resetMode) {
      case 0: case 1: case 2: case 4: case 8: case 9:
        return Reset{w.navBbrMask, static_cast<ResetMode>(w.resetMode)};
      default:
        return std::nullopt;
    }
  }

  constexpr StartKind start() const noexcept {
    return nav_bbr_mask == 0 ? StartKind::kHot : nav_bbr_mask == 0xFFFF ? StartKind::kCold : StartKind::kWarm;
  }
  /// What the navBbrMask bits keep of the battery-backed navigation data
  /// (UBX-13003221 CFG-RST: b0 eph, b1 alm, b4 pos, b8 rtc).
  constexpr bool keeps_ephemeris() const noexcept { return (nav_bbr_mask & 0x0001) == 0; }
  constexpr bool keeps_almanac() const noexcept { return (nav_bbr_mask & 0x0002) == 0; }
  constexpr bool keeps_position() const noexcept { return (nav_bbr_mask & 0x0010) == 0; }
  constexpr bool keeps_time() const noexcept { return (nav_bbr_mask & 0x0100) == 0; }
  /// "hot", "warm", "cold" (logs).
  constexpr std::string_view start_name() const noexcept {
    switch (start()) {
      case StartKind::kHot: return "hot";
      case StartKind::kCold: return "cold";
      case StartKind::kWarm: break;
    }
    return "warm";
  }
  /// Every mode but GNSS stop restarts navigation: tracking and the solution
  /// start afresh, uptime (msss) and time to first fix count from the reset.
  /// GNSS stop is not modelled: the receiver keeps navigating.
  constexpr bool restarts_navigation() const noexcept { return mode != ResetMode::kGnssStop; }
  /// Hardware and software resets reboot the chip: the RAM configuration is
  /// lost and the saved one loaded. GNSS-only resets keep it.
  constexpr bool reloads_saved_config() const noexcept {
    return mode == ResetMode::kHardware || mode == ResetMode::kSoftware || mode == ResetMode::kHardwareAfterShutdown;
  }
  /// resetMode as sent (logs).
  constexpr unsigned mode_number() const noexcept { return static_cast<unsigned>(mode); }
};

}  // namespace gnssemu::protocol::ubx

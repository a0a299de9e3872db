// SPDX-License-Identifier: Apache-2.0
#pragma once
// The u-blox hardware generation the emulated chip presents. It decides what
// MON-VER says, which configuration interface answers (an M8 NAKs CFG-VAL*,
// an M9 and an F9P take it beside the legacy CFG messages they keep) and
// which output messages exist (MON-RF and SEC-SIG from the M9; NAV-SVINFO
// up to the M8; the high-precision NAV messages on the F9P only).
// Sources: shared/reference/ubx.md §MON-VER; docs/ubx.md §Generations.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/protocol/nmea/nmea_settings.hpp"

namespace gnssemu::protocol::ubx {

enum class Generation : std::uint8_t {
  kM8,  ///< NEO-M8N, firmware SPG 3.01, protocol 18.00 (hwVersion 00080000)
  kM9,  ///< NEO-M9N, firmware SPG 4.04, protocol 32.01 (hwVersion 00190000)
  kF9P, ///< ZED-F9P, firmware HPG 1.32, protocol 27.31 (hwVersion 00190000): L1/L2, RTK
};
inline constexpr std::size_t kNumGenerations = 3;

/// "m8", "m9", "f9p" (the configuration's spelling).
constexpr std::string_view generation_name(Generation g) noexcept {
  return g == Generation::kF9P ? "f9p" : g == Generation::kM9 ? "m9" : "m8";
}

/// Protocol 27 and later configure through CFG-VALSET/VALGET (PX4 switches on
/// PROTVER >= 27; shared/reference/ubx.md §Hosts).
constexpr bool has_config_interface(Generation g) noexcept { return g != Generation::kM8; }

/// A u-blox 9 (protocol 27+): the M9's and F9P's conventions where they
/// differ from the M8's (sigIds, NMEA 4.10, MON-RF).
constexpr bool is_generation9(Generation g) noexcept { return g != Generation::kM8; }

/// The NMEA conventions of the generation's firmware (GSV signal ids, factory
/// NMEA version: nmea::factory_settings).
constexpr nmea::NmeaDevice nmea_device(Generation g) noexcept {
  return g == Generation::kM8 ? nmea::NmeaDevice::kM8 : g == Generation::kM9 ? nmea::NmeaDevice::kM9 : nmea::NmeaDevice::kF9;
}

/// Two RF front ends (L1 and L2/L5 band): MON-RF blocks, NAV-SIG bands.
constexpr bool is_dual_band(Generation g) noexcept { return g == Generation::kF9P; }

}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
#pragma once
// The u-blox hardware generation the emulated chip presents. It decides what
// MON-VER says, which configuration interface answers (an M8 NAKs CFG-VAL*,
// an M9 takes it beside the legacy CFG messages) and which output messages
// exist (MON-RF and SEC-SIG from the M9; NAV-SVINFO up to the M8).
// Sources: shared/reference/ubx.md §MON-VER; docs/ubx.md §Generations.
#include <cstdint>
#include <string_view>

namespace gnssemu::protocol::ubx {

enum class Generation : std::uint8_t {
  kM8,  ///< NEO-M8N, firmware SPG 3.01, protocol 18.00 (hwVersion 00080000)
  kM9,  ///< NEO-M9N, firmware SPG 4.04, protocol 32.01 (hwVersion 00190000)
};

/// "m8", "m9" (the configuration's spelling).
constexpr std::string_view generation_name(Generation g) noexcept { return g == Generation::kM9 ? "m9" : "m8"; }

/// Protocol 27 and later configure through CFG-VALSET/VALGET (PX4 switches on
/// PROTVER >= 27; shared/reference/ubx.md §Hosts).
constexpr bool has_config_interface(Generation g) noexcept { return g == Generation::kM9; }

}  // namespace gnssemu::protocol::ubx

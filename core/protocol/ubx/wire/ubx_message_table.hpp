// SPDX-License-Identifier: Apache-2.0
#pragma once
// The periodic UBX messages the emulated chip sends, named once: their ids,
// where an epoch carries them, whether a port's configuration lists them and
// which hardware generations have them. Names are u-blox's (UBX-13003221
// §32, UBX-21022436; shared/reference/ubx.md §2; docs/ubx.md §Generations).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/config/ubx_generation.hpp"

namespace gnssemu::protocol::ubx {

/// Where an epoch carries a message relative to its NMEA sentences: a real
/// u-blox stream with both protocols (gpsd's ublox-zed-f9t-ubx_nmea_l5.log)
/// sends position and velocity first, then NMEA, then the rest.
enum class EpochGroup : std::uint8_t { kBeforeNmea, kAfterNmea };

/// Generations that have a message: bit (1 << Generation).
using GenerationSet = std::uint8_t;
constexpr GenerationSet generation_bit(Generation g) noexcept {
  return static_cast<GenerationSet>(1u << static_cast<unsigned>(g));
}
inline constexpr GenerationSet kM8Only = generation_bit(Generation::kM8);
inline constexpr GenerationSet kM9Only = generation_bit(Generation::kM9);
inline constexpr GenerationSet kF9POnly = generation_bit(Generation::kF9P);
/// Protocol 27 and later: the M9 and the F9P.
inline constexpr GenerationSet kGen9 = kM9Only | kF9POnly;
inline constexpr GenerationSet kAllGenerations = kM8Only | kGen9;

struct PeriodicMessage {
  MsgId id;
  std::string_view name;  ///< "NAV-PVT"
  EpochGroup group;
  bool configurable;      ///< may be listed in a port's ubx_messages (docs/configuration.md)
  /// Generations whose firmware has the message: NAV-SVINFO is gone from
  /// protocol 27 (shared/reference/ubx.md §3), MON-RF, SEC-SIG and NAV-SIG
  /// are new on the M9 (docs/ubx.md §Generations).
  GenerationSet generations = kAllGenerations;
  /// Raw data (RXM-RAWX, RXM-SFRBX): only firmware variants with raw output
  /// send it (DeviceSetup::raw_firmware; docs/raw-output.md "Availability").
  bool raw = false;

  constexpr bool exists_on(Generation g) const noexcept { return (generations & generation_bit(g)) != 0; }
};

/// Rows in the order the configuration lists them (docs/configuration.md).
inline constexpr std::array<PeriodicMessage, 24> kPeriodicMessages{{
    {msg::kNavPvt, "NAV-PVT", EpochGroup::kBeforeNmea, true},
    {msg::kNavPosllh, "NAV-POSLLH", EpochGroup::kBeforeNmea, true},
    {msg::kNavVelned, "NAV-VELNED", EpochGroup::kBeforeNmea, true},
    {msg::kNavStatus, "NAV-STATUS", EpochGroup::kBeforeNmea, true},
    {msg::kNavDop, "NAV-DOP", EpochGroup::kAfterNmea, true},
    {msg::kNavSol, "NAV-SOL", EpochGroup::kBeforeNmea, true},
    {msg::kNavTimeutc, "NAV-TIMEUTC", EpochGroup::kAfterNmea, true},
    {msg::kNavSat, "NAV-SAT", EpochGroup::kAfterNmea, true},
    {msg::kNavSvinfo, "NAV-SVINFO", EpochGroup::kAfterNmea, true, kM8Only},
    {msg::kMonHw, "MON-HW", EpochGroup::kAfterNmea, true},
    {msg::kMonRf, "MON-RF", EpochGroup::kAfterNmea, true, kGen9},
    {msg::kSecSig, "SEC-SIG", EpochGroup::kAfterNmea, true, kGen9},
    {msg::kNavEoe, "NAV-EOE", EpochGroup::kAfterNmea, true},
    {msg::kNavTimegps, "NAV-TIMEGPS", EpochGroup::kAfterNmea, false},
    {msg::kNavSig, "NAV-SIG", EpochGroup::kAfterNmea, true, kGen9},
    {msg::kNavTimeglo, "NAV-TIMEGLO", EpochGroup::kAfterNmea, true},
    {msg::kNavTimegal, "NAV-TIMEGAL", EpochGroup::kAfterNmea, true},
    {msg::kNavTimebds, "NAV-TIMEBDS", EpochGroup::kAfterNmea, true},
    {msg::kMonHw2, "MON-HW2", EpochGroup::kAfterNmea, true},
    {msg::kRxmRawx, "RXM-RAWX", EpochGroup::kAfterNmea, true, kAllGenerations, true},
    {msg::kRxmSfrbx, "RXM-SFRBX", EpochGroup::kAfterNmea, true, kAllGenerations, true},
    // HPG firmware only (ubx_hpg.hpp).
    {msg::kNavHpposecef, "NAV-HPPOSECEF", EpochGroup::kAfterNmea, true, kF9POnly},
    {msg::kNavHpposllh, "NAV-HPPOSLLH", EpochGroup::kAfterNmea, true, kF9POnly},
    {msg::kNavRelposned, "NAV-RELPOSNED", EpochGroup::kAfterNmea, true, kF9POnly},
}};

namespace detail {
/// Send order within an epoch: NAV by id (the M8 message table order), then
/// MON and SEC by class and id, NAV-EOE closing the epoch (ubx.md §3 NAV-EOE).
constexpr int epoch_rank(MsgId id) noexcept {
  const int group = id == msg::kNavEoe ? 2 : id.cls == cls::kNav ? 0 : 1;
  return group << 16 | id.key();
}
}  // namespace detail

/// Indices into kPeriodicMessages in send order within an epoch group.
inline constexpr std::array<std::size_t, kPeriodicMessages.size()> kEpochOrder = [] {
  std::array<std::size_t, kPeriodicMessages.size()> order{};
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  for (std::size_t i = 1; i < order.size(); ++i) {
    for (std::size_t j = i; j > 0 && detail::epoch_rank(kPeriodicMessages[order[j]].id) <
                                          detail::epoch_rank(kPeriodicMessages[order[j - 1]].id);
         --j) {
      const std::size_t t = order[j];
      order[j] = order[j - 1];
      order[j - 1] = t;
    }
  }
  return order;
}();

/// Row of a periodic message, or nullopt.
constexpr std::optional<PeriodicMessage> periodic_message(MsgId id) noexcept {
  for (const PeriodicMessage& m : kPeriodicMessages) {
    if (m.id == id) return m;
  }
  return std::nullopt;
}

/// False only for a periodic message generation g lacks (NAV-SVINFO on an
/// M9, MON-RF on an M8); ids outside the table are not judged here.
constexpr bool message_exists(MsgId id, Generation g) noexcept {
  const auto m = periodic_message(id);
  return !m || m->exists_on(g);
}

/// Name of a message the device sends, for logs: the periodic names,
/// "ACK-ACK", "ACK-NAK", "MON-VER", "CFG" for CFG poll answers, else "UBX".
constexpr std::string_view message_label(MsgId id) noexcept {
  if (const auto m = periodic_message(id)) return m->name;
  if (id == msg::kAckAck) return "ACK-ACK";
  if (id == msg::kAckNak) return "ACK-NAK";
  if (id == msg::kMonVer) return "MON-VER";
  if (id.cls == cls::kCfg) return "CFG";
  return "UBX";
}

}  // namespace gnssemu::protocol::ubx

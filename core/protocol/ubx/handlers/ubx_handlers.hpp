// SPDX-License-Identifier: Apache-2.0
#pragma once
// One handler per UBX input message the emulated M8 answers (gpsd's
// ubx_msg_* shape): each checks its payload, changes the configuration and
// appends its reply. find_handler() maps class/id to a handler through one
// table (ubx_handlers.cpp); adding a CFG message is one handler and one row.
// Behaviour and sources: docs/ubx.md §Configuration responder.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "core/protocol/ubx/config/ubx_device_config.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/config/ubx_reset.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::ubx {

struct ValTransaction;  // ubx_config_keys.hpp

/// What one input message got.
enum class Reply : std::uint8_t {
  kNone,      ///< ignored (not for us, or UBX output off on the port)
  kAck,       ///< ACK-ACK sent (a CFG set was applied)
  kNak,       ///< ACK-NAK sent
  kPollData,  ///< poll answered with data (CFG polls: data then ACK-ACK)
  kReset,     ///< CFG-RST: no answer, see HandlerContext::reset
};

/// What a handler works on. Handlers never throw and allocate only when out
/// lacks capacity (2 KiB beyond its size is always enough).
struct HandlerContext {
  DeviceConfig& current;         ///< RAM configuration
  DeviceConfig& saved;           ///< BBR/flash configuration (CFG-CFG, resets)
  const DeviceConfig& defaults;  ///< factory configuration (CFG-CFG clear)
  std::size_t uart;              ///< UART1 of the host: its output (< current.uarts())
  std::uint8_t port_id;          ///< u-blox port the frame arrived on (< kNumPorts; 1: the host's UART1)
  std::string& out;              ///< replies are appended here
  const UbxEncoder& encoder;     ///< MON-VER and polled output messages
  const receiver::Fix& last_fix;  ///< the last epoch's Fix, for polls of output messages
  const EpochInfo& info;          ///< and its uptime and ttff
  bool ack_unknown_cfg = false;  ///< ACK CFG ids an M8 lacks (except CFG-VAL*) instead of NAKing them
  Generation generation = Generation::kM8;  ///< the chip's (ubx_generation.hpp)
  std::optional<Reset> reset;    ///< set by CFG-RST
  /// The chip's CFG-VALSET transaction and scratch configurations; nullptr:
  /// VALSET and VALDEL are NAKed (ubx_cfg_val.cpp).
  ValTransaction* transaction = nullptr;

  /// Column of u-blox port p (< kNumPorts) as this host sees it.
  std::size_t column(std::uint8_t p) const noexcept { return current.column(uart, p); }
};

using Handler = Reply (*)(HandlerContext& ctx, const FrameView& frame);

/// The handler of id, or nullptr when the M8 does not answer it.
Handler find_handler(MsgId id) noexcept;
/// Payload lengths a stored CFG message accepts as a set (zeros end the
/// list); empty for messages without a row or with a handler of their own.
std::array<std::uint16_t, 3> stored_set_lengths(MsgId id) noexcept;

/// Append ACK-ACK (ok) or ACK-NAK for id.
Reply ack(HandlerContext& ctx, MsgId id, bool ok);
/// Append the poll answer for id (data, then ACK-ACK).
Reply poll_reply(HandlerContext& ctx, MsgId id, std::span<const std::uint8_t> data);

// Ports and rates (ubx_cfg_port.cpp).
Reply handle_cfg_prt(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_msg(HandlerContext& ctx, const FrameView& frame);
// Navigation (ubx_cfg_nav.cpp).
Reply handle_cfg_rate(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_nav5(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_gnss(HandlerContext& ctx, const FrameView& frame);
// Stored blocks (ubx_cfg_stored.cpp).
Reply handle_cfg_tp5(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_inf(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_dat(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_rinv(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_geofence(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_pwr(HandlerContext& ctx, const FrameView& frame);
/// Messages stored verbatim, set at one of stored_set_lengths(id).
Reply handle_cfg_stored(HandlerContext& ctx, const FrameView& frame);
// Saved configuration and resets (ubx_cfg_save.cpp).
Reply handle_cfg_cfg(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_rst(HandlerContext& ctx, const FrameView& frame);
// The configuration interface of protocol 27+ (ubx_cfg_val.cpp): answered
// when has_config_interface(ctx.generation), else as handle_cfg_unknown.
Reply handle_cfg_valset(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_valget(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_valdel(HandlerContext& ctx, const FrameView& frame);
// The ZED-F9P's legacy RTK and base messages (ubx_cfg_hpg.cpp): answered on
// an F9P, else as handle_cfg_unknown.
Reply handle_cfg_dgnss(HandlerContext& ctx, const FrameView& frame);
Reply handle_cfg_tmode3(HandlerContext& ctx, const FrameView& frame);
/// The generation has legacy CFG message id: an F9P dropped CFG-PM2,
/// CFG-RXM and CFG-PMS (its interface description lists no such message)
/// and an M8 or M9 lacks CFG-DGNSS and CFG-TMODE3.
bool cfg_message_exists(MsgId id, Generation g) noexcept;
// Everything else (ubx_handlers.cpp).
/// CFG ids an M8 lacks: CFG-VALSET/VALGET/VALDEL and the rest.
Reply handle_cfg_unknown(HandlerContext& ctx, const FrameView& frame);
Reply handle_mon_ver(HandlerContext& ctx, const FrameView& frame);
/// MON-GNSS poll: supported, default and enabled systems (ubx_gnss.hpp).
Reply handle_mon_gnss(HandlerContext& ctx, const FrameView& frame);
/// A poll of a NAV message, MON-HW, MON-HW2, MON-RF or SEC-SIG: the message from the
/// last epoch; ignored for a message the generation lacks.
Reply handle_output_poll(HandlerContext& ctx, const FrameView& frame);

}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/handlers/ubx_handlers.hpp"

#include "core/protocol/ubx/config/ubx_gnss.hpp"

namespace gnssemu::protocol::ubx {

namespace {

struct HandlerRow {
  MsgId id;
  Handler handle;
  std::array<std::uint16_t, 3> set_lengths{};  ///< handle_cfg_stored: accepted set lengths
};

constexpr HandlerRow kHandlers[] = {
    {msg::kCfgPrt, handle_cfg_prt},
    {msg::kCfgMsg, handle_cfg_msg},
    {msg::kCfgRate, handle_cfg_rate},
    {msg::kCfgNav5, handle_cfg_nav5},
    {msg::kCfgGnss, handle_cfg_gnss},
    {msg::kCfgTp5, handle_cfg_tp5},
    {msg::kCfgInf, handle_cfg_inf},
    {msg::kCfgDat, handle_cfg_dat},
    {msg::kCfgRinv, handle_cfg_rinv},
    {msg::kCfgGeofence, handle_cfg_geofence},
    {msg::kCfgPwr, handle_cfg_pwr},
    {msg::kCfgCfg, handle_cfg_cfg},
    {msg::kCfgRst, handle_cfg_rst},
    {msg::kCfgSbas, handle_cfg_stored, {8}},
    {msg::kCfgItfm, handle_cfg_stored, {8}},
    {msg::kCfgNavx5, handle_cfg_stored, {40, 44}},
    {msg::kCfgPm2, handle_cfg_stored, {44, 48}},
    {msg::kCfgRxm, handle_cfg_stored, {2}},
    {msg::kCfgUsb, handle_cfg_stored, {108}},
    {msg::kCfgAnt, handle_cfg_stored, {4}},
    {msg::kCfgOdo, handle_cfg_stored, {20}},
    {msg::kCfgNmea, handle_cfg_stored, {4, 12, 20}},
    {msg::kCfgPms, handle_cfg_stored, {8}},
    {msg::kCfgLogfilter, handle_cfg_stored, {12}},
    {msg::kCfgDgnss, handle_cfg_dgnss},
    {msg::kCfgTmode3, handle_cfg_tmode3},
    {msg::kCfgValset, handle_cfg_valset},
    {msg::kCfgValget, handle_cfg_valget},
    {msg::kCfgValdel, handle_cfg_valdel},
    {msg::kMonVer, handle_mon_ver},
    {msg::kMonGnss, handle_mon_gnss},
};

const HandlerRow* find_row(MsgId id) noexcept {
  for (const HandlerRow& r : kHandlers) {
    if (r.id == id) return &r;
  }
  return nullptr;
}

}  // namespace

Handler find_handler(MsgId id) noexcept {
  if (const HandlerRow* r = find_row(id)) return r->handle;
  if (id.cls == cls::kCfg) return handle_cfg_unknown;
  if (id.cls == cls::kNav || id == msg::kMonHw || id == msg::kMonHw2 || id == msg::kMonRf || id == msg::kSecSig) {
    return handle_output_poll;
  }
  return nullptr;
}

bool cfg_message_exists(MsgId id, Generation g) noexcept {
  if (id == msg::kCfgPm2 || id == msg::kCfgRxm || id == msg::kCfgPms) return g != Generation::kF9P;
  if (id == msg::kCfgDgnss || id == msg::kCfgTmode3) return g == Generation::kF9P;
  return true;
}

std::array<std::uint16_t, 3> stored_set_lengths(MsgId id) noexcept {
  const HandlerRow* r = find_row(id);
  return r != nullptr ? r->set_lengths : std::array<std::uint16_t, 3>{};
}

Reply ack(HandlerContext& ctx, MsgId id, bool ok) {
  UbxEncoder::ack(id, ok, ctx.out);
  return ok ? Reply::kAck : Reply::kNak;
}

Reply poll_reply(HandlerContext& ctx, MsgId id, std::span<const std::uint8_t> data) {
  append_frame(ctx.out, id, data);
  UbxEncoder::ack(id, true, ctx.out);
  return Reply::kPollData;
}

Reply handle_cfg_unknown(HandlerContext& ctx, const FrameView& frame) {
  // An M8 NAKs the CFG-VAL* interface of later generations (PX4 tells an M8
  // from an M9 that way) and every other CFG id it lacks.
  const MsgId id = frame.id;
  return ack(ctx, id, ctx.ack_unknown_cfg && id != msg::kCfgValset && id != msg::kCfgValget && id != msg::kCfgValdel);
}

Reply handle_mon_ver(HandlerContext& ctx, const FrameView& frame) {
  if (!frame.payload.empty()) return Reply::kNone;
  ctx.encoder.mon_ver(ctx.out);
  return Reply::kPollData;
}

Reply handle_mon_gnss(HandlerContext& ctx, const FrameView& frame) {
  if (!frame.payload.empty()) return Reply::kNone;
  UbxEncoder::mon_gnss(ctx.generation, enabled_systems(ctx.current), ctx.out);
  return Reply::kPollData;
}

Reply handle_output_poll(HandlerContext& ctx, const FrameView& frame) {
  // encode() writes nothing for an id the chip does not produce, including a
  // message its generation lacks (an unknown id to that firmware): no answer.
  if (!frame.payload.empty()) return Reply::kNone;
  return ctx.encoder.encode(frame.id, ctx.last_fix, ctx.info, ctx.out) > 0 ? Reply::kPollData : Reply::kNone;
}

}  // namespace gnssemu::protocol::ubx

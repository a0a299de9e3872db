// SPDX-License-Identifier: Apache-2.0
// CFG-PRT and CFG-MSG: port settings and message rates (UBX-13003221
// CFG-PRT, CFG-MSG). Port ids are the host's view: port 1 is its own UART1.
#include <algorithm>

#include "core/protocol/ubx/handlers/ubx_handlers.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"

namespace gnssemu::protocol::ubx {

namespace {

wire::CfgPrt to_wire(const PortSettings& s) noexcept {
  wire::CfgPrt w{};
  w.portID = s.port_id;
  w.txReady = s.tx_ready;
  w.mode = s.mode;
  w.baudRate = s.baud_bps;
  w.inProtoMask = s.in_proto_mask;
  w.outProtoMask = s.out_proto_mask;
  w.flags = s.flags;
  return w;
}

/// Classes whose messages CFG-MSG can rate: output messages only.
bool rateable_class(std::uint8_t cls) noexcept { return cls != cls::kAck && cls != cls::kCfg && cls != cls::kUpd; }

}  // namespace

Reply handle_cfg_prt(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  const MsgId id = frame.id;
  if (p.size() <= 1) {
    const std::uint8_t which = p.empty() ? ctx.port_id : p[0];
    if (which >= kNumPorts || !ctx.current.port(ctx.column(which)).exists) return ack(ctx, id, false);
    const wire::CfgPrt w = to_wire(ctx.current.port(ctx.column(which)));
    return poll_reply(ctx, id, {reinterpret_cast<const std::uint8_t*>(&w), sizeof w});
  }
  if (p.size() % sizeof(wire::CfgPrt) != 0) return ack(ctx, id, false);
  for (std::size_t off = 0; off < p.size(); off += sizeof(wire::CfgPrt)) {
    wire::CfgPrt w{};
    read_wire(p, w, off);
    if (w.portID >= kNumPorts || !ctx.current.port(ctx.column(w.portID)).exists) return ack(ctx, id, false);
    // A UART block must ask for what the emulated line can really be set
    // to: a standard u-blox baud and 8N1. Anything else would be ACKed and
    // then silently not applied (the daemon's lines run 8N1 at the standard
    // rates only), so it gets a NAK.
    if (is_uart(w.portID) && (!is_ubx_baud(w.baudRate) || !is_8n1(w.mode))) return ack(ctx, id, false);
  }
  for (std::size_t off = 0; off < p.size(); off += sizeof(wire::CfgPrt)) {
    wire::CfgPrt w{};
    read_wire(p, w, off);
    PortSettings& s = ctx.current.port(ctx.column(w.portID));
    s.tx_ready = w.txReady;
    s.mode = w.mode;
    if (is_uart(w.portID)) s.baud_bps = w.baudRate;
    s.in_proto_mask = w.inProtoMask;
    s.out_proto_mask = w.outProtoMask;
    s.flags = w.flags;
  }
  return ack(ctx, id, true);
}

Reply handle_cfg_msg(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  const MsgId id = frame.id;
  // A message the generation's firmware lacks cannot be rated or polled: NAK
  // (as an M9 NAKs the CFG-MSGOUT keys of messages it lacks, docs/ubx.md §Generations).
  if (p.size() >= 2 && !message_exists(MsgId{p[0], p[1]}, ctx.generation)) return ack(ctx, id, false);
  if (p.size() == 2) {
    const MsgId target{p[0], p[1]};
    if (!rateable_class(target.cls)) return ack(ctx, id, false);
    std::uint8_t data[2 + kNumPorts] = {p[0], p[1]};
    for (std::uint8_t port = 0; port < kNumPorts; ++port) data[2 + port] = ctx.current.message_rate(ctx.column(port), target);
    return poll_reply(ctx, id, data);
  }
  if ((p.size() != 3 && p.size() != 2 + kNumPorts) || !rateable_class(p[0])) return ack(ctx, id, false);
  const MsgId target{p[0], p[1]};
  if (p.size() == 3) return ack(ctx, id, ctx.current.set_message_rate(ctx.column(ctx.port_id), target, p[2]));
  // One rate per port; the table takes all or, when full, none of them (a
  // new id takes its row at its first non-zero rate).
  bool ok = true;
  for (std::uint8_t port = 0; port < kNumPorts; ++port) {
    ok = ctx.current.set_message_rate(ctx.column(port), target, p[2 + port]) && ok;
  }
  return ack(ctx, id, ok);
}

}  // namespace gnssemu::protocol::ubx

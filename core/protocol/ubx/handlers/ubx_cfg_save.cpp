// SPDX-License-Identifier: Apache-2.0
// CFG-CFG and CFG-RST: the saved configuration and resets (UBX-13003221
// CFG-CFG, CFG-RST). The configuration is the whole chip's, every UART1
// included: a host saves, loads and resets them all.
#include "core/protocol/ubx/handlers/ubx_handlers.hpp"

namespace gnssemu::protocol::ubx {

namespace {
constexpr std::size_t kRstBytes = sizeof(wire::CfgRst);
}  // namespace

Reply handle_cfg_cfg(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  if (p.size() != sizeof(wire::CfgCfg) && p.size() != sizeof(wire::CfgCfg) + 1) {  // + deviceMask, ignored
    return ack(ctx, frame.id, false);
  }
  wire::CfgCfg w{};
  read_wire(p, w);
  // In this order: clear (saved <- defaults), save (saved <- current), load (current <- saved).
  if (w.clearMask != 0) ctx.saved.copy_sections(ctx.defaults, w.clearMask);
  if (w.saveMask != 0) ctx.saved.copy_sections(ctx.current, w.saveMask);
  if (w.loadMask != 0) ctx.current.copy_sections(ctx.saved, w.loadMask);
  return ack(ctx, frame.id, true);
}

Reply handle_cfg_rst(HandlerContext& ctx, const FrameView& frame) {
  wire::CfgRst w{};
  const std::optional<Reset> reset =
      frame.payload.size() == kRstBytes && read_wire(frame.payload, w) ? Reset::from_wire(w) : std::nullopt;
  if (!reset) return ack(ctx, frame.id, false);
  // No answer: the receiver resets.
  ctx.reset = reset;
  if (reset->reloads_saved_config()) ctx.current = ctx.saved;
  return Reply::kReset;
}

}  // namespace gnssemu::protocol::ubx

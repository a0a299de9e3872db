// SPDX-License-Identifier: Apache-2.0
// CFG messages the emulated M8 keeps verbatim and returns on poll: the
// generic ones (handle_cfg_stored, lengths in the handler table) and those
// with an index or a poll form of their own (UBX-13003221 CFG-TP5, CFG-INF,
// CFG-DAT, CFG-RINV, CFG-GEOFENCE); CFG-PWR is a command.
#include <algorithm>

#include "core/protocol/ubx/handlers/ubx_handlers.hpp"

namespace gnssemu::protocol::ubx {

namespace {

constexpr std::size_t kTp5Bytes = 32;
constexpr std::size_t kInfBlockBytes = 10;
constexpr std::size_t kDatSetBytes = 44;
constexpr std::size_t kMaxRinvBytes = 31;
constexpr std::uint8_t kMaxFences = 4;
constexpr std::size_t kPwrBytes = 8;

/// Poll answer with the stored (id, index), or NAK when there is none.
Reply poll_stored(HandlerContext& ctx, MsgId id, std::uint8_t index) {
  const StoredBlock* b = ctx.current.stored(id, index);
  if (b == nullptr) return ack(ctx, id, false);
  return poll_reply(ctx, id, b->payload());
}

}  // namespace

Reply handle_cfg_tp5(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  if (p.size() <= 1) return poll_stored(ctx, frame.id, p.empty() ? 0 : p[0]);  // tpIdx
  if (p.size() != kTp5Bytes || p[0] > 1) return ack(ctx, frame.id, false);
  ctx.current.store(frame.id, p[0], p);
  return ack(ctx, frame.id, true);
}

Reply handle_cfg_inf(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  if (p.size() == 1) return poll_stored(ctx, frame.id, p[0]);  // protocolID
  if (p.empty() || p.size() % kInfBlockBytes != 0) return ack(ctx, frame.id, false);
  for (std::size_t off = 0; off < p.size(); off += kInfBlockBytes) {
    if (p[off] > 1) return ack(ctx, frame.id, false);  // 0 UBX, 1 NMEA
  }
  for (std::size_t off = 0; off < p.size(); off += kInfBlockBytes) {
    ctx.current.store(frame.id, p[off], p.subspan(off, kInfBlockBytes));
  }
  return ack(ctx, frame.id, true);
}

Reply handle_cfg_dat(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  if (p.empty()) return poll_stored(ctx, frame.id, 0);
  if (p.size() != kDatSetBytes) return ack(ctx, frame.id, false);
  // A set carries the user datum; the poll form adds datumNum and name.
  std::uint8_t poll[8 + kDatSetBytes] = {0xFF, 0xFF, 'U', 'S', 'E', 'R', 0, 0};
  std::copy(p.begin(), p.end(), poll + 8);
  ctx.current.store(frame.id, 0, poll);
  return ack(ctx, frame.id, true);
}

Reply handle_cfg_rinv(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  if (p.empty()) return poll_stored(ctx, frame.id, 0);
  if (p.size() > kMaxRinvBytes) return ack(ctx, frame.id, false);
  ctx.current.store(frame.id, 0, p);
  return ack(ctx, frame.id, true);
}

Reply handle_cfg_geofence(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  if (p.empty()) return poll_stored(ctx, frame.id, 0);
  // 8-byte header with numFences, then 12 bytes per fence.
  if (p.size() < 8 || p[1] > kMaxFences || p.size() != 8u + 12u * p[1]) return ack(ctx, frame.id, false);
  ctx.current.store(frame.id, 0, p);
  return ack(ctx, frame.id, true);
}

Reply handle_cfg_pwr(HandlerContext& ctx, const FrameView& frame) {
  return ack(ctx, frame.id, frame.payload.size() == kPwrBytes);  // command: run/stop/backup; nothing to store
}

Reply handle_cfg_stored(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  const StoredBlock* cur = ctx.current.stored(frame.id);
  if (p.empty()) return poll_reply(ctx, frame.id, cur->payload());
  const auto lengths = stored_set_lengths(frame.id);  // p is not empty: the zeros ending the list never match
  if (std::find(lengths.begin(), lengths.end(), p.size()) == lengths.end()) return ack(ctx, frame.id, false);
  if (frame.id == msg::kCfgNmea && p.size() < cur->size) {
    // Older, shorter CFG-NMEA forms set a prefix of the fields.
    std::array<std::uint8_t, kMaxStoredBytes> merged = cur->bytes;
    std::copy(p.begin(), p.end(), merged.begin());
    ctx.current.store(frame.id, 0, {merged.data(), cur->size});
  } else {
    ctx.current.store(frame.id, 0, p);
  }
  return ack(ctx, frame.id, true);
}

}  // namespace gnssemu::protocol::ubx

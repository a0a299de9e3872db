// SPDX-License-Identifier: Apache-2.0
// CFG-RATE, CFG-NAV5 and CFG-GNSS: the navigation settings of the chip
// (UBX-13003221 CFG-RATE, CFG-NAV5, CFG-GNSS).
#include <algorithm>

#include "core/protocol/ubx/config/ubx_gnss.hpp"
#include "core/protocol/ubx/handlers/ubx_handlers.hpp"

namespace gnssemu::protocol::ubx {

namespace {

constexpr std::uint16_t kMinMeasRate_ms = 25;  // M8: up to 40 Hz measurement rate (GPS only)
constexpr std::uint16_t kMaxNavRate = 127;
constexpr std::uint8_t kMaxGnssBlocks = 7;

/// NAV5 dynModel values an M8 accepts (1 is reserved).
bool dyn_model_ok(std::uint8_t m) noexcept { return m == 0 || (m >= 2 && m <= 9); }

/// Apply the fields of a CFG-NAV5 set that its mask selects.
void apply_nav5(wire::CfgNav5& cur, const wire::CfgNav5& in) noexcept {
  const std::uint16_t m = in.mask;
  if (m & 0x0001) cur.dynModel = in.dynModel;
  if (m & 0x0002) cur.minElev = in.minElev;
  if (m & 0x0004) {
    cur.fixMode = in.fixMode;
    cur.fixedAlt = in.fixedAlt;
    cur.fixedAltVar = in.fixedAltVar;
  }
  if (m & 0x0008) cur.drLimit = in.drLimit;
  if (m & 0x0010) {
    cur.pDop = in.pDop;
    cur.pAcc = in.pAcc;
  }
  if (m & 0x0020) {
    cur.tDop = in.tDop;
    cur.tAcc = in.tAcc;
  }
  if (m & 0x0040) {
    cur.staticHoldThresh = in.staticHoldThresh;
    cur.staticHoldMaxDist = in.staticHoldMaxDist;
  }
  if (m & 0x0080) cur.dgnssTimeout = in.dgnssTimeout;
  if (m & 0x0100) {
    cur.cnoThreshNumSVs = in.cnoThreshNumSVs;
    cur.cnoThresh = in.cnoThresh;
  }
  if (m & 0x0400) cur.utcStandard = in.utcStandard;
  cur.mask = 0xFFFF;  // a poll reports every field
}

}  // namespace

Reply handle_cfg_rate(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  wire::CfgRate& rate = ctx.current.rate;
  if (p.empty()) return poll_reply(ctx, frame.id, {reinterpret_cast<const std::uint8_t*>(&rate), sizeof rate});
  if (p.size() != sizeof(wire::CfgRate)) return ack(ctx, frame.id, false);
  wire::CfgRate w{};
  read_wire(p, w);
  const bool ok = w.measRate >= kMinMeasRate_ms && w.navRate >= 1 && w.navRate <= kMaxNavRate && w.timeRef <= 4;
  if (ok) rate = w;
  return ack(ctx, frame.id, ok);
}

Reply handle_cfg_nav5(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  wire::CfgNav5& nav5 = ctx.current.nav5;
  if (p.empty()) return poll_reply(ctx, frame.id, {reinterpret_cast<const std::uint8_t*>(&nav5), sizeof nav5});
  if (p.size() != sizeof(wire::CfgNav5)) return ack(ctx, frame.id, false);
  wire::CfgNav5 w{};
  read_wire(p, w);
  const bool ok = (!(w.mask & 0x0001) || dyn_model_ok(w.dynModel)) && (!(w.mask & 0x0004) || (w.fixMode >= 1 && w.fixMode <= 3));
  if (ok) apply_nav5(nav5, w);
  return ack(ctx, frame.id, ok);
}

Reply handle_cfg_gnss(HandlerContext& ctx, const FrameView& frame) {
  const auto p = frame.payload;
  const StoredBlock* cur = ctx.current.stored(msg::kCfgGnss);
  if (p.empty()) return poll_reply(ctx, frame.id, cur->payload());
  // msgVer 0, numConfigBlocks 1..7, 8 bytes per block.
  if (p.size() < 4 || p[0] != 0 || p[3] < 1 || p[3] > kMaxGnssBlocks || p.size() != 4u + 8u * p[3]) {
    return ack(ctx, frame.id, false);
  }
  // Merge the given blocks by gnssId into the stored set (an M8 keeps the
  // systems a host does not mention), then judge the whole: a configuration
  // the chip cannot run is NAKed and the old one kept (UBX-13003221 CFG-GNSS).
  std::array<std::uint8_t, kMaxStoredBytes> merged{};
  std::copy(cur->bytes.begin(), cur->bytes.begin() + cur->size, merged.begin());
  std::size_t n = merged[3];
  for (std::size_t b = 0; b < p[3]; ++b) {
    const std::uint8_t* blk = p.data() + 4 + 8 * b;
    if (blk[0] > kMaxCfgGnssId) return ack(ctx, frame.id, false);
    std::size_t slot = n;
    for (std::size_t k = 0; k < n; ++k) {
      if (merged[4 + 8 * k] == blk[0]) slot = k;
    }
    if (slot == kMaxGnssBlocks) return ack(ctx, frame.id, false);
    if (slot == n) ++n;
    std::copy(blk, blk + 8, merged.begin() + 4 + 8 * slot);
  }
  // numTrkChUse: 0xFF = all the hardware has; 0 keeps the current value.
  if (p[2] == 0xFF) merged[2] = merged[1];
  else if (p[2] != 0) merged[2] = p[2];
  merged[3] = static_cast<std::uint8_t>(n);
  const std::span<const std::uint8_t> config{merged.data(), 4 + 8 * n};
  if (!cfg_gnss_valid(config, ctx.generation)) return ack(ctx, frame.id, false);
  ctx.current.store(msg::kCfgGnss, 0, config);
  return ack(ctx, frame.id, true);
}

}  // namespace gnssemu::protocol::ubx

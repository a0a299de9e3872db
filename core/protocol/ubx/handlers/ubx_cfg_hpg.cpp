// SPDX-License-Identifier: Apache-2.0
// CFG-DGNSS and CFG-TMODE3: the ZED-F9P's legacy messages for its RTK mode
// and base-station position (UBX-18010854 CFG-DGNSS, CFG-TMODE3; deprecated
// since protocol 23.01 but answered by HPG 1.32). They read and write the
// CFG-NAVHPG-DGNSSMODE and CFG-TMODE-* keys, so both interfaces see one
// configuration. Other generations NAK them as CFG ids they lack.
#include <array>

#include "core/protocol/ubx/config/ubx_config_keys.hpp"
#include "core/protocol/ubx/handlers/ubx_handlers.hpp"

namespace gnssemu::protocol::ubx {

namespace {

constexpr std::uint32_t kDgnssMode = 0x20140011, kTmodeMode = 0x20030001, kTmodePosType = 0x20030002,
                        kTmodeEcefX = 0x40030003, kTmodeEcefXHp = 0x20030006, kTmodeLat = 0x40030009,
                        kTmodeLatHp = 0x2003000C, kTmodeFixedAcc = 0x4003000F, kTmodeSvinDur = 0x40030010,
                        kTmodeSvinAcc = 0x40030011;
constexpr std::size_t kTmode3Bytes = 40;

/// Write value to key id of the RAM configuration when valid; false otherwise.
bool write_key(HandlerContext& ctx, DeviceConfig& staged, std::uint32_t id, std::uint64_t value) noexcept {
  const ConfigKey* k = find_config_key(id, ctx.generation);
  return k != nullptr && valid_config_value(*k, value) && write_config_key(*k, staged, ctx.uart, value);
}

std::uint64_t read_key(const HandlerContext& ctx, std::uint32_t id) noexcept {
  const ConfigKey* k = find_config_key(id, ctx.generation);
  return k != nullptr ? read_config_key(*k, ctx.current, ctx.uart) : 0;
}

}  // namespace

Reply handle_cfg_dgnss(HandlerContext& ctx, const FrameView& frame) {
  if (ctx.generation != Generation::kF9P) return handle_cfg_unknown(ctx, frame);
  const auto p = frame.payload;
  if (p.empty()) {
    const std::array<std::uint8_t, 4> data{static_cast<std::uint8_t>(read_key(ctx, kDgnssMode)), 0, 0, 0};
    return poll_reply(ctx, frame.id, data);
  }
  DeviceConfig& staged = ctx.transaction != nullptr ? ctx.transaction->scratch_ram : ctx.current;
  staged = ctx.current;
  if (p.size() != 4 || !write_key(ctx, staged, kDgnssMode, p[0])) return ack(ctx, frame.id, false);
  ctx.current = staged;
  return ack(ctx, frame.id, true);
}

Reply handle_cfg_tmode3(HandlerContext& ctx, const FrameView& frame) {
  if (ctx.generation != Generation::kF9P) return handle_cfg_unknown(ctx, frame);
  const auto p = frame.payload;
  if (p.empty()) {
    std::array<std::uint8_t, kTmode3Bytes> d{};
    const bool llh = read_key(ctx, kTmodePosType) != 0;
    const std::uint16_t flags = static_cast<std::uint16_t>(read_key(ctx, kTmodeMode) | (llh ? 0x100u : 0u));
    store_le(d, 2, 2, flags);
    const std::uint32_t pos = llh ? kTmodeLat : kTmodeEcefX, hp = llh ? kTmodeLatHp : kTmodeEcefXHp;
    for (std::uint32_t i = 0; i < 3; ++i) {
      store_le(d, 4 + 4 * i, 4, read_key(ctx, pos + i));
      d[16 + i] = static_cast<std::uint8_t>(read_key(ctx, hp + i));
    }
    store_le(d, 20, 4, read_key(ctx, kTmodeFixedAcc));
    store_le(d, 24, 4, read_key(ctx, kTmodeSvinDur));
    store_le(d, 28, 4, read_key(ctx, kTmodeSvinAcc));
    return poll_reply(ctx, frame.id, d);
  }
  if (p.size() != kTmode3Bytes || p[0] != 0) return ack(ctx, frame.id, false);
  const std::uint64_t flags = load_le(p, 2, 2);
  const bool llh = (flags & 0x100) != 0;
  DeviceConfig& staged = ctx.transaction != nullptr ? ctx.transaction->scratch_ram : ctx.current;
  staged = ctx.current;
  bool ok = write_key(ctx, staged, kTmodeMode, flags & 0xFF) && write_key(ctx, staged, kTmodePosType, llh ? 1 : 0);
  const std::uint32_t pos = llh ? kTmodeLat : kTmodeEcefX, hp = llh ? kTmodeLatHp : kTmodeEcefXHp;
  for (std::uint32_t i = 0; i < 3 && ok; ++i) {
    ok = write_key(ctx, staged, pos + i, load_le(p, 4 + 4 * i, 4)) && write_key(ctx, staged, hp + i, p[16 + i]);
  }
  ok = ok && write_key(ctx, staged, kTmodeFixedAcc, load_le(p, 20, 4)) &&
       write_key(ctx, staged, kTmodeSvinDur, load_le(p, 24, 4)) && write_key(ctx, staged, kTmodeSvinAcc, load_le(p, 28, 4));
  if (ok) ctx.current = staged;
  return ack(ctx, frame.id, ok);
}

}  // namespace gnssemu::protocol::ubx

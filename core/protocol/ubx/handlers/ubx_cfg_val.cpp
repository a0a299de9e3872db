// SPDX-License-Identifier: Apache-2.0
// CFG-VALSET, CFG-VALGET and CFG-VALDEL: the configuration interface of
// protocol 27 and later (u-blox ZED-F9P Interface Description UBX-18010854
// §5.9 UBX-CFG-VALDEL/VALGET/VALSET, §6 configuration keys and layers). An
// M8 NAKs all three (handle_cfg_unknown). Layers: RAM is the current
// configuration, BBR and Flash the one saved configuration (CFG-CFG's), the
// default layer the factory one. Behaviour: docs/ubx.md §Configuration interface.
#include <algorithm>

#include "core/protocol/ubx/config/ubx_config_keys.hpp"
#include "core/protocol/ubx/config/ubx_gnss.hpp"
#include "core/protocol/ubx/handlers/ubx_handlers.hpp"

namespace gnssemu::protocol::ubx {

namespace {

constexpr std::size_t kMaxKeysPerMessage = 64;  // UBX-18010854 CFG-VALSET/VALGET/VALDEL: N <= 64
constexpr std::uint8_t kLayerRam = 0x01, kLayerBbr = 0x02, kLayerFlash = 0x04;
constexpr std::uint8_t kLayerSaved = kLayerBbr | kLayerFlash;
/// VALGET layer numbers (not bits).
constexpr std::uint8_t kGetRam = 0, kGetBbr = 1, kGetFlash = 2, kGetDefault = 7;
/// VALSET v1 transaction actions.
constexpr std::uint8_t kNoTransaction = 0, kStart = 1, kOngoing = 2, kApply = 3;

std::uint32_t u4_at(std::span<const std::uint8_t> p, std::size_t off) noexcept {
  return static_cast<std::uint32_t>(load_le(p, off, 4));
}

using Pairs = std::span<const ValTransaction::Pending>;

/// key/value pairs of a VALSET body (p from byte 4); false when a key is
/// unknown, a value is cut short or there are more than 64.
bool parse_pairs(std::span<const std::uint8_t> p, Generation g,
                 std::array<ValTransaction::Pending, kMaxKeysPerMessage>& out, std::size_t& n) noexcept {
  n = 0;
  std::size_t off = 0;
  while (off < p.size()) {
    if (off + 4 > p.size() || n == out.size()) return false;
    const std::uint32_t id = u4_at(p, off);
    const ConfigKey* k = find_config_key(id, g);
    if (k == nullptr) return false;
    const std::size_t len = k->value_bytes();
    if (off + 4 + len > p.size()) return false;
    out[n++] = {id, load_le(p, off + 4, len)};
    off += 4 + len;
  }
  return true;
}

/// Write pairs into staged (a copy of cfg); false when one does not go in.
bool stage(const DeviceConfig& cfg, DeviceConfig& staged, std::size_t uart, Pairs pairs) noexcept {
  staged = cfg;
  for (const auto& [id, value] : pairs) {
    if (!write_config_key(*find_config_key(id), staged, uart, value)) return false;
  }
  return true;
}

/// Validate and apply to the layers: every pair in every layer, or nothing.
/// Values are checked for every layer, not only RAM as u-blox does: a value
/// the emulator cannot run would come back with the next CFG-CFG load.
bool apply_pairs(HandlerContext& ctx, std::uint8_t layers, Pairs pairs) noexcept {
  for (const auto& [id, value] : pairs) {
    if (!valid_config_value(*find_config_key(id), value)) return false;
  }
  ValTransaction& t = *ctx.transaction;
  if ((layers & kLayerSaved) && !stage(ctx.saved, t.scratch, ctx.uart, pairs)) return false;
  if ((layers & kLayerRam) && !stage(ctx.current, t.scratch_ram, ctx.uart, pairs)) return false;
  // The CFG-SIGNAL keys must leave a signal configuration the chip can run
  // (at least one major GNSS and a signal per enabled system); else the
  // whole VALSET is NAKed (PX4-GPSDrivers#225: "rejected as a whole").
  const auto gnss_ok = [&](const DeviceConfig& c) {
    const StoredBlock* b = c.stored(msg::kCfgGnss);
    return b == nullptr || cfg_gnss_valid(b->payload(), ctx.generation);
  };
  if ((layers & kLayerSaved) && !gnss_ok(t.scratch)) return false;
  if ((layers & kLayerRam) && !gnss_ok(t.scratch_ram)) return false;
  if (layers & kLayerSaved) ctx.saved = t.scratch;
  if (layers & kLayerRam) ctx.current = t.scratch_ram;
  return true;
}

/// Add pairs to the open transaction (last value per key wins).
bool add_pending(ValTransaction& t, Pairs pairs) noexcept {
  for (const auto& pr : pairs) {
    const auto end = t.pending.begin() + static_cast<std::ptrdiff_t>(t.size);
    const auto it =
        std::find_if(t.pending.begin(), end, [&](const ValTransaction::Pending& q) { return q.key == pr.key; });
    if (it != end) {
      it->value = pr.value;
    } else {
      if (t.size == t.pending.size()) return false;
      t.pending[t.size++] = pr;
    }
  }
  return true;
}

/// Keys of a VALGET/VALDEL body (from byte 4): 1..64, each known or a wildcard matching some key.
bool keys_ok(std::span<const std::uint8_t> p, Generation g) noexcept {
  if (p.empty() || p.size() % 4 != 0 || p.size() / 4 > kMaxKeysPerMessage) return false;
  for (std::size_t off = 0; off < p.size(); off += 4) {
    const std::uint32_t id = u4_at(p, off);
    if (!is_key_wildcard(id)) {
      if (find_config_key(id, g) == nullptr) return false;
      continue;
    }
    const auto keys = config_keys();
    if (std::none_of(keys.begin(), keys.end(), [&](const ConfigKey& k) { return k.exists_on(g) && key_matches(id, k.id); })) {
      return false;
    }
  }
  return true;
}

Reply nak_cancel(HandlerContext& ctx, MsgId id) {
  if (ctx.transaction != nullptr) ctx.transaction->cancel();
  return ack(ctx, id, false);
}

}  // namespace

Reply handle_cfg_valset(HandlerContext& ctx, const FrameView& frame) {
  if (!has_config_interface(ctx.generation) || ctx.transaction == nullptr) return handle_cfg_unknown(ctx, frame);
  const auto p = frame.payload;
  const MsgId id = frame.id;
  if (p.size() < 4 || p[0] > 1) return nak_cancel(ctx, id);
  const std::uint8_t layers = p[1];
  const std::uint8_t action = p[0] == 1 ? p[2] : kNoTransaction;
  if (layers == 0 || (layers & ~(kLayerRam | kLayerSaved)) != 0 || action > kApply) return nak_cancel(ctx, id);
  std::array<ValTransaction::Pending, kMaxKeysPerMessage> pairs{};
  std::size_t n = 0;
  if (!parse_pairs(p.subspan(4), ctx.generation, pairs, n)) return nak_cancel(ctx, id);
  const Pairs these{pairs.data(), n};
  ValTransaction& t = *ctx.transaction;
  switch (action) {
    case kNoTransaction:
      t.cancel();  // a transaction-less set ends any started transaction
      return ack(ctx, id, apply_pairs(ctx, layers, these));
    case kStart:
      t.cancel();
      t.open = true;
      t.layers = layers;
      return add_pending(t, these) ? ack(ctx, id, true) : nak_cancel(ctx, id);
    default: {
      // Ongoing and apply need a started transaction with the same layers.
      if (!t.open || t.layers != layers || !add_pending(t, these)) return nak_cancel(ctx, id);
      if (action == kOngoing) return ack(ctx, id, true);
      const bool ok = apply_pairs(ctx, layers, {t.pending.data(), t.size});
      t.cancel();
      return ack(ctx, id, ok);
    }
  }
}

Reply handle_cfg_valget(HandlerContext& ctx, const FrameView& frame) {
  if (!has_config_interface(ctx.generation)) return handle_cfg_unknown(ctx, frame);
  const auto p = frame.payload;
  const MsgId id = frame.id;
  if (p.size() < 4 || p[0] != 0 || !keys_ok(p.subspan(4), ctx.generation)) return ack(ctx, id, false);
  const std::uint8_t layer = p[1];
  const DeviceConfig* src = layer == kGetRam                          ? &ctx.current
                            : layer == kGetBbr || layer == kGetFlash ? &ctx.saved
                            : layer == kGetDefault                    ? &ctx.defaults
                                                                      : nullptr;
  if (src == nullptr) return ack(ctx, id, false);
  const std::size_t position = static_cast<std::size_t>(load_le(p, 2, 2));
  // Reply: version 1, layer, position, then key/value pairs: at most 64 per
  // message; a host pages through a longer answer with position (values to skip).
  std::array<std::uint8_t, 4 + kMaxKeysPerMessage * 12> reply{};
  reply[0] = 1;
  reply[1] = layer;
  reply[2] = p[2];
  reply[3] = p[3];
  std::size_t len = 4, index = 0, emitted = 0;
  for (std::size_t off = 4; off < p.size() && emitted < kMaxKeysPerMessage; off += 4) {
    const std::uint32_t want = u4_at(p, off);
    for (const ConfigKey& k : config_keys()) {
      if (!k.exists_on(ctx.generation) || !key_matches(want, k.id)) continue;
      if (index++ < position) continue;
      if (emitted == kMaxKeysPerMessage) break;
      const std::uint64_t v = read_config_key(k, *src, ctx.uart);
      store_le(reply, len, 4, k.id);
      store_le(reply, len + 4, k.value_bytes(), v);
      len += 4 + k.value_bytes();
      ++emitted;
    }
  }
  if (emitted == 0) return ack(ctx, id, false);  // position beyond the answer
  return poll_reply(ctx, id, {reply.data(), len});
}

Reply handle_cfg_valdel(HandlerContext& ctx, const FrameView& frame) {
  if (!has_config_interface(ctx.generation) || ctx.transaction == nullptr) return handle_cfg_unknown(ctx, frame);
  const auto p = frame.payload;
  const MsgId id = frame.id;
  // Version 0, or 1 without a transaction (VALDEL transactions are not modelled: NAK).
  if (p.size() < 4 || p[0] > 1 || (p[0] == 1 && p[2] != 0) || !keys_ok(p.subspan(4), ctx.generation)) return ack(ctx, id, false);
  const std::uint8_t layers = p[1];
  if ((layers & kLayerSaved) == 0 || (layers & ~kLayerSaved) != 0) return ack(ctx, id, false);
  // Deleting from BBR/Flash reverts the saved value to the default.
  DeviceConfig& staged = ctx.transaction->scratch;
  staged = ctx.saved;
  for (std::size_t off = 4; off < p.size(); off += 4) {
    const std::uint32_t want = u4_at(p, off);
    for (const ConfigKey& k : config_keys()) {
      if (!k.exists_on(ctx.generation) || !key_matches(want, k.id)) continue;
      if (!write_config_key(k, staged, ctx.uart, read_config_key(k, ctx.defaults, ctx.uart))) {
        return ack(ctx, id, false);
      }
    }
  }
  ctx.saved = staged;
  return ack(ctx, id, true);
}

}  // namespace gnssemu::protocol::ubx

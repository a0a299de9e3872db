// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/config/ubx_gnss.hpp"

#include <algorithm>

#include "core/common/gnss_systems.hpp"
#include "core/protocol/ubx/config/ubx_device_config.hpp"

namespace gnssemu::protocol::ubx {

namespace {

constexpr std::size_t kHeadBytes = 4, kBlockBytes = 8;
constexpr std::uint32_t kEnable = 0x01;
constexpr std::uint8_t kMinMajorMaxTrk = 4;  // maxTrkCh of an enabled major GNSS (M8 spec, CFG-GNSS)

constexpr SystemSet set_of(std::initializer_list<GnssSystem> systems) {
  SystemSet s;
  for (const GnssSystem g : systems) s = s.with(g);
  return s;
}

using enum GnssSystem;
// sigCfgMask per gnssId (GPS, SBAS, Galileo, BeiDou, IMES, QZSS, GLONASS): L1-band only on
// both; the M8 has QZSS L1SAIF (0x04) and IMES, the NEO-M9N neither (its MON-VER lists
// "SBAS;QZSS"; L1S is CFG-QZSS there, PX4-GPSDrivers#225).
constexpr GnssCapabilities kM8{32, 3, 0x7F, {0x01, 0x01, 0x01, 0x01, 0x01, 0x05, 0x01},
                               set_of({kGps, kGlonass, kGalileo, kBeiDou, kQzss, kSbas}),
                               set_of({kGps, kGlonass, kQzss, kSbas})};
constexpr GnssCapabilities kM9{32, 4, 0x6F, {0x01, 0x01, 0x01, 0x01, 0x00, 0x01, 0x01},
                               set_of({kGps, kGlonass, kGalileo, kBeiDou, kQzss, kSbas}),
                               set_of({kGps, kGlonass, kGalileo, kBeiDou, kQzss, kSbas})};
// ZED-F9P: L1 and L2 band (GPS L2C 0x10, Galileo E5b 0x20, BeiDou B2I 0x10, QZSS L1S 0x04
// and L2C 0x10, GLONASS L2OF 0x10; ZED-F9P interface description UBX-18010854, legacy
// CFG-GNSS sigCfgMask); its integration manual UBX-18010802 §3.1.2 enables every system
// on both bands from the factory.
constexpr GnssCapabilities kF9P{60, 4, 0x6F, {0x11, 0x01, 0x21, 0x11, 0x00, 0x15, 0x11},
                                set_of({kGps, kGlonass, kGalileo, kBeiDou, kQzss, kSbas}),
                                set_of({kGps, kGlonass, kGalileo, kBeiDou, kQzss, kSbas})};

// Factory CFG-GNSS: channel counts as u-center's defaults (PX4-GPSDrivers ubx.cpp), flags
// 0x01010001 = L1 signal on + enable; 0x01010000 the same signal, disabled.
constexpr std::uint8_t kM8Factory[] = {
    0, 32, 32, 7,                                //
    0, 8, 16, 0, 0x01, 0x00, 0x01, 0x01,         // GPS L1C/A
    1, 1, 3, 0, 0x01, 0x00, 0x01, 0x01,          // SBAS L1C/A
    2, 4, 8, 0, 0x00, 0x00, 0x01, 0x01,          // Galileo E1 (off)
    3, 8, 16, 0, 0x00, 0x00, 0x01, 0x01,         // BeiDou B1I (off)
    4, 0, 8, 0, 0x00, 0x00, 0x01, 0x01,          // IMES L1 (off)
    5, 0, 3, 0, 0x01, 0x00, 0x01, 0x01,          // QZSS L1C/A
    6, 8, 14, 0, 0x01, 0x00, 0x01, 0x01,         // GLONASS L1OF
};
constexpr std::uint8_t kM9Factory[] = {
    0, 32, 32, 6,                                //
    0, 8, 16, 0, 0x01, 0x00, 0x01, 0x01,         // GPS L1C/A
    1, 1, 3, 0, 0x01, 0x00, 0x01, 0x01,          // SBAS L1C/A
    2, 4, 8, 0, 0x01, 0x00, 0x01, 0x01,          // Galileo E1
    3, 8, 16, 0, 0x01, 0x00, 0x01, 0x01,         // BeiDou B1I
    5, 0, 3, 0, 0x01, 0x00, 0x01, 0x01,          // QZSS L1C/A
    6, 8, 14, 0, 0x01, 0x00, 0x01, 0x01,         // GLONASS L1OF
};

constexpr std::uint8_t kF9PFactory[] = {
    0, 60, 60, 6,                                //
    0, 8, 16, 0, 0x01, 0x00, 0x11, 0x01,         // GPS L1C/A + L2C
    1, 1, 3, 0, 0x01, 0x00, 0x01, 0x01,          // SBAS L1C/A
    2, 4, 12, 0, 0x01, 0x00, 0x21, 0x01,         // Galileo E1 + E5b
    3, 8, 16, 0, 0x01, 0x00, 0x11, 0x01,         // BeiDou B1I + B2I
    5, 0, 4, 0, 0x01, 0x00, 0x11, 0x01,          // QZSS L1C/A + L2C
    6, 8, 12, 0, 0x01, 0x00, 0x11, 0x01,         // GLONASS L1OF + L2OF
};

struct Block {
  std::uint8_t gnss_id, res, max;
  std::uint32_t flags;
  bool enabled() const noexcept { return (flags & kEnable) != 0; }
  std::uint8_t signals() const noexcept { return static_cast<std::uint8_t>(flags >> 16); }
};

std::size_t num_blocks(std::span<const std::uint8_t> p) noexcept {
  return p.size() < kHeadBytes ? 0 : std::min<std::size_t>(p[3], (p.size() - kHeadBytes) / kBlockBytes);
}

Block block(std::span<const std::uint8_t> p, std::size_t i) noexcept {
  const std::uint8_t* b = p.data() + kHeadBytes + kBlockBytes * i;
  const std::uint32_t flags = static_cast<std::uint32_t>(b[4]) | static_cast<std::uint32_t>(b[5]) << 8 |
                              static_cast<std::uint32_t>(b[6]) << 16 | static_cast<std::uint32_t>(b[7]) << 24;
  return {b[0], b[1], b[2], flags};
}

}  // namespace

std::optional<GnssSystem> system_of_gnss_id(std::uint8_t gnss_id) noexcept {
  for (const SystemInfo& s : kSystems) {
    if (s.ubx_gnss_id == gnss_id) return s.system;
  }
  return std::nullopt;
}

const GnssCapabilities& gnss_capabilities(Generation g) noexcept {
  return g == Generation::kF9P ? kF9P : g == Generation::kM9 ? kM9 : kM8;
}

std::span<const std::uint8_t> factory_cfg_gnss(Generation g) noexcept {
  if (g == Generation::kF9P) return kF9PFactory;
  if (g == Generation::kM9) return kM9Factory;
  return kM8Factory;
}

bool cfg_gnss_valid(std::span<const std::uint8_t> p, Generation g) noexcept {
  const GnssCapabilities& cap = gnss_capabilities(g);
  if (p.size() < kHeadBytes || p[0] != 0) return false;
  const std::size_t n = num_blocks(p);
  if (p.size() != kHeadBytes + kBlockBytes * n) return false;
  const unsigned use = p[2];
  if (use > cap.num_trk_ch_hw) return false;
  unsigned reserved = 0, majors = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Block b = block(p, i);
    if (b.gnss_id > kMaxCfgGnssId) return false;
    if (!b.enabled()) continue;
    if (!(cap.gnss_ids >> b.gnss_id & 1u)) return false;
    const std::uint8_t has = cap.signals[b.gnss_id];
    if ((b.signals() & has) == 0 || (b.signals() & ~has) != 0) return false;
    // A second-band signal needs its L1-band one (ZED-F9P integration manual
    // UBX-18010802 §3.1.2: L2/E5b alone is no configuration the F9P runs).
    if (is_dual_band(g) && (b.signals() & 0x01) == 0) return false;
    const unsigned min_max = is_major_gnss_id(b.gnss_id) ? kMinMajorMaxTrk : 1u;
    if (b.max < std::max<unsigned>(b.res, min_max) || b.max > use) return false;
    reserved += b.res;
    if (is_major_gnss_id(b.gnss_id)) ++majors;
  }
  return reserved <= use && majors >= 1 && majors <= cap.max_major;
}

SystemSet enabled_systems(std::span<const std::uint8_t> p) noexcept {
  SystemSet s;
  for (std::size_t i = 0; i < num_blocks(p); ++i) {
    const Block b = block(p, i);
    const auto sys = system_of_gnss_id(b.gnss_id);
    if (sys && b.enabled() && b.signals() != 0) s = s.with(*sys);
  }
  return s;
}

SystemSet enabled_systems(const DeviceConfig& c) noexcept {
  const StoredBlock* b = c.stored(msg::kCfgGnss);
  return b != nullptr ? enabled_systems(b->payload()) : SystemSet();
}

ChannelLimits channel_limits(std::span<const std::uint8_t> p, Generation g) noexcept {
  ChannelLimits lim;
  const int hw = gnss_capabilities(g).num_trk_ch_hw;
  lim.total = p.size() < kHeadBytes || p[2] == 0xFF ? hw : std::min<int>(p[2], hw);
  for (std::size_t i = 0; i < num_blocks(p); ++i) {
    const Block b = block(p, i);
    const std::optional<GnssSystem> sys = system_of_gnss_id(b.gnss_id);
    if (sys && b.enabled() && b.signals() != 0) lim.per_system[static_cast<std::size_t>(*sys)] = std::min<int>(b.max, lim.total);
  }
  return lim;
}

ChannelLimits channel_limits(const DeviceConfig& c, Generation g) noexcept {
  const StoredBlock* b = c.stored(msg::kCfgGnss);
  return channel_limits(b != nullptr ? b->payload() : factory_cfg_gnss(g), g);
}

bool same_signals(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) noexcept {
  const auto covers = [](std::span<const std::uint8_t> x, std::span<const std::uint8_t> y) {
    for (std::size_t i = 0; i < num_blocks(x); ++i) {
      const Block bx = block(x, i);
      bool found = false;
      for (std::size_t j = 0; j < num_blocks(y) && !found; ++j) {
        const Block by = block(y, j);
        found = by.gnss_id == bx.gnss_id && (by.flags & 0x00FF0001u) == (bx.flags & 0x00FF0001u);
      }
      if (!found) return false;
    }
    return true;
  };
  return covers(a, b) && covers(b, a);
}

std::uint8_t mon_gnss_bits(SystemSet s) noexcept {
  return static_cast<std::uint8_t>((s.has(kGps) ? 0x01 : 0) | (s.has(kGlonass) ? 0x02 : 0) |
                                   (s.has(kBeiDou) ? 0x04 : 0) | (s.has(kGalileo) ? 0x08 : 0));
}

std::uint8_t svinfo_svid(SatId id) noexcept {
  if (!id.valid()) return 0;
  const int n = id.number;
  switch (id.system) {
    case kGps: return static_cast<std::uint8_t>(n);
    case kSbas: return static_cast<std::uint8_t>(id.prn());
    case kGalileo: return static_cast<std::uint8_t>(210 + n);
    case kBeiDou: return n <= 5 ? static_cast<std::uint8_t>(158 + n) : n <= 37 ? static_cast<std::uint8_t>(27 + n) : 0;
    case kQzss: return static_cast<std::uint8_t>(id.prn());
    case kGlonass: return n <= 32 ? static_cast<std::uint8_t>(64 + n) : 0;
  }
  return 0;
}

std::uint8_t ubx_sv_id(SatId id) noexcept {
  if (!id.valid()) return 0;
  return static_cast<std::uint8_t>(id.system == kSbas ? id.prn() : id.number);
}

NavRateLimits nav_rate_limits(Generation g, SystemSet enabled) noexcept {
  if (g == Generation::kM9) return {25.0, 8.0, 16};
  if (g == Generation::kF9P) return {kF9PMaxRtkRateHz, 1e9, kMaxSatsInView};
  int majors = 0;
  for (const GnssSystem s : {kGps, kGlonass, kGalileo, kBeiDou}) majors += enabled.has(s) ? 1 : 0;
  return {majors <= 1 ? 18.0 : 10.0, 1e9, kMaxSatsInView};
}

}  // namespace gnssemu::protocol::ubx

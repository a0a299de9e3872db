// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/config/ubx_device_config.hpp"

#include <algorithm>
#include <cstring>
#include <initializer_list>

#include "core/protocol/ubx/config/ubx_config_keys.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/protocol/ubx/config/ubx_gnss.hpp"

namespace gnssemu::protocol::ubx {

namespace {

// CFG-ITFM config word (M8 receiver description, UBX-CFG-ITFM): bbThreshold
// bits 0-3, cwThreshold bits 4-8, algorithmBits 9-30 (0x16B156, fixed by
// u-blox), enable bit 31.
constexpr std::uint32_t kFactoryItfmConfig = static_cast<std::uint32_t>(kFactoryItfmBbThreshold_db) |
                                             static_cast<std::uint32_t>(kFactoryItfmCwThreshold_db) << 4 |
                                             0x16B156u << 9;
static_assert(kFactoryItfmConfig == 0x2D62ACF3u, "the factory CFG-ITFM word of a u-blox M8");

/// Little-endian payload builder for the default blocks below.
struct Bytes {
  std::array<std::uint8_t, kMaxStoredBytes> b{};
  std::size_t n = 0;
  Bytes& u1(unsigned v) { b[n++] = static_cast<std::uint8_t>(v); return *this; }
  Bytes& u2(unsigned v) { return u1(v & 0xFF).u1(v >> 8 & 0xFF); }
  Bytes& u4(std::uint32_t v) { return u2(v & 0xFFFF).u2(v >> 16); }
  Bytes& zeros(std::size_t k) { n += k; return *this; }
  Bytes& str(const char* s, std::size_t field) {
    const std::size_t len = std::min(std::strlen(s), field);
    std::memcpy(b.data() + n, s, len);
    n += field;
    return *this;
  }
  Bytes& r8(double v) { std::memcpy(b.data() + n, &v, 8); n += 8; return *this; }
  Bytes& r4(float v) { std::memcpy(b.data() + n, &v, 4); n += 4; return *this; }
  std::span<const std::uint8_t> span() const { return {b.data(), n}; }
};

/// CFG-CFG section of each stored block (UBX-13003221 CFG-CFG clearMask).
std::uint32_t section_of(MsgId id) noexcept {
  if (id == msg::kCfgUsb) return 1u << 0;        // ioPort
  if (id == msg::kCfgInf) return 1u << 2;        // infMsg
  if (id == msg::kCfgRxm || id == msg::kCfgPm2 || id == msg::kCfgPms || id == msg::kCfgItfm) return 1u << 4;  // rxmConf
  if (id == msg::kCfgRinv) return 1u << 9;       // rinvConf
  if (id == msg::kCfgAnt) return 1u << 10;       // antConf
  if (id == msg::kCfgLogfilter) return 1u << 11; // logConf
  return 1u << 3;                                // navConf: NAV5 NAVX5 GNSS SBAS TP5 ODO NMEA DAT GEOFENCE
}

}  // namespace

std::uint32_t DeviceConfig::factory_uart1_baud(Generation generation) noexcept {
  return generation == Generation::kM8 ? 9600 : 38400;
}

DeviceConfig DeviceConfig::factory_defaults(std::size_t uarts, Generation generation) {
  DeviceConfig c;
  // Ports (NEO-M8N: DDC, UART1, USB, SPI; no UART2). UART 8N1 = mode 0x8C0.
  c.ports_.resize(kNumPorts + std::max<std::size_t>(uarts, 1) - 1);
  c.rates_.assign(kMaxRateEntries * c.ports_.size(), 0);
  for (std::uint8_t p = 0; p < kNumPorts; ++p) c.ports_[p].port_id = p;
  const std::uint16_t in = proto::kUbx | proto::kNmea | proto::kRtcm2;
  const std::uint16_t out = proto::kUbx | proto::kNmea;
  const PortSettings uart1{kPortUart1, true, 0, 0x8C0, factory_uart1_baud(generation), in, out, 0, false};
  c.ports_[kPortDdc] = {kPortDdc, true, 0, 0x42u << 1, 0, in, out, 0, false};
  c.ports_[kPortUsb] = {kPortUsb, true, 0, 0, 0, in, out, 0, false};
  c.ports_[kPortSpi] = {kPortSpi, true, 0, 0x100, 0, in, out, 0, false};
  for (std::size_t u = 0; u < c.uarts(); ++u) c.ports_[c.column(u, kPortUart1)] = uart1;
  if (generation == Generation::kF9P) {
    // ZED-F9P: RTCM 3 in on every port (HPG 1.32 CFG-*INPROT-RTCM3X defaults).
    for (PortSettings& p : c.ports_)
      if (p.exists) p.in_proto_mask = static_cast<std::uint16_t>(p.in_proto_mask | proto::kRtcm3);
    // ZED-F9P UART2: 38400 8N1, RTCM 3 (and UBX) in, RTCM 3 out (HPG 1.32
    // CFG-UART2 and CFG-UART2IN/OUTPROT defaults; docs/ubx.md §ZED-F9P).
    c.ports_[kPortUart2] = {kPortUart2, true, 0, 0x8C0, 38400, proto::kUbx | proto::kRtcm3, proto::kRtcm3, 0, false};
  }
  // NMEA GGA GLL GSA GSV RMC VTG at 1 on every existing port; TXT is on too.
  for (MsgId id : {msg::kNmeaGga, msg::kNmeaGll, msg::kNmeaGsa, msg::kNmeaGsv, msg::kNmeaRmc, msg::kNmeaVtg}) {
    for (std::size_t col = 0; col < c.columns(); ++col) {
      if (c.ports_[col].exists) c.set_message_rate(col, id, 1);
    }
  }
  c.rate = {1000, 1, 1};  // 1 Hz, aligned to GPS time
  c.nav5 = {};
  c.nav5.mask = 0xFFFF;
  c.nav5.dynModel = 0;  // portable
  c.nav5.fixMode = 3;   // auto 2D/3D
  c.nav5.fixedAltVar = 10000;
  c.nav5.minElev = 5;
  c.nav5.pDop = 250;
  c.nav5.tDop = 250;
  c.nav5.pAcc = 100;
  c.nav5.tAcc = 350;
  c.nav5.dgnssTimeout = 60;

  Bytes b;
  c.store(msg::kCfgGnss, 0, factory_cfg_gnss(generation));
  b = {};  // CFG-SBAS: enabled, range + corrections, 3 channels, auto scan
  b.u1(1).u1(3).u1(3).u1(0).u4(0);
  c.store(msg::kCfgSbas, 0, b.span());
  b = {};  // CFG-TP5 TIMEPULSE: 1 Hz, 100 ms locked, 50 ns cable delay
  b.u1(0).u1(1).zeros(2).u2(50).u2(0).u4(1000000).u4(1000000).u4(0).u4(100000).u4(0).u4(0x77);
  c.store(msg::kCfgTp5, 0, b.span());
  b = {};  // CFG-TP5 TIMEPULSE2: inactive
  b.u1(1).u1(1).zeros(2).u2(50).u2(0).u4(4).u4(1).u4(0).u4(125000).u4(0).u4(0x76);
  c.store(msg::kCfgTp5, 1, b.span());
  b = {};  // CFG-INF UBX: nothing
  b.u1(0).zeros(3).zeros(6);
  c.store(msg::kCfgInf, 0, b.span());
  b = {};  // CFG-INF NMEA: ERROR WARNING NOTICE on DDC UART1 USB SPI
  b.u1(1).zeros(3).u1(7).u1(7).u1(0).u1(7).u1(7).u1(0);
  c.store(msg::kCfgInf, 1, b.span());
  b = {};  // CFG-ITFM: factory thresholds, monitor disabled
  b.u4(kFactoryItfmConfig).u4(0x0000031E);
  c.store(msg::kCfgItfm, 0, b.span());
  b = {};  // CFG-NAVX5 version 2
  b.u2(2).u2(0).u4(0).zeros(2).u1(3).u1(32).u1(6).zeros(1).u1(0).zeros(2).u1(0).u2(1867).u1(0)
      .zeros(5).u1(0).u1(0).zeros(2).u2(100).zeros(7).u1(0);
  c.store(msg::kCfgNavx5, 0, b.span());
  b = {};  // CFG-PM2 version 1
  b.u1(1).u1(0).u1(0).u1(0).u4(0x00029000).u4(1000).u4(10000).u4(0).u2(0).u2(0).zeros(20);
  c.store(msg::kCfgPm2, 0, b.span());
  b = {};  // CFG-RXM: continuous mode
  b.u1(8).u1(0);
  c.store(msg::kCfgRxm, 0, b.span());
  b = {};  // CFG-USB
  b.u2(0x1546).u2(0x01A8).zeros(2).u2(1).u2(0).u2(0)
      .str("u-blox AG - www.u-blox.com", 32).str("u-blox GNSS receiver", 32).str("", 32);
  c.store(msg::kCfgUsb, 0, b.span());
  b = {};  // CFG-ANT
  b.u2(0x001B).u2(0xA98B);
  c.store(msg::kCfgAnt, 0, b.span());
  b = {};  // CFG-ODO: off
  b.u1(0).zeros(3).u1(0).u1(0).zeros(6).u1(10).u1(50).zeros(2).u1(153).u1(76).zeros(2);
  c.store(msg::kCfgOdo, 0, b.span());
  b = {};  // CFG-NMEA version 1: NMEA 4.0 on the M8, 4.10 on the NEO-M9N (their logs, multi-gnss.md §7)
  b.u1(0).u1(is_generation9(generation) ? 0x41 : 0x40).u1(0).u1(0).u4(0).u1(0).u1(0).u1(0).u1(1).zeros(2).zeros(6);
  c.store(msg::kCfgNmea, 0, b.span());
  b = {};  // CFG-PMS: full power
  b.u1(0).u1(0).u2(0).u2(0).zeros(2);
  c.store(msg::kCfgPms, 0, b.span());
  b = {};  // CFG-RINV
  b.u1(0).str("Notice: no data saved!", 22);
  c.store(msg::kCfgRinv, 0, b.span());
  b = {};  // CFG-LOGFILTER version 1: off
  b.u1(1).u1(0).u2(0).u2(0).u2(0).u4(0);
  c.store(msg::kCfgLogfilter, 0, b.span());
  b = {};  // CFG-GEOFENCE: no fences
  b.u1(0).u1(0).u1(0).u1(0).u1(0).u1(0).u1(0).u1(0);
  c.store(msg::kCfgGeofence, 0, b.span());
  b = {};  // CFG-DAT poll form: WGS-84
  b.u2(0).str("WGS84", 6).r8(6378137.0).r8(298.257223563).r4(0).r4(0).r4(0).r4(0).r4(0).r4(0).r4(0);
  c.store(msg::kCfgDat, 0, b.span());
  set_plain_defaults(c);
  return c;
}

std::size_t DeviceConfig::row(MsgId id) const noexcept {
  for (std::size_t i = 0; i < num_rates_; ++i) {
    if (rate_ids_[i] == id) return i;
  }
  return num_rates_;
}

std::uint8_t DeviceConfig::message_rate(std::size_t column, MsgId id) const noexcept {
  const std::size_t r = row(id);
  if (column >= columns() || r == num_rates_) return 0;
  return rates_[r * columns() + column];
}

bool DeviceConfig::set_message_rate(std::size_t column, MsgId id, std::uint8_t value) noexcept {
  if (column >= columns()) return false;
  std::size_t r = row(id);
  if (r == num_rates_) {
    if (value == 0) return true;
    if (num_rates_ == kMaxRateEntries) return false;
    rate_ids_[num_rates_++] = id;
    std::fill_n(rates_.begin() + static_cast<std::ptrdiff_t>(r * columns()), columns(), std::uint8_t{0});
  }
  rates_[r * columns() + column] = value;
  return true;
}

const StoredBlock* DeviceConfig::stored(MsgId id, std::uint8_t index) const noexcept {
  for (std::size_t i = 0; i < num_blocks_; ++i) {
    if (blocks_[i].id == id && blocks_[i].index == index) return &blocks_[i];
  }
  return nullptr;
}

bool DeviceConfig::store(MsgId id, std::uint8_t index, std::span<const std::uint8_t> payload) noexcept {
  if (payload.size() > kMaxStoredBytes) return false;
  StoredBlock* slot = nullptr;
  for (std::size_t i = 0; i < num_blocks_; ++i) {
    if (blocks_[i].id == id && blocks_[i].index == index) slot = &blocks_[i];
  }
  if (slot == nullptr) {
    if (num_blocks_ == blocks_.size()) return false;
    slot = &blocks_[num_blocks_++];
    slot->id = id;
    slot->index = index;
  }
  slot->bytes = {};
  std::copy(payload.begin(), payload.end(), slot->bytes.begin());
  slot->size = static_cast<std::uint16_t>(payload.size());
  return true;
}

bool DeviceConfig::operator==(const DeviceConfig& o) const {
  const auto port_eq = [](const PortSettings& a, const PortSettings& b) {
    return a.port_id == b.port_id && a.exists == b.exists && a.tx_ready == b.tx_ready && a.mode == b.mode &&
           a.baud_bps == b.baud_bps && a.in_proto_mask == b.in_proto_mask &&
           a.out_proto_mask == b.out_proto_mask && a.flags == b.flags && a.autobauding == b.autobauding;
  };
  if (columns() != o.columns()) return false;
  for (std::size_t p = 0; p < columns(); ++p) {
    if (!port_eq(ports_[p], o.ports_[p])) return false;
  }
  if (std::memcmp(&rate, &o.rate, sizeof rate) != 0 || std::memcmp(&nav5, &o.nav5, sizeof nav5) != 0) return false;
  if (!same_rates(o) || plain_ != o.plain_) return false;
  if (num_blocks_ != o.num_blocks_) return false;
  for (std::size_t i = 0; i < num_blocks_; ++i) {
    const StoredBlock* b = o.stored(blocks_[i].id, blocks_[i].index);
    if (b == nullptr || b->size != blocks_[i].size ||
        !std::equal(b->bytes.begin(), b->bytes.begin() + b->size, blocks_[i].bytes.begin())) {
      return false;
    }
  }
  return true;
}

bool DeviceConfig::same_rates(const DeviceConfig& o) const noexcept {
  if (columns() != o.columns()) return false;
  // Rows are appended, so the tables of one chip usually share a prefix of
  // ids: compare it cell by cell, the longer table's other rows must be 0.
  const DeviceConfig& longer = num_rates_ >= o.num_rates_ ? *this : o;
  const std::size_t common = std::min(num_rates_, o.num_rates_);
  if (std::equal(rate_ids_.begin(), rate_ids_.begin() + common, o.rate_ids_.begin())) {
    const auto cell = [this](std::size_t rows) { return static_cast<std::ptrdiff_t>(rows * columns()); };
    return std::equal(rates_.begin(), rates_.begin() + cell(common), o.rates_.begin()) &&
           std::all_of(longer.rates_.begin() + cell(common), longer.rates_.begin() + cell(longer.num_rates_),
                       [](std::uint8_t r) { return r == 0; });
  }
  // Tables filled in another order: equal as sets of non-zero rates.
  const auto covers = [](const DeviceConfig& a, const DeviceConfig& b) {
    for (const MsgId id : a.rated_messages()) {
      for (std::size_t col = 0; col < a.columns(); ++col) {
        if (b.message_rate(col, id) != a.message_rate(col, id)) return false;
      }
    }
    return true;
  };
  return covers(*this, o) && covers(o, *this);
}

void DeviceConfig::copy_sections(const DeviceConfig& src, std::uint32_t mask) noexcept {
  if (mask != 0) plain_ = src.plain_;
  if (mask & (1u << 0)) ports_ = src.ports_;
  if (mask & (1u << 1)) {
    rate_ids_ = src.rate_ids_;
    num_rates_ = src.num_rates_;
    rates_ = src.rates_;
  }
  if (mask & (1u << 3)) {
    rate = src.rate;
    nav5 = src.nav5;
  }
  for (std::size_t i = 0; i < src.num_blocks_; ++i) {
    const StoredBlock& b = src.blocks_[i];
    if (mask & section_of(b.id)) store(b.id, b.index, b.payload());
  }
}

}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
// CFG-VALSET / VALGET / VALDEL on an emulated M9: every key reads and writes
// the same state as the legacy CFG messages, layers, transactions, the NAK of
// every bad input (nothing applied), wildcards and paging; an M8 NAKs all three.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/protocol/ubx/config/ubx_config_keys.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using ValKeyValues = std::vector<std::pair<std::uint32_t, std::uint64_t>>;

constexpr std::uint32_t kRateMeas = 0x30210001, kRateNav = 0x30210002, kUart1Baud = 0x40520001,
                        kNavPvtUart1 = 0x20910007, kDynModel = 0x20110021, kUseOdo = 0x10220001,
                        kItfmEnable = 0x1041000D, kGalEna = 0x10310021, kNmeaProtver = 0x20930001,
                        kUart1OutNmea = 0x10740002, kMonRfUart1 = 0x2091035A, kSecSigUsb = 0x20910637;
constexpr std::uint8_t kRam = 1, kBbr = 2, kFlash = 4;

DeviceSetup m9_setup() {
  DeviceSetup s;
  s.mon_ver = mon_ver_of(Generation::kM9);
  return s;
}

void put(std::vector<std::uint8_t>& p, std::uint64_t v, std::size_t bytes) {
  for (std::size_t i = 0; i < bytes; ++i) p.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

std::vector<std::uint8_t> valset(std::uint8_t layers, const ValKeyValues& kv, std::uint8_t version = 0,
                                 std::uint8_t action = 0) {
  std::vector<std::uint8_t> p{version, layers, version == 1 ? action : std::uint8_t{0}, 0};
  for (const auto& [key, value] : kv) {
    put(p, key, 4);
    put(p, value, ConfigKey::value_bytes_of(key));
  }
  return p;
}

std::vector<std::uint8_t> valget(std::uint8_t layer, const std::vector<std::uint32_t>& keys,
                                 std::uint16_t position = 0) {
  std::vector<std::uint8_t> p{0, layer};
  put(p, position, 2);
  for (const std::uint32_t k : keys) put(p, k, 4);
  return p;
}

std::vector<std::uint8_t> valdel(std::uint8_t layers, const std::vector<std::uint32_t>& keys) {
  std::vector<std::uint8_t> p{0, layers, 0, 0};
  for (const std::uint32_t k : keys) put(p, k, 4);
  return p;
}

/// A host on UART1 of output 0.
struct ValHost {
  explicit ValHost(Device& d, Link at = {}) : dev(d), link(at) {}
  Device& dev;
  Link link;
  std::string out;
  InputResult last;
  std::vector<test::Frame> send(MsgId id, const std::vector<std::uint8_t>& payload) {
    out.clear();
    last = dev.handle_ubx(link, FrameView{id, payload}, 0.0, out);
    return test::split_frames(out);
  }
  bool acked(MsgId id, const std::vector<std::uint8_t>& payload) {
    const auto f = send(id, payload);
    return !f.empty() && f.back().id == msg::kAckAck;
  }
  /// VALGET values (key -> value) of one reply; empty when NAKed.
  std::vector<std::pair<std::uint32_t, std::uint64_t>> get(std::uint8_t layer, const std::vector<std::uint32_t>& keys,
                                                           std::uint16_t position = 0) {
    const auto f = send(msg::kCfgValget, valget(layer, keys, position));
    std::vector<std::pair<std::uint32_t, std::uint64_t>> values;
    if (f.size() != 2 || f[0].id != msg::kCfgValget || f[1].id != msg::kAckAck) return values;
    const auto& p = f[0].payload;
    EXPECT_EQ(p[0], 1);  // response version
    EXPECT_EQ(p[1], layer);
    EXPECT_EQ(test::u2(p, 2), position);
    for (std::size_t off = 4; off < p.size();) {
      const std::uint32_t key = test::u4(p, off);
      const std::size_t n = ConfigKey::value_bytes_of(key);
      std::uint64_t v = 0;
      for (std::size_t i = 0; i < n; ++i) v |= std::uint64_t{p[off + 4 + i]} << (8 * i);
      values.emplace_back(key, v);
      off += 4 + n;
    }
    return values;
  }
  std::uint64_t value(std::uint8_t layer, std::uint32_t key) {
    const auto v = get(layer, {key});
    EXPECT_EQ(v.size(), 1u) << std::hex << key;
    return v.empty() ? ~0ull : v[0].second;
  }
  std::vector<std::uint8_t> poll(MsgId id, const std::vector<std::uint8_t>& payload = {}) {
    const auto f = send(id, payload);
    EXPECT_EQ(f.size(), 2u);
    return f.empty() ? std::vector<std::uint8_t>{} : f[0].payload;
  }
};

TEST(UbxCfgVal, AnM8NaksAllThree) {
  Device d({});
  ValHost h(d);
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 200}})));
  EXPECT_EQ(h.last.reply, Reply::kNak);
  EXPECT_EQ(d.config().rate.measRate, 1000);
  EXPECT_FALSE(h.acked(msg::kCfgValget, valget(0, {kRateMeas})));
  EXPECT_FALSE(h.acked(msg::kCfgValdel, valdel(kBbr, {kRateMeas})));
}

TEST(UbxCfgVal, RateMeasIsCfgRate) {
  Device d(m9_setup());
  ValHost h(d);
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 200}, {kRateNav, 1}})));
  EXPECT_TRUE(h.last.nav_rate_changed);
  EXPECT_FALSE(h.last.rates_changed);
  EXPECT_DOUBLE_EQ(d.epoch_period_s(), 0.2);
  EXPECT_EQ(test::u2(h.poll(msg::kCfgRate), 0), 200);
  // And back: CFG-RATE 500 ms shows in VALGET.
  EXPECT_TRUE(h.acked(msg::kCfgRate, {0xF4, 0x01, 1, 0, 1, 0}));
  EXPECT_EQ(h.value(0, kRateMeas), 500u);
  EXPECT_EQ(h.value(0, 0x20210003), 1u);  // CFG-RATE-TIMEREF = GPS
}

TEST(UbxCfgVal, MsgOutIsCfgMsgPerPort) {
  Device d(m9_setup());
  ValHost h(d);
  EXPECT_TRUE(h.acked(msg::kCfgMsg, {0x01, 0x07, 3}));  // NAV-PVT every 3rd epoch on this port
  EXPECT_EQ(h.value(0, kNavPvtUart1), 3u);
  EXPECT_EQ(h.value(0, kNavPvtUart1 - 1), 0u);  // I2C
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kNavPvtUart1 + 2, 2}, {kMonRfUart1, 1}, {kSecSigUsb, 4}})));
  EXPECT_TRUE(h.last.rates_changed);
  const auto rates = h.poll(msg::kCfgMsg, {0x01, 0x07});  // class, id, then DDC UART1 UART2 USB SPI reserved
  EXPECT_EQ(rates[2 + kPortUart1], 3);
  EXPECT_EQ(rates[2 + kPortUsb], 2);
  EXPECT_EQ(d.message_rate({}, msg::kMonRf), 1);
  EXPECT_EQ(d.message_rate({0, kPortUsb}, msg::kSecSig), 4);
  // NMEA: UART1 GGA (factory 1) off.
  EXPECT_EQ(h.value(0, 0x209100BB), 1u);
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{0x209100BB, 0}})));
  EXPECT_FALSE(d.nmea_due({}).has(nmea::Sentence::kGga));
}

TEST(UbxCfgVal, BaudSwitchesAfterTheAck) {
  Device d(m9_setup());
  ValHost h(d);
  const auto f = h.send(msg::kCfgValset, valset(kRam, {{kUart1Baud, 115200}}));
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].id, msg::kAckAck);  // sent at the old baud
  EXPECT_EQ(h.last.new_baud_bps, 115200u);
  EXPECT_TRUE(h.last.ports_changed);
  EXPECT_EQ(test::u4(h.poll(msg::kCfgPrt, {kPortUart1}), 8), 115200u);
  // Not a u-blox rate, or not 8N1: NAK, nothing applied.
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {{kUart1Baud, 12345}})));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {{0x20520004, 2}})));  // even parity
  EXPECT_EQ(h.last.new_baud_bps, 0u);
  EXPECT_EQ(d.port({}).baud_bps, 115200u);
  // PX4's probe: UART1 8N1, UBX in/out, NMEA off.
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{0x20520002, 1}, {0x20520003, 0}, {0x20520004, 0},
                                                     {0x10730001, 1}, {0x10730002, 0}, {0x10740001, 1},
                                                     {kUart1OutNmea, 0}})));
  EXPECT_FALSE(d.port({}).outputs_nmea());
  EXPECT_FALSE(d.port({}).accepts_nmea());
  EXPECT_TRUE(d.port({}).outputs_ubx());
}

TEST(UbxCfgVal, LegacyBlocksSeeTheKeys) {
  Device d(m9_setup());
  ValHost h(d);
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kDynModel, 7}, {0x20110011, 2}, {0x201100A4, 0xF6}})));
  EXPECT_TRUE(h.last.nav_config_changed);
  const auto nav5 = h.poll(msg::kCfgNav5);
  EXPECT_EQ(nav5[2], 7);                              // dynModel airborne <2g
  EXPECT_EQ(nav5[3], 2);                              // fixMode 3D only
  EXPECT_EQ(static_cast<std::int8_t>(nav5[12]), -10);  // minElev
  EXPECT_EQ(h.value(0, 0x201100A4), 0xF6u);
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kUseOdo, 1}, {kItfmEnable, 1}, {kGalEna, 1},
                                                     {kNmeaProtver, 40}, {0x10360005, 1}})));
  EXPECT_EQ(h.poll(msg::kCfgOdo)[4] & 1, 1);
  EXPECT_EQ(h.poll(msg::kCfgItfm)[3] & 0x80, 0x80);
  const auto gnss = h.poll(msg::kCfgGnss);
  EXPECT_EQ(gnss[4 + 8 * 2], 2);           // block 2 is Galileo
  EXPECT_EQ(gnss[4 + 8 * 2 + 4] & 1, 1);   // now enabled
  EXPECT_EQ(h.poll(msg::kCfgNmea)[1], 0x40);
  EXPECT_EQ(h.poll(msg::kCfgSbas)[1] & 0x4, 0x4);
  // Legacy sets show in VALGET: CFG-NAV5 dynModel 4, CFG-ODO off.
  std::vector<std::uint8_t> n5(36, 0);
  n5[0] = 0x01;
  n5[2] = 4;
  EXPECT_TRUE(h.acked(msg::kCfgNav5, n5));
  EXPECT_EQ(h.value(0, kDynModel), 4u);
  EXPECT_EQ(h.value(0, 0x20410001), 3u);   // ITFM bbThreshold of the factory block
  EXPECT_EQ(h.value(0, 0x20410002), 15u);  // cwThreshold
  EXPECT_EQ(h.value(0, kNmeaProtver), 40u);
}

/// Every key: a valid value other than the current one goes in and reads back.
class UbxCfgValGen : public ::testing::TestWithParam<Generation> {};

TEST_P(UbxCfgValGen, EveryKeyRoundTrips) {
  DeviceSetup setup;
  setup.mon_ver = mon_ver_of(GetParam());
  Device d(setup);
  ValHost uart1(d);
  ValHost usb(d, {0, kPortUsb});
  for (const ConfigKey& k : config_keys()) {
    if (!k.exists_on(GetParam())) continue;
    SCOPED_TRACE(config_key_name(k));
    // A port's own protocol keys are set from another port (UBX off would cut the host off).
    const bool own = (k.store == KeyStore::kInProto || k.store == KeyStore::kOutProto) && k.port == kPortUart1;
    ValHost& h = own ? usb : uart1;
    const std::uint64_t now = h.value(0, k.id);
    std::vector<std::uint64_t> candidates{static_cast<std::uint64_t>(k.max), static_cast<std::uint64_t>(k.min), 1, 0,
                                          38400, 3, 115200};
    if (k.is_signed) candidates.push_back(static_cast<std::uint64_t>(k.min) & ((1ull << (8 * k.value_bytes())) - 1));
    std::uint64_t pick = now;
    for (const std::uint64_t c : candidates) {
      if (c != now && valid_config_value(k, c)) {
        pick = c;
        break;
      }
    }
    if (pick == now) {  // one valid value only (8N1 framing)
      EXPECT_EQ(k.store, KeyStore::kUartFraming);
    }
    EXPECT_EQ(h.value(7, k.id), read_config_key(k, DeviceConfig::factory_defaults(1, GetParam()), 0));
    // The only signal of an enabled system cannot go: that VALSET is NAKed (test_ubx_gnss.cpp).
    if (k.store == KeyStore::kGnss && k.shift == 16 && pick == 0) {
      EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {{k.id, pick}})));
      EXPECT_EQ(h.value(0, k.id), now);
      continue;
    }
    EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{k.id, pick}})));
    EXPECT_EQ(h.value(0, k.id), pick);
    EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{k.id, now}})));  // back, so the hosts keep talking
  }
}

INSTANTIATE_TEST_SUITE_P(Generations, UbxCfgValGen, ::testing::Values(Generation::kM9, Generation::kF9P),
                         [](const auto& p) { return std::string(generation_name(p.param)); });

TEST(UbxCfgVal, BadInputIsNakedAndNothingApplied) {
  Device d(m9_setup());
  ValHost h(d);
  const auto unchanged = [&] { return d.config() == d.saved(); };
  // Unknown key after a good one.
  auto p = valset(kRam, {{kRateMeas, 200}});
  put(p, 0x30219999, 4);
  put(p, 1, 2);
  EXPECT_FALSE(h.acked(msg::kCfgValset, p));
  EXPECT_TRUE(unchanged());
  // A good key and a bad value (dynModel 1 is reserved; measRate 10 ms too fast).
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 200}, {kDynModel, 1}})));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 10}})));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {{kUseOdo, 2}})));  // L: 0 or 1
  EXPECT_TRUE(unchanged());
  // A value cut short; a stray byte after the last pair.
  p = valset(kRam, {{kRateMeas, 200}});
  p.pop_back();
  EXPECT_FALSE(h.acked(msg::kCfgValset, p));
  p = valset(kRam, {{kRateMeas, 200}});
  p.push_back(0);
  EXPECT_FALSE(h.acked(msg::kCfgValset, p));
  // No layer, an unknown layer bit, an unknown version, a short header.
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(0, {{kRateMeas, 200}})));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(0x09, {{kRateMeas, 200}})));
  p = valset(kRam, {{kRateMeas, 200}});
  p[0] = 2;
  EXPECT_FALSE(h.acked(msg::kCfgValset, p));
  EXPECT_FALSE(h.acked(msg::kCfgValset, {0, 1}));
  EXPECT_TRUE(unchanged());
  EXPECT_EQ(h.last.reply, Reply::kNak);
  EXPECT_FALSE(h.last.nav_rate_changed);
}

TEST(UbxCfgVal, AtMost64KeysPerMessage) {
  Device d(m9_setup());
  ValHost h(d);
  ValKeyValues kv;
  std::vector<std::uint32_t> keys;
  for (std::uint32_t i = 0; i < 65; ++i) {
    kv.emplace_back(0x20910006 + i % 5, i % 7);  // NAV-PVT on the five ports, repeated: last wins
    keys.push_back(kRateMeas);
  }
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, kv)));
  EXPECT_TRUE(h.get(0, keys).empty());
  kv.pop_back();
  keys.pop_back();
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, kv)));
  EXPECT_EQ(h.value(0, 0x20910006 + 63 % 5), 63u % 7);
  EXPECT_EQ(h.get(0, keys).size(), 64u);
  EXPECT_FALSE(h.acked(msg::kCfgValdel, valdel(kBbr, std::vector<std::uint32_t>(65, kRateMeas))));
}

TEST(UbxCfgVal, LayersAndDelete) {
  Device d(m9_setup());
  ValHost h(d);
  // BBR and Flash only: RAM keeps running at 1 Hz.
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kBbr | kFlash, {{kRateMeas, 200}, {kNavPvtUart1, 1}})));
  EXPECT_FALSE(h.last.nav_rate_changed);
  EXPECT_EQ(h.value(0, kRateMeas), 1000u);
  EXPECT_EQ(h.value(1, kRateMeas), 200u);
  EXPECT_EQ(h.value(2, kRateMeas), 200u);
  EXPECT_EQ(h.value(7, kRateMeas), 1000u);
  EXPECT_TRUE(h.get(3, {kRateMeas}).empty());  // no layer 3
  // CFG-CFG load of msgConf+navConf brings them into RAM.
  EXPECT_TRUE(h.acked(msg::kCfgCfg, {0, 0, 0, 0, 0, 0, 0, 0, 0x0A, 0, 0, 0}));
  EXPECT_EQ(h.value(0, kRateMeas), 200u);
  EXPECT_EQ(d.message_rate({}, msg::kNavPvt), 1);
  // VALDEL from BBR reverts the saved value to the default; RAM keeps its own.
  EXPECT_TRUE(h.acked(msg::kCfgValdel, valdel(kBbr, {kRateMeas})));
  EXPECT_EQ(h.value(1, kRateMeas), 1000u);
  EXPECT_EQ(h.value(0, kRateMeas), 200u);
  EXPECT_EQ(h.value(1, kNavPvtUart1), 1u);
  EXPECT_TRUE(h.acked(msg::kCfgValdel, valdel(kBbr, {0x0091FFFF})));  // every MSGOUT key
  EXPECT_EQ(h.value(1, kNavPvtUart1), 0u);
  // VALDEL needs BBR or Flash and known keys.
  EXPECT_FALSE(h.acked(msg::kCfgValdel, valdel(kRam, {kRateMeas})));
  EXPECT_FALSE(h.acked(msg::kCfgValdel, valdel(kBbr, {0x30219999})));
  EXPECT_FALSE(h.acked(msg::kCfgValdel, valdel(kBbr, {})));
}

TEST(UbxCfgVal, Transactions) {
  Device d(m9_setup());
  ValHost h(d);
  // Start, ongoing, apply: nothing changes before the apply.
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 200}}, 1, 1)));
  EXPECT_EQ(h.value(0, kRateMeas), 1000u);  // VALGET is another CFG message: it cancels the transaction
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {{kNavPvtUart1, 1}}, 1, 3)));
  EXPECT_EQ(d.message_rate({}, msg::kNavPvt), 0);

  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 200}}, 1, 1)));
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kNavPvtUart1, 1}, {kRateMeas, 250}}, 1, 2)));
  EXPECT_DOUBLE_EQ(d.epoch_period_s(), 1.0);
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {}, 1, 3)));
  EXPECT_TRUE(h.last.nav_rate_changed);
  EXPECT_TRUE(h.last.rates_changed);
  EXPECT_EQ(h.value(0, kRateMeas), 250u);  // the last value sent wins
  EXPECT_EQ(d.message_rate({}, msg::kNavPvt), 1);

  // Ongoing or apply without a start; layers changing mid-way; an unknown action.
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 300}}, 1, 2)));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {}, 1, 3)));
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 300}}, 1, 1)));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam | kBbr, {}, 1, 2)));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {}, 1, 3)));  // cancelled by the NAK
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {}, 1, 4)));
  // A bad value is found at the apply: NAK, nothing of the transaction applied.
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 300}}, 1, 1)));
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kDynModel, 1}}, 1, 2)));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {}, 1, 3)));
  EXPECT_EQ(h.value(0, kRateMeas), 250u);
  // A transaction-less set ends a started transaction.
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kRateMeas, 300}}, 1, 1)));
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset(kRam, {{kNavPvtUart1, 2}}, 1, 0)));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset(kRam, {}, 1, 3)));
  EXPECT_EQ(d.message_rate({}, msg::kNavPvt), 2);
  EXPECT_EQ(d.config().rate.measRate, 250);
}

TEST(UbxCfgVal, WildcardsAndPaging) {
  Device d(m9_setup());
  ValHost h(d);
  // Group CFG-RATE (0x21): its three keys in table order.
  const auto rate = h.get(0, {0x0021FFFF});
  ASSERT_EQ(rate.size(), 3u);
  EXPECT_EQ(rate[0], (std::pair<std::uint32_t, std::uint64_t>{kRateMeas, 1000}));
  EXPECT_EQ(rate[2].first, 0x20210003u);
  // Every key: pages of 64 via position.
  std::vector<std::uint32_t> seen;
  for (std::uint16_t pos = 0;; pos = static_cast<std::uint16_t>(pos + 64)) {
    const auto page = h.get(7, {0x0FFFFFFF}, pos);
    if (page.empty()) break;
    EXPECT_LE(page.size(), 64u);
    for (const auto& kv : page) seen.push_back(kv.first);
  }
  std::vector<std::uint32_t> m9_keys;
  for (const ConfigKey& k : config_keys()) {
    if (k.exists_on(Generation::kM9)) m9_keys.push_back(k.id);
  }
  EXPECT_EQ(seen, m9_keys);
  // Unknown key, unknown group, too many keys, a wrong length: NAK.
  EXPECT_TRUE(h.get(0, {kRateMeas, 0x30219999}).empty());
  EXPECT_TRUE(h.get(0, {0x00EEFFFF}).empty());
  EXPECT_TRUE(h.get(0, std::vector<std::uint32_t>(65, kRateMeas)).empty());
  auto p = valget(0, {kRateMeas});
  p.push_back(0);
  EXPECT_FALSE(h.acked(msg::kCfgValget, p));
  EXPECT_FALSE(h.acked(msg::kCfgValget, {0, 0, 0, 0}));
}

TEST(UbxCfgVal, KeyTableMatchesItsSources) {
  // Spot checks against shared/reference/ubx.md and PX4-GPSDrivers ubx.h.
  for (const auto& [id, name] : std::vector<std::pair<std::uint32_t, std::string>>{
           {0x30210001, "CFG-RATE-MEAS"},
           {0x40520001, "CFG-UART1-BAUDRATE"},
           {0x20910007, "CFG-MSGOUT-UBX_NAV_PVT_UART1"},
           {0x2091035A, "CFG-MSGOUT-UBX_MON_RF_UART1"},
           {0x209100BB, "CFG-MSGOUT-NMEA_ID_GGA_UART1"},
           {0x209100D9, "CFG-MSGOUT-NMEA_ID_ZDA_UART1"},
           {0x20910160, "CFG-MSGOUT-UBX_NAV_EOE_UART1"},
           {0x2011001C, "CFG-NAVSPG-UTCSTANDARD"},
           {0x1041000D, "CFG-ITFM-ENABLE"},
           {0x10310025, "CFG-SIGNAL-GLO_ENA"},
       }) {
    const ConfigKey* k = find_config_key(id);
    ASSERT_NE(k, nullptr) << name;
    EXPECT_EQ(config_key_name(*k), name);
  }
  // CFG-NAVHPG-DGNSSMODE: an F9P key, an M9N NAKs it.
  EXPECT_EQ(find_config_key(0x20140011, Generation::kM9), nullptr);
  ASSERT_NE(find_config_key(0x20140011, Generation::kF9P), nullptr);
  EXPECT_EQ(config_key_name(*find_config_key(0x20140011, Generation::kF9P)), "CFG-NAVHPG-DGNSSMODE");
  EXPECT_EQ(ConfigKey::value_bytes_of(0x10730001), 1u);
  EXPECT_EQ(ConfigKey::value_bytes_of(0x30210001), 2u);
  EXPECT_EQ(ConfigKey::value_bytes_of(0x40520001), 4u);
  EXPECT_EQ(ConfigKey::value_bytes_of(0x50360006), 8u);
  EXPECT_EQ(ConfigKey::value_bytes_of(0x00360006), 0u);
}

TEST(UbxCfgVal, HandlersAloneHonourTheGeneration) {
  test::HandlerRig rig;  // an M8 encoder
  EXPECT_EQ(rig.call(handle_cfg_valset, msg::kCfgValset, valset(kRam, {{kRateMeas, 200}})), Reply::kNak);
  EXPECT_EQ(rig.call(handle_cfg_valget, msg::kCfgValget, valget(0, {kRateMeas})), Reply::kNak);
  EXPECT_EQ(rig.call(handle_cfg_valdel, msg::kCfgValdel, valdel(kBbr, {kRateMeas})), Reply::kNak);
  rig.encoder = UbxEncoder(mon_ver_of(Generation::kM9));
  EXPECT_EQ(rig.call(handle_cfg_valset, msg::kCfgValset, valset(kRam, {{kRateMeas, 200}})), Reply::kAck);
  EXPECT_EQ(rig.current.rate.measRate, 200);
  EXPECT_EQ(rig.call(handle_cfg_valget, msg::kCfgValget, valget(0, {kRateMeas})), Reply::kPollData);
  // The second output's host sets its own UART1.
  EXPECT_EQ(rig.call(handle_cfg_valset, msg::kCfgValset, valset(kRam, {{kNavPvtUart1, 5}}), 1), Reply::kAck);
  EXPECT_EQ(rig.current.message_rate(test::kUart1OfOutput1, msg::kNavPvt), 5);
  EXPECT_EQ(rig.current.message_rate(kPortUart1, msg::kNavPvt), 0);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
// The ZED-F9P's INF-WARNING "DGNSS baseline big" beyond a 50 km RTK baseline
// (ZED-F9P Integration Manual R08 §3.1.5.4): only where CFG-INFMSG enables
// UBX warnings on the port (factory: none), and as NMEA TXT where the NMEA
// info messages carry warnings (factory: yes); once when the baseline goes
// beyond and again at most every 60 s while it stays (ours: u-blox gives no
// repeat interval).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/protocol/nmea/nmea_format.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

constexpr MsgId kInfWarning{0x04, 0x01};

DeviceSetup chip(Generation g) {
  DeviceSetup s;
  s.mon_ver = mon_ver_of(g);
  return s;
}

/// CFG-VALSET RAM of CFG-INFMSG-UBX_UART1 (0x20920002).
Reply enable_ubx_inf(Device& d, std::uint8_t mask) {
  const std::uint8_t p[] = {0, 1, 0, 0, 0x02, 0x00, 0x92, 0x20, mask};
  std::string out;
  return d.handle_ubx({}, FrameView{msg::kCfgValset, p}, 0.0, out).reply;
}

/// The INF-WARNING texts of one epoch at now_s with a baseline_m RTK baseline.
std::vector<std::string> warnings(Device& d, double now_s, double baseline_m) {
  receiver::Fix f = test::sample_fix();
  f.rel_pos.valid = true;
  f.rel_pos.length_m = baseline_m;
  d.on_epoch(f, now_s);
  std::string out;
  test::ubx_epoch(d, {}, out);
  std::vector<std::string> w;
  for (const test::Frame& fr : test::split_frames(out)) {
    if (fr.id == kInfWarning) w.emplace_back(fr.payload.begin(), fr.payload.end());
  }
  return w;
}

TEST(UbxInfWarning, F9pWarnsBaselineBigWhenUbxWarningsAreOn) {
  Device d(chip(Generation::kF9P));
  EXPECT_TRUE(warnings(d, 0.0, 60.0e3).empty());  // factory CFG-INFMSG-UBX_*: 0
  ASSERT_EQ(enable_ubx_inf(d, 0x07), Reply::kAck);  // ERROR | WARNING | NOTICE
  // Already beyond: the repeat clock started at the silent epoch before.
  EXPECT_TRUE(warnings(d, 1.0, 60.0e3).empty());
  const auto w = warnings(d, 60.0, 60.0e3);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], "DGNSS baseline big");
  for (int s = 61; s < 120; ++s) EXPECT_TRUE(warnings(d, s, 60.0e3).empty()) << s;
  EXPECT_EQ(warnings(d, 120.0, 60.0e3).size(), 1u);
  // Back within 50 km, then beyond again: at once.
  EXPECT_TRUE(warnings(d, 121.0, 40.0e3).empty());
  EXPECT_EQ(warnings(d, 122.0, 50.1e3).size(), 1u);
}

TEST(UbxInfWarning, NoWarningWithoutTheWarningBitOrWithinFiftyKm) {
  Device d(chip(Generation::kF9P));
  ASSERT_EQ(enable_ubx_inf(d, 0x05), Reply::kAck);  // ERROR | NOTICE
  EXPECT_TRUE(warnings(d, 0.0, 200.0e3).empty());
  Device near(chip(Generation::kF9P));
  ASSERT_EQ(enable_ubx_inf(near, 0x02), Reply::kAck);
  EXPECT_TRUE(warnings(near, 0.0, 49.9e3).empty());
  EXPECT_EQ(warnings(near, 1.0, 50.1e3).size(), 1u);
}

TEST(UbxInfWarning, InfmsgKeysReadAndWriteTheCfgInfBlocks) {
  Device d(chip(Generation::kF9P));
  ASSERT_EQ(enable_ubx_inf(d, 0x03), Reply::kAck);
  const StoredBlock* ubx = d.config().stored(msg::kCfgInf, 0);
  const StoredBlock* nmea = d.config().stored(msg::kCfgInf, 1);
  ASSERT_NE(ubx, nullptr);
  ASSERT_NE(nmea, nullptr);
  EXPECT_EQ(ubx->bytes[4 + kPortUart1], 0x03);
  EXPECT_EQ(nmea->bytes[4 + kPortUart1], 0x07);  // NMEA untouched: factory ERROR | WARNING | NOTICE
  const ConfigKey* k = find_config_key(0x20920007, Generation::kF9P);  // CFG-INFMSG-NMEA_UART1
  ASSERT_NE(k, nullptr);
  EXPECT_EQ(read_config_key(*k, d.config(), 0), 0x07u);
}

/// The NMEA TXT sentences of one epoch at now_s with a baseline_m RTK baseline.
std::vector<std::string> txts(Device& d, double now_s, double baseline_m) {
  receiver::Fix f = test::sample_fix();
  f.rel_pos.valid = true;
  f.rel_pos.length_m = baseline_m;
  d.on_epoch(f, now_s);
  MessageList list;
  d.compose({}, list, Layout::kPerProtocol);
  std::vector<std::string> t;
  for (const MessageList::Message& m : list.messages()) {
    if (m.protocol == Protocol::kNmea && m.label == "TXT") t.emplace_back(list.bytes(m));
  }
  return t;
}

// Where the port's NMEA info messages carry warnings (the factory setting,
// CFG-INFMSG-NMEA_* = ERROR | WARNING | NOTICE), the warning is a TXT sentence.
TEST(UbxInfWarning, FactoryF9pWarnsInNmeaTxt) {
  Device d(chip(Generation::kF9P));
  const auto t = txts(d, 0.0, 60.0e3);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].substr(0, t[0].find('*')), "$GNTXT,01,01,01,DGNSS baseline big");
  EXPECT_TRUE(nmea::nmea_checksum_ok(t[0])) << t[0];
  EXPECT_TRUE(txts(d, 1.0, 60.0e3).empty());
  EXPECT_EQ(txts(d, 60.0, 60.0e3).size(), 1u);
  Device quiet(chip(Generation::kF9P));
  const std::uint8_t p[] = {0, 1, 0, 0, 0x07, 0x00, 0x92, 0x20, 0x05};  // CFG-INFMSG-NMEA_UART1: ERROR | NOTICE
  std::string ack;
  ASSERT_EQ(quiet.handle_ubx({}, FrameView{msg::kCfgValset, p}, 0.0, ack).reply, Reply::kAck);
  EXPECT_TRUE(txts(quiet, 0.0, 60.0e3).empty());
  EXPECT_TRUE(txts(d, 61.0, 40.0e3).empty());
}

TEST(UbxInfWarning, OnlyTheF9pWarns) {
  Device d(chip(Generation::kM9));
  ASSERT_EQ(enable_ubx_inf(d, 0x07), Reply::kAck);
  EXPECT_TRUE(warnings(d, 0.0, 200.0e3).empty());
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
// The per-epoch path never allocates once buffers have capacity: encoding an
// epoch, answering configuration input, decoding input. This executable's
// global operator new counts calls (tests/support/alloc_counter).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/protocol/ubx/wire/ubx_decoder.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "tests/support/alloc_counter.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

struct NullSink : DecoderSink {
  Device* r = nullptr;
  std::string* out = nullptr;
  std::size_t frames = 0;
  void on_ubx(const FrameView& f) override {
    ++frames;
    r->handle_ubx({}, f, 0.0, *out);
  }
  void on_nmea(std::string_view s) override {
    ++frames;
    r->handle_nmea({}, s, *out);
  }
};

class UbxAlloc : public ::testing::TestWithParam<Generation> {};

TEST_P(UbxAlloc, EpochEncodeConfigAndDecodeDoNotAllocate) {
  DeviceSetup setup;
  setup.mon_ver = mon_ver_of(GetParam());
  Device r(setup);
  // Every output message of the table on, at rate 1, on UART1 (the M9's
  // MON-RF and SEC-SIG included; what the generation lacks is not sent).
  for (const PeriodicMessage& m : kPeriodicMessages) r.config().set_message_rate(kPortUart1, m.id, 1);
  receiver::Fix fix = test::sample_fix();
  fix.num_sats = kMaxSatsInView;  // worst case: every slot, every system
  for (int i = 0; i < kMaxSatsInView; ++i) {
    fix.sats[static_cast<std::size_t>(i)] = fix.sats[static_cast<std::size_t>(i % 10)];
    fix.sats[static_cast<std::size_t>(i)].sat = SatId::from_index(i * (kNumSats / kMaxSatsInView));
  }
  // Host input: a CFG-MSG poll, a CFG-RATE, MON-VER poll, MON-RF poll, PUBX,41, some garbage.
  std::string input = "\x01\x02\x03";
  input += test::frame_bytes(msg::kCfgMsg, {0x01, 0x07});
  input += test::frame_bytes(msg::kCfgRate, {0xC8, 0, 1, 0, 0, 0});
  input += test::frame_bytes(msg::kMonVer, {});
  input += test::frame_bytes(msg::kMonRf, {});
  input += test::frame_bytes(msg::kCfgNav5, {});
  input += "$PUBX,41,1,0007,0003,9600,0*10\r\n";
  input += test::frame_bytes(msg::kCfgValset, {0, 1, 0, 0});

  std::string out;
  out.reserve(16 * kMaxEpochBytes);
  StreamDecoder decoder;
  NullSink sink;
  sink.r = &r;
  sink.out = &out;
  MessageList epoch;
  r.on_epoch(fix, 0.0);  // warm-up
  r.compose({}, epoch);
  decoder.feed(input, sink);
  out.clear();

  const long before = support::allocation_count();
  std::size_t bytes = 0;
  for (int e = 1; e <= 50; ++e) {
    out.clear();
    fix.t += 0.2;
    r.on_epoch(fix, 0.2 * e);
    r.compose({}, epoch);
    for (const MessageList::Message& m : epoch.messages()) bytes += m.protocol == Protocol::kUbx ? m.end - m.begin : 0;
    decoder.feed(input, sink);
  }
  EXPECT_EQ(support::allocation_count(), before);
  // Every message with 32 satellites was really encoded (the M9 has no NAV-SVINFO).
  EXPECT_GT(bytes, 50u * (GetParam() == Generation::kM8 ? 1200u : 850u));
  EXPECT_EQ(sink.frames, 51u * 7u);
}

INSTANTIATE_TEST_SUITE_P(Generations, UbxAlloc, ::testing::Values(Generation::kM8, Generation::kM9),
                         [](const ::testing::TestParamInfo<Generation>& p) { return std::string(generation_name(p.param)); });

TEST(UbxAlloc, ConfigInterfaceDoesNotAllocate) {
  // An M9: VALSET (a transaction and a transaction-less set on RAM+BBR), a
  // VALGET of every key (paged), a VALDEL, and their NAKs.
  DeviceSetup setup;
  setup.mon_ver = mon_ver_of(Generation::kM9);
  Device r(setup);
  const auto le = [](std::uint32_t v) {
    return std::vector<std::uint8_t>{static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                                     static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)};
  };
  const auto cat = [](std::vector<std::uint8_t> a, const std::vector<std::uint8_t>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  std::string input;
  input += test::frame_bytes(msg::kCfgValset, cat(cat({1, 1, 1, 0}, le(0x30210001)), {0xC8, 0}));   // start: RATE-MEAS 200
  input += test::frame_bytes(msg::kCfgValset, cat(cat({1, 1, 3, 0}, le(0x20910007)), {1}));         // apply: NAV-PVT UART1 1
  input += test::frame_bytes(msg::kCfgValset, cat(cat({0, 3, 0, 0}, le(0x40520001)), le(9600)));    // RAM+BBR baud
  input += test::frame_bytes(msg::kCfgValset, cat(cat({0, 1, 0, 0}, le(0x20110021)), {1}));         // NAK: dynModel 1
  input += test::frame_bytes(msg::kCfgValget, cat({0, 0, 0, 0}, le(0x0FFFFFFF)));                   // every key, page 1
  input += test::frame_bytes(msg::kCfgValget, cat({0, 7, 64, 0}, le(0x0FFFFFFF)));                  // page 2, defaults
  input += test::frame_bytes(msg::kCfgValdel, cat({0, 2, 0, 0}, le(0x0091FFFF)));                   // every MSGOUT in BBR
  std::string out;
  out.reserve(64 * 1024);
  StreamDecoder decoder;
  NullSink sink;
  sink.r = &r;
  sink.out = &out;
  decoder.feed(input, sink);  // warm-up
  const long before = support::allocation_count();
  for (int i = 0; i < 20; ++i) {
    out.clear();
    decoder.feed(input, sink);
  }
  EXPECT_EQ(support::allocation_count(), before);
  EXPECT_EQ(sink.frames, 21u * 7u);
  EXPECT_GT(out.size(), 2u * 64u * 5u);  // the VALGET pages were really written
  EXPECT_EQ(r.config().rate.measRate, 200);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
// Random CFG and other input against the device: never out of bounds
// (run under ASan by hand), exactly one ACK or NAK per CFG message except
// CFG-RST, replies are valid frames, and the epoch output stays sane.
#include <gtest/gtest.h>

#include <random>

#include "core/protocol/ubx/device/ubx_device.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

TEST(UbxDeviceFuzz, RandomInputAlwaysAnsweredOnceOrIgnored) {
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> len(0, 120);
  Device r({});
  const receiver::Fix fix = test::sample_fix();
  int cfg = 0, answered = 0;
  for (int i = 0; i < 20000; ++i) {
    // Mostly CFG ids an M8 knows, with lengths near the valid ones.
    const std::uint8_t cls = (i % 5 == 0) ? static_cast<std::uint8_t>(byte(rng) % 16) : cls::kCfg;
    const std::uint8_t id = static_cast<std::uint8_t>(i % 3 == 0 ? byte(rng) : byte(rng) % 0x40);
    std::vector<std::uint8_t> p(static_cast<std::size_t>(len(rng)));
    for (auto& v : p) v = static_cast<std::uint8_t>(byte(rng));
    if (i % 4 == 0 && p.size() > 3) p[3] = static_cast<std::uint8_t>(p[3] % 8);  // plausible block counts
    std::string out;
    const std::uint8_t port = static_cast<std::uint8_t>(byte(rng) % 7);
    const auto res = r.handle_ubx({0, port}, FrameView{MsgId{cls, id}, p}, 0.0, out);
    EXPECT_EQ(res.bytes, out.size());
    const auto frames = test::split_frames(out);
    std::size_t total = 0;
    for (const auto& f : frames) total += f.payload.size() + 8;
    EXPECT_EQ(total, out.size());  // nothing but whole, valid frames
    if (cls == cls::kCfg && !out.empty()) {
      ++cfg;
      int acks = 0;
      for (const auto& f : frames) acks += f.id == msg::kAckAck || f.id == msg::kAckNak;
      EXPECT_EQ(acks, 1);
      ++answered;
    }
    if (i % 50 == 0) {
      // Keep UBX on UART1 so answers keep flowing, and run an epoch.
      r.config().port(kPortUart1).in_proto_mask = 0x07;
      r.config().port(kPortUart1).out_proto_mask = 0x03;
      r.on_epoch(fix, i * 0.1);
      std::string epoch;
      test::ubx_epoch(r, {0, kPortUart1}, epoch);
      EXPECT_LE(epoch.size(), kMaxEpochBytes);
      std::size_t n = 0;
      for (const auto& f : test::split_frames(epoch)) n += f.payload.size() + 8;
      EXPECT_EQ(n, epoch.size());
    }
  }
  EXPECT_GT(cfg, 1000);
  EXPECT_EQ(answered, cfg);
  EXPECT_GT(r.stats().acks, 20u);  // random payloads of a valid length
  EXPECT_GT(r.stats().naks, 1000u);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

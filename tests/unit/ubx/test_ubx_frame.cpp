// SPDX-License-Identifier: Apache-2.0
// Frame layer: checksums and frames against byte examples in
// shared/reference/ubx.md §1 (each recomputed by hand there).
#include <gtest/gtest.h>

#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::frame_bytes;
using test::from_hex;
using test::to_hex;

TEST(UbxFrame, PollsMatchReferenceBytes) {
  EXPECT_EQ(to_hex(frame_bytes(msg::kMonVer, {})), "B5 62 0A 04 00 00 0E 34");
  EXPECT_EQ(to_hex(frame_bytes(msg::kNavPvt, {})), "B5 62 01 07 00 00 08 19");
}

TEST(UbxFrame, AckAndNakMatchReferenceBytes) {
  std::string out;
  EXPECT_EQ(UbxEncoder::ack(msg::kCfgPrt, true, out), 10u);
  EXPECT_EQ(to_hex(out), "B5 62 05 01 02 00 06 00 0E 37");
  out.clear();
  UbxEncoder::ack(msg::kCfgPrt, false, out);
  EXPECT_EQ(to_hex(out), "B5 62 05 00 02 00 06 00 0D 32");
}

TEST(UbxFrame, ValsetExampleChecksum) {
  // CFG-VALSET RAM RATE_MEAS = 100 ms (ubx.md §1).
  const std::string f = frame_bytes(msg::kCfgValset, {0x00, 0x01, 0x00, 0x00, 0x01, 0x00, 0x21, 0x30, 0x64, 0x00});
  EXPECT_EQ(to_hex(f), "B5 62 06 8A 0A 00 00 01 00 00 01 00 21 30 64 00 51 B9");
}

TEST(UbxFrame, Fletcher8OverHeaderAndPayload) {
  const std::string f = from_hex("B5 62 05 01 02 00 06 00 0E 37");
  const auto ck = fletcher8({reinterpret_cast<const std::uint8_t*>(f.data()) + 2, f.size() - 4});
  EXPECT_EQ(ck.ck_a, 0x0E);
  EXPECT_EQ(ck.ck_b, 0x37);
}

TEST(UbxFrame, AppendKeepsExistingBytesAndReturnsLength) {
  std::string out = "xy";
  const std::uint8_t payload[3] = {1, 2, 3};
  EXPECT_EQ(append_frame(out, MsgId{0x01, 0x02}, payload), 11u);
  ASSERT_EQ(out.size(), 13u);
  EXPECT_EQ(out.substr(0, 2), "xy");
  EXPECT_EQ(static_cast<unsigned char>(out[2]), 0xB5);
  EXPECT_EQ(static_cast<unsigned char>(out[6]), 3);  // length LE
  EXPECT_EQ(static_cast<unsigned char>(out[7]), 0);
}

TEST(UbxFrame, WireStructOffsetsFollowTheSpec) {
  EXPECT_EQ(offsetof(wire::NavPvt, fixType), 20u);
  EXPECT_EQ(offsetof(wire::NavPvt, numSV), 23u);
  EXPECT_EQ(offsetof(wire::NavPvt, hMSL), 36u);
  EXPECT_EQ(offsetof(wire::NavPvt, gSpeed), 60u);
  EXPECT_EQ(offsetof(wire::NavPvt, headAcc), 72u);
  EXPECT_EQ(offsetof(wire::NavPvt, magAcc), 90u);
  EXPECT_EQ(offsetof(wire::NavSol, week), 8u);
  EXPECT_EQ(offsetof(wire::NavSol, pDOP), 44u);
  EXPECT_EQ(offsetof(wire::NavSol, numSV), 47u);
  EXPECT_EQ(offsetof(wire::NavVelned, heading), 24u);
  EXPECT_EQ(offsetof(wire::NavTimeutc, valid), 19u);
  EXPECT_EQ(offsetof(wire::MonHw, noisePerMS), 16u);
  EXPECT_EQ(offsetof(wire::MonHw, jamInd), 45u);
  EXPECT_EQ(offsetof(wire::CfgPrt, baudRate), 8u);
  EXPECT_EQ(offsetof(wire::CfgPrt, outProtoMask), 14u);
  EXPECT_EQ(offsetof(wire::CfgNav5, minElev), 12u);
  EXPECT_EQ(offsetof(wire::CfgNav5, utcStandard), 30u);
}

TEST(UbxFrame, ReadWireRejectsShortPayload) {
  const std::uint8_t p[5] = {};
  wire::CfgRate r{};
  EXPECT_FALSE(read_wire(p, r));
  wire::Ack a{};
  EXPECT_TRUE(read_wire(p, a, 3));
  EXPECT_FALSE(read_wire(p, a, 4));
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

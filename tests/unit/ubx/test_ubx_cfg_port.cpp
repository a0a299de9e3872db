// SPDX-License-Identifier: Apache-2.0
// CFG-PRT and CFG-MSG handlers alone, on a chip with two UART1s: port 1 is
// the asking host's own UART1, the other ports are the chip's.
#include <gtest/gtest.h>

#include "core/protocol/ubx/handlers/ubx_handlers.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::HandlerRig;
using test::kUart1OfOutput1;

std::vector<std::uint8_t> prt(std::uint8_t port, std::uint32_t baud, std::uint32_t mode = 0x8C0) {
  wire::CfgPrt w{};
  w.portID = port;
  w.mode = mode;
  w.baudRate = baud;
  w.inProtoMask = 0x07;
  w.outProtoMask = 0x01;
  const auto* b = reinterpret_cast<const std::uint8_t*>(&w);
  return {b, b + sizeof w};
}

TEST(UbxCfgPort, PrtPollAnswersForTheHostsOwnUart1) {
  HandlerRig rig;
  rig.current.port(kUart1OfOutput1).baud_bps = 115200;
  for (const std::size_t uart : {0u, 1u}) {
    EXPECT_EQ(rig.call(handle_cfg_prt, msg::kCfgPrt, {}, uart), Reply::kPollData);
    const auto frames = rig.replies();
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].payload[0], kPortUart1);  // portID: every host sees UART1
    EXPECT_EQ(test::u4(frames[0].payload, 8), uart == 0 ? 9600u : 115200u);
    EXPECT_EQ(frames[1].id, msg::kAckAck);
  }
  // A portID byte asks for that port; USB is the chip's one USB.
  rig.call(handle_cfg_prt, msg::kCfgPrt, {kPortUsb}, 1);
  EXPECT_EQ(rig.replies()[0].payload[0], kPortUsb);
  EXPECT_EQ(rig.call(handle_cfg_prt, msg::kCfgPrt, {kPortUart2}, 1), Reply::kNak);  // no UART2 on a NEO-M8N
}

TEST(UbxCfgPort, PrtSetChangesTheHostsUart1AndTheSharedPorts) {
  HandlerRig rig;
  EXPECT_EQ(rig.call(handle_cfg_prt, msg::kCfgPrt, prt(kPortUart1, 38400), 1), Reply::kAck);
  EXPECT_EQ(rig.current.port(kUart1OfOutput1).baud_bps, 38400u);
  EXPECT_EQ(rig.current.port(kPortUart1).baud_bps, 9600u);  // the other output's UART1
  std::vector<std::uint8_t> usb = prt(kPortUsb, 0, 0);
  EXPECT_EQ(rig.call(handle_cfg_prt, msg::kCfgPrt, usb, 1), Reply::kAck);
  EXPECT_EQ(rig.current.port(kPortUsb).out_proto_mask, proto::kUbx);
  EXPECT_EQ(rig.current.port(kPortUsb).baud_bps, 0u);  // no baud outside UARTs
}

TEST(UbxCfgPort, PrtNaksAnyBadBlockAndAppliesNone) {
  HandlerRig rig;
  std::vector<std::uint8_t> two = prt(kPortUsb, 0, 0);
  const std::vector<std::uint8_t> bad = prt(kPortUart1, 14400);  // not a u-blox rate
  two.insert(two.end(), bad.begin(), bad.end());
  EXPECT_EQ(rig.call(handle_cfg_prt, msg::kCfgPrt, two), Reply::kNak);
  EXPECT_TRUE(rig.current == rig.defaults);
  EXPECT_EQ(rig.call(handle_cfg_prt, msg::kCfgPrt, prt(kPortUart1, 9600, 0x0C0)), Reply::kNak);  // even parity
  EXPECT_EQ(rig.call(handle_cfg_prt, msg::kCfgPrt, std::vector<std::uint8_t>(21, 0)), Reply::kNak);
  EXPECT_TRUE(rig.current == rig.defaults);
}

TEST(UbxCfgPort, MsgShortFormRatesThePortItArrivedOn) {
  HandlerRig rig;
  EXPECT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x01, 0x07, 2}, 1), Reply::kAck);
  EXPECT_EQ(rig.current.message_rate(kUart1OfOutput1, msg::kNavPvt), 2);
  EXPECT_EQ(rig.current.message_rate(kPortUart1, msg::kNavPvt), 0);
  EXPECT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x01, 0x07, 3}, 1, kPortUsb), Reply::kAck);
  EXPECT_EQ(rig.current.message_rate(kPortUsb, msg::kNavPvt), 3);
}

TEST(UbxCfgPort, MsgLongFormAndPollMapPort1ToTheHostsUart1) {
  HandlerRig rig;
  EXPECT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x01, 0x35, 0, 4, 0, 5, 0, 0}, 1), Reply::kAck);
  EXPECT_EQ(rig.current.message_rate(kUart1OfOutput1, msg::kNavSat), 4);
  EXPECT_EQ(rig.current.message_rate(kPortUart1, msg::kNavSat), 0);
  EXPECT_EQ(rig.current.message_rate(kPortUsb, msg::kNavSat), 5);
  EXPECT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x01, 0x35}, 1), Reply::kPollData);
  EXPECT_EQ(rig.replies()[0].payload, (std::vector<std::uint8_t>{0x01, 0x35, 0, 4, 0, 5, 0, 0}));
  rig.call(handle_cfg_msg, msg::kCfgMsg, {0x01, 0x35}, 0);
  EXPECT_EQ(rig.replies()[0].payload, (std::vector<std::uint8_t>{0x01, 0x35, 0, 0, 0, 5, 0, 0}));
}

TEST(UbxCfgPort, MsgNaksInputClassesAndAFullTableTakesNothing) {
  HandlerRig rig;
  EXPECT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x06, 0x00, 1}), Reply::kNak);  // CFG is input
  EXPECT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x05, 0x01}), Reply::kNak);     // ACK too
  EXPECT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x01, 0x07, 1, 1}), Reply::kNak);  // no such form
  for (std::uint8_t id = 0; rig.current.rated_messages().size() < kMaxRateEntries; ++id) {
    ASSERT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x02, id, 1}), Reply::kAck);
  }
  EXPECT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x0D, 0x01, 0, 1, 0, 1, 0, 0}), Reply::kNak);
  EXPECT_EQ(rig.current.message_rate(kPortUsb, MsgId{0x0D, 0x01}), 0);
  // Turning a message off needs no row.
  EXPECT_EQ(rig.call(handle_cfg_msg, msg::kCfgMsg, {0x0D, 0x02, 0}), Reply::kAck);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

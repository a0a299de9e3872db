// SPDX-License-Identifier: Apache-2.0
// One chip behind every output: each host configures its own UART1, while
// the navigation rate, resets, uptime and ttff are the chip's; and the order
// the chip composes an epoch's messages in.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

constexpr Link kA{0, kPortUart1};
constexpr Link kB{1, kPortUart1};

/// Two outputs: A sends NAV-STATUS, B NAV-STATUS and NAV-PVT; A at 38400 baud.
Device two_outputs() {
  DeviceSetup setup;
  OutputSetup a;
  a.baud_bps = 38400;
  a.protocols_out = proto::kUbx;
  a.rates = {{msg::kNavStatus, 1}};
  OutputSetup b;
  b.rates = {{msg::kNavStatus, 1}, {msg::kNavPvt, 1}, {msg::kNmeaGga, 1}};
  setup.outputs = {a, b};
  return Device(setup);
}

std::string send(Device& d, Link at, MsgId id, const std::vector<std::uint8_t>& payload, double now_s = 0.0) {
  std::string out;
  d.handle_ubx(at, FrameView{id, payload}, now_s, out);
  return out;
}

wire::NavStatus status(const Device& d, Link at) {
  std::string ubx;
  test::ubx_epoch(d, at, ubx);
  for (const test::Frame& f : test::split_frames(ubx)) {
    if (f.id != msg::kNavStatus) continue;
    wire::NavStatus s{};
    std::memcpy(&s, f.payload.data(), sizeof s);
    return s;
  }
  ADD_FAILURE() << "no NAV-STATUS";
  return {};
}

TEST(UbxOneChip, EveryOutputStartsWithItsOwnUart1) {
  const Device d = two_outputs();
  EXPECT_EQ(d.outputs(), 2u);
  EXPECT_EQ(d.port(kA).baud_bps, 38400u);
  EXPECT_EQ(d.port(kB).baud_bps, 9600u);
  EXPECT_EQ(d.port(kA).out_proto_mask, proto::kUbx);
  EXPECT_EQ(d.message_rate(kA, msg::kNavPvt), 0);
  EXPECT_EQ(d.message_rate(kB, msg::kNavPvt), 1);
  EXPECT_EQ(d.message_rate(kA, msg::kNmeaGga), 0);  // NMEA not listed: off
  EXPECT_EQ(d.message_rate(kB, msg::kNmeaRmc), 0);
  EXPECT_EQ(d.protocols_sent(kA), proto::kUbx);
  EXPECT_EQ(d.protocols_sent(kB), proto::kUbx | proto::kNmea);
  EXPECT_TRUE(d.saved() == d.config());  // the start-up settings are the stored configuration
}

TEST(UbxOneChip, CfgPrtFromAHostAnswersAsUart1) {
  Device d = two_outputs();
  for (const Link at : {kA, kB}) {
    const auto frames = test::split_frames(send(d, at, msg::kCfgPrt, {}));
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].payload[0], kPortUart1);
    EXPECT_EQ(test::u4(frames[0].payload, 8), at.output == 0 ? 38400u : 9600u);
  }
  // PX4 on B sets portID 1: B's line, not A's.
  wire::CfgPrt w{};
  w.portID = kPortUart1;
  w.mode = 0x8C0;
  w.baudRate = 115200;
  w.inProtoMask = 1;
  w.outProtoMask = 1;
  std::string out;
  const std::vector<std::uint8_t> p(reinterpret_cast<const std::uint8_t*>(&w), reinterpret_cast<const std::uint8_t*>(&w) + sizeof w);
  const InputResult r = d.handle_ubx(kB, FrameView{msg::kCfgPrt, p}, 0.0, out);
  EXPECT_EQ(r.reply, Reply::kAck);
  EXPECT_EQ(r.new_baud_bps, 115200u);
  EXPECT_EQ(d.port(kB).baud_bps, 115200u);
  EXPECT_EQ(d.port(kA).baud_bps, 38400u);
}

TEST(UbxOneChip, CfgRateOnOneOutputChangesThePeriodEverywhere) {
  Device d = two_outputs();
  EXPECT_DOUBLE_EQ(d.epoch_period_s(), 1.0);
  send(d, kA, msg::kCfgRate, {200, 0, 1, 0, 1, 0});
  EXPECT_DOUBLE_EQ(d.epoch_period_s(), 0.2);
  const auto frames = test::split_frames(send(d, kB, msg::kCfgRate, {}));
  EXPECT_EQ(frames[0].payload, (std::vector<std::uint8_t>{200, 0, 1, 0, 1, 0}));
  // Outside what the emulator runs: stored as set, run at the nearest rate.
  send(d, kB, msg::kCfgRate, {50, 0, 1, 0, 1, 0});
  EXPECT_DOUBLE_EQ(d.config().nav_period_s(), 0.05);
  EXPECT_DOUBLE_EQ(d.epoch_period_s(), kMinEpochPeriodS);
  send(d, kA, msg::kCfgRate, {0xD0, 0x07, 1, 0, 1, 0});  // 2 s
  EXPECT_DOUBLE_EQ(d.epoch_period_s(), kMaxEpochPeriodS);
}

TEST(UbxOneChip, AResetOnOneOutputRestartsTtffOnAnother) {
  Device d = two_outputs();
  d.power_on(100.0);
  receiver::Fix fix = test::sample_fix();
  d.on_epoch(fix, 100.5);
  EXPECT_EQ(status(d, kB).ttff, 500u);
  d.on_epoch(fix, 104.0);
  EXPECT_EQ(status(d, kB).msss, 4000u);
  // A host on A asks for a GNSS-only cold start at 104.2 s.
  std::string out;
  const std::vector<std::uint8_t> rst = {0xFF, 0xFF, 2, 0};
  const InputResult r = d.handle_ubx(kA, FrameView{msg::kCfgRst, rst}, 104.2, out);
  ASSERT_TRUE(r.reset.has_value());
  EXPECT_TRUE(r.reset->restarts_navigation());
  EXPECT_TRUE(out.empty());
  receiver::Fix none = fix;
  none.type = receiver::FixType::kNone;
  d.on_epoch(none, 105.0);
  for (const Link at : {kA, kB}) {
    EXPECT_EQ(status(d, at).ttff, 0u);
    EXPECT_EQ(status(d, at).msss, 800u);
  }
  d.on_epoch(fix, 106.2);
  EXPECT_EQ(status(d, kA).ttff, 2000u);
  EXPECT_EQ(status(d, kB).ttff, 2000u);
  // GNSS stop: the receiver keeps navigating, nothing restarts.
  d.handle_ubx(kB, FrameView{msg::kCfgRst, std::vector<std::uint8_t>{0, 0, 8, 0}}, 107.0, out);
  d.on_epoch(fix, 108.2);
  EXPECT_EQ(status(d, kA).ttff, 2000u);
  EXPECT_EQ(status(d, kA).msss, 4000u);
}

TEST(UbxOneChip, AHardwareResetLoadsTheWholeChipsSavedConfiguration) {
  Device d = two_outputs();
  send(d, kA, msg::kCfgMsg, {0x01, 0x07, 1});  // A: NAV-PVT on
  send(d, kB, msg::kCfgMsg, {0x01, 0x07, 0});  // B: NAV-PVT off
  send(d, kB, msg::kCfgRate, {200, 0, 1, 0, 1, 0});
  std::string out;
  const InputResult r = d.handle_ubx(kB, FrameView{msg::kCfgRst, std::vector<std::uint8_t>{0xFF, 0xFF, 0, 0}}, 0.0, out);
  ASSERT_TRUE(r.reset.has_value());
  EXPECT_TRUE(r.reset->reloads_saved_config());
  EXPECT_TRUE(r.nav_rate_changed);
  EXPECT_EQ(d.message_rate(kA, msg::kNavPvt), 0);
  EXPECT_EQ(d.message_rate(kB, msg::kNavPvt), 1);
  EXPECT_DOUBLE_EQ(d.epoch_period_s(), 1.0);
  EXPECT_TRUE(d.config() == d.saved());
}

TEST(UbxOneChip, LineLayoutPutsNmeaBetweenPositionAndTheRest) {
  DeviceSetup setup;
  OutputSetup o;
  o.rates = {{msg::kNavDop, 1}, {msg::kNavPvt, 1}, {msg::kNavStatus, 1}, {msg::kNavEoe, 1}, {msg::kNmeaGga, 1},
             {msg::kNmeaRmc, 1}};
  setup.outputs = {o};
  Device d(setup);
  d.on_epoch(test::sample_fix(), 1.0);
  const auto labels = [&](Layout layout) {
    MessageList list;
    d.compose({}, list, layout);
    std::vector<std::string> out;
    for (const MessageList::Message& m : list.messages()) out.emplace_back(m.label);
    EXPECT_EQ(list.messages().back().end, list.bytes().size());  // the messages cover the bytes
    return out;
  };
  EXPECT_EQ(labels(Layout::kLine),
            (std::vector<std::string>{"NAV-STATUS", "NAV-PVT", "RMC", "GGA", "NAV-DOP", "NAV-EOE"}));
  EXPECT_EQ(labels(Layout::kPerProtocol),
            (std::vector<std::string>{"NAV-STATUS", "NAV-DOP", "NAV-PVT", "NAV-EOE", "RMC", "GGA"}));
}

TEST(UbxOneChip, MessageLabels) {
  EXPECT_EQ(message_label(msg::kNavPvt), "NAV-PVT");
  EXPECT_EQ(message_label(msg::kNavTimegps), "NAV-TIMEGPS");
  EXPECT_EQ(message_label(msg::kAckAck), "ACK-ACK");
  EXPECT_EQ(message_label(msg::kAckNak), "ACK-NAK");
  EXPECT_EQ(message_label(msg::kMonVer), "MON-VER");
  EXPECT_EQ(message_label(msg::kCfgNav5), "CFG");
  EXPECT_EQ(message_label(MsgId{0x0D, 0x01}), "UBX");
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
// CFG-CFG and CFG-RST handlers alone, and the Reset they make: the saved
// configuration is the whole chip's, every output's UART1 included.
#include <gtest/gtest.h>

#include "core/protocol/ubx/handlers/ubx_handlers.hpp"
#include "core/protocol/ubx/config/ubx_reset.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::HandlerRig;
using test::kUart1OfOutput1;

std::vector<std::uint8_t> cfg_cfg(std::uint32_t clear, std::uint32_t save, std::uint32_t load) {
  wire::CfgCfg w{clear, save, load};
  const auto* b = reinterpret_cast<const std::uint8_t*>(&w);
  return {b, b + sizeof w};
}

TEST(UbxCfgSave, SaveAndLoadCoverEveryUart1) {
  HandlerRig rig;
  rig.current.port(kUart1OfOutput1).baud_bps = 115200;
  rig.current.set_message_rate(kUart1OfOutput1, msg::kNavPvt, 1);
  // A host on the first output saves the ports and rates: the second output's too.
  EXPECT_EQ(rig.call(handle_cfg_cfg, msg::kCfgCfg, cfg_cfg(0, 0x3, 0)), Reply::kAck);
  EXPECT_EQ(rig.saved.port(kUart1OfOutput1).baud_bps, 115200u);
  rig.current.port(kUart1OfOutput1).baud_bps = 9600;
  rig.current.set_message_rate(kUart1OfOutput1, msg::kNavPvt, 0);
  EXPECT_EQ(rig.call(handle_cfg_cfg, msg::kCfgCfg, cfg_cfg(0, 0, 0x3)), Reply::kAck);
  EXPECT_EQ(rig.current.port(kUart1OfOutput1).baud_bps, 115200u);
  EXPECT_EQ(rig.current.message_rate(kUart1OfOutput1, msg::kNavPvt), 1);
  // Clear, then load: factory everywhere. deviceMask (13th byte) is accepted.
  std::vector<std::uint8_t> clear_load = cfg_cfg(0xFFFF, 0, 0xFFFF);
  clear_load.push_back(0x17);
  EXPECT_EQ(rig.call(handle_cfg_cfg, msg::kCfgCfg, clear_load), Reply::kAck);
  EXPECT_TRUE(rig.current == rig.defaults);
  EXPECT_EQ(rig.call(handle_cfg_cfg, msg::kCfgCfg, std::vector<std::uint8_t>(11, 0)), Reply::kNak);
}

TEST(UbxCfgSave, ResetModesAndWhatTheyReload) {
  HandlerRig rig;
  rig.current.port(kUart1OfOutput1).baud_bps = 115200;
  // GNSS-only cold start: no answer, the configuration stays.
  EXPECT_EQ(rig.call(handle_cfg_rst, msg::kCfgRst, {0xFF, 0xFF, 2, 0}, 1), Reply::kReset);
  EXPECT_TRUE(rig.out.empty());
  ASSERT_TRUE(rig.reset.has_value());
  EXPECT_EQ(rig.reset->start(), StartKind::kCold);
  EXPECT_TRUE(rig.reset->restarts_navigation());
  EXPECT_FALSE(rig.reset->reloads_saved_config());
  EXPECT_EQ(rig.current.port(kUart1OfOutput1).baud_bps, 115200u);
  // Software reset from the other output: the saved configuration everywhere.
  EXPECT_EQ(rig.call(handle_cfg_rst, msg::kCfgRst, {0x01, 0x00, 1, 0}, 0), Reply::kReset);
  EXPECT_EQ(rig.reset->start(), StartKind::kWarm);
  EXPECT_TRUE(rig.reset->reloads_saved_config());
  EXPECT_EQ(rig.current.port(kUart1OfOutput1).baud_bps, 9600u);
  // Unknown modes and lengths: NAK, no reset.
  EXPECT_EQ(rig.call(handle_cfg_rst, msg::kCfgRst, {0, 0, 3, 0}), Reply::kNak);
  EXPECT_FALSE(rig.reset.has_value());
  EXPECT_EQ(rig.call(handle_cfg_rst, msg::kCfgRst, {0, 0, 1}), Reply::kNak);
}

TEST(UbxReset, ModesAndStartKinds) {
  const auto reset = [](std::uint16_t mask, std::uint8_t mode) { return Reset::from_wire(wire::CfgRst{mask, mode, 0}); };
  for (const int m : {0, 1, 4}) EXPECT_TRUE(reset(0, static_cast<std::uint8_t>(m))->reloads_saved_config()) << m;
  for (const int m : {2, 8, 9}) EXPECT_FALSE(reset(0, static_cast<std::uint8_t>(m))->reloads_saved_config()) << m;
  EXPECT_FALSE(reset(0, 8)->restarts_navigation());  // GNSS stop: not modelled
  EXPECT_TRUE(reset(0, 9)->restarts_navigation());
  for (const int m : {3, 5, 6, 7, 10, 255}) EXPECT_FALSE(reset(0, static_cast<std::uint8_t>(m)).has_value()) << m;
  EXPECT_EQ(reset(0x0000, 0)->start_name(), "hot");
  EXPECT_EQ(reset(0x0001, 0)->start_name(), "warm");
  EXPECT_EQ(reset(0x00F0, 0)->start_name(), "warm");
  EXPECT_EQ(reset(0xFFFF, 0)->start_name(), "cold");
  EXPECT_EQ(reset(0, 9)->mode_number(), 9u);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

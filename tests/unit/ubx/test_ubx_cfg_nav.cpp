// SPDX-License-Identifier: Apache-2.0
// CFG-RATE, CFG-NAV5 and CFG-GNSS handlers alone: the chip-wide navigation
// settings, whichever output a host is on.
#include <gtest/gtest.h>

#include "core/protocol/ubx/handlers/ubx_handlers.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::HandlerRig;

TEST(UbxCfgNav, RateSetAndPollAreChipWide) {
  HandlerRig rig;
  EXPECT_EQ(rig.call(handle_cfg_rate, msg::kCfgRate, {200, 0, 2, 0, 0, 0}, 1), Reply::kAck);
  EXPECT_DOUBLE_EQ(rig.current.nav_period_s(), 0.4);
  rig.call(handle_cfg_rate, msg::kCfgRate, {}, 0);
  EXPECT_EQ(rig.replies()[0].payload, (std::vector<std::uint8_t>{200, 0, 2, 0, 0, 0}));
  EXPECT_EQ(rig.call(handle_cfg_rate, msg::kCfgRate, {24, 0, 1, 0, 0, 0}), Reply::kNak);    // < 25 ms
  EXPECT_EQ(rig.call(handle_cfg_rate, msg::kCfgRate, {200, 0, 0, 0, 0, 0}), Reply::kNak);   // navRate 0
  EXPECT_EQ(rig.call(handle_cfg_rate, msg::kCfgRate, {200, 0, 128, 0, 0, 0}), Reply::kNak); // navRate > 127
  EXPECT_EQ(rig.call(handle_cfg_rate, msg::kCfgRate, {200, 0, 1, 0, 5, 0}), Reply::kNak);   // timeRef
  EXPECT_EQ(rig.call(handle_cfg_rate, msg::kCfgRate, {200, 0, 1, 0, 0}), Reply::kNak);      // length
  EXPECT_DOUBLE_EQ(rig.current.nav_period_s(), 0.4);
}

TEST(UbxCfgNav, Nav5AppliesTheMaskedFieldsOnly) {
  HandlerRig rig;
  std::vector<std::uint8_t> nav5(36, 0);
  nav5[0] = 0x02;  // minElev only
  nav5[2] = 1;     // reserved dynModel: not in the mask, so not checked
  nav5[12] = 15;
  EXPECT_EQ(rig.call(handle_cfg_nav5, msg::kCfgNav5, nav5), Reply::kAck);
  EXPECT_EQ(rig.current.nav5.minElev, 15);
  EXPECT_EQ(rig.current.nav5.dynModel, 0);
  EXPECT_EQ(rig.current.nav5.mask, 0xFFFF);  // a poll reports every field
  nav5[0] = 0x01;
  EXPECT_EQ(rig.call(handle_cfg_nav5, msg::kCfgNav5, nav5), Reply::kNak);
  nav5[0] = 0x04;
  nav5[3] = 4;  // fixMode outside 1..3
  EXPECT_EQ(rig.call(handle_cfg_nav5, msg::kCfgNav5, nav5), Reply::kNak);
  EXPECT_EQ(rig.current.nav5.fixMode, 3);
}

TEST(UbxCfgNav, GnssMergesBlocksByGnssId) {
  HandlerRig rig;
  // Galileo on (block for gnssId 2), numTrkChUse 0xFF: keep the stored one.
  EXPECT_EQ(rig.call(handle_cfg_gnss, msg::kCfgGnss, {0, 32, 0xFF, 1, 2, 4, 8, 0, 1, 0, 1, 1}), Reply::kAck);
  rig.call(handle_cfg_gnss, msg::kCfgGnss, {});
  const auto p = rig.replies()[0].payload;
  ASSERT_EQ(p.size(), 60u);  // still 7 blocks
  EXPECT_EQ(p[2], 32);
  EXPECT_EQ(p[4 + 8 * 2], 2);
  EXPECT_EQ(test::u4(p, 4 + 8 * 2 + 4), 0x01010001u);
  EXPECT_EQ(test::u4(p, 4 + 4), 0x01010001u);  // GPS untouched
  const DeviceConfig before = rig.current;
  EXPECT_EQ(rig.call(handle_cfg_gnss, msg::kCfgGnss, {0, 32, 32, 1, 7, 0, 0, 0, 0, 0, 0, 0}), Reply::kNak);  // gnssId 7
  EXPECT_EQ(rig.call(handle_cfg_gnss, msg::kCfgGnss, {0, 32, 32, 2, 0, 0, 0, 0, 0, 0, 0, 0}), Reply::kNak);  // 2 blocks, 1 sent
  EXPECT_EQ(rig.call(handle_cfg_gnss, msg::kCfgGnss, {1, 32, 32, 0}), Reply::kNak);                           // msgVer
  EXPECT_TRUE(rig.current == before);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
// Handlers of the CFG messages kept verbatim (the table's stored rows,
// CFG-TP5, CFG-INF, CFG-DAT, CFG-RINV, CFG-GEOFENCE, CFG-PWR) alone, and
// the handler table itself.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/protocol/ubx/handlers/ubx_handlers.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::HandlerRig;

TEST(UbxCfgStored, TableRowsSetTheirLengthsAndRoundTrip) {
  const MsgId stored[] = {msg::kCfgSbas, msg::kCfgItfm, msg::kCfgNavx5, msg::kCfgPm2, msg::kCfgRxm, msg::kCfgUsb,
                          msg::kCfgAnt,  msg::kCfgOdo,  msg::kCfgNmea,  msg::kCfgPms, msg::kCfgLogfilter};
  for (const MsgId id : stored) {
    SCOPED_TRACE(id.key());
    EXPECT_EQ(find_handler(id), &handle_cfg_stored);
    HandlerRig rig;
    std::uint16_t len = 0;  // the longest form
    for (const std::uint16_t l : stored_set_lengths(id)) len = std::max(len, l);
    ASSERT_GT(len, 0);
    std::vector<std::uint8_t> set(len, 0x5A);
    EXPECT_EQ(rig.call(handle_cfg_stored, id, set), Reply::kAck);
    rig.call(handle_cfg_stored, id, {});
    EXPECT_EQ(rig.replies()[0].payload, set);
    set.push_back(0);
    EXPECT_EQ(rig.call(handle_cfg_stored, id, set), Reply::kNak);
  }
}

TEST(UbxCfgStored, ShortCfgNmeaSetsAPrefix) {
  HandlerRig rig;
  EXPECT_EQ(rig.call(handle_cfg_stored, msg::kCfgNmea, {0, 0x23, 0, 0}), Reply::kAck);  // NMEA 2.3
  rig.call(handle_cfg_stored, msg::kCfgNmea, {});
  const auto p = rig.replies()[0].payload;
  ASSERT_EQ(p.size(), 20u);
  EXPECT_EQ(p[1], 0x23);
  EXPECT_EQ(p[11], 1);  // the rest as stored (version 1 field)
}

TEST(UbxCfgStored, IndexedAndPollFormMessages) {
  HandlerRig rig;
  std::vector<std::uint8_t> tp5(32, 0);
  tp5[0] = 1;
  EXPECT_EQ(rig.call(handle_cfg_tp5, msg::kCfgTp5, tp5), Reply::kAck);
  rig.call(handle_cfg_tp5, msg::kCfgTp5, {1});
  EXPECT_EQ(rig.replies()[0].payload, tp5);
  tp5[0] = 2;
  EXPECT_EQ(rig.call(handle_cfg_tp5, msg::kCfgTp5, tp5), Reply::kNak);  // tpIdx 0..1
  EXPECT_EQ(rig.call(handle_cfg_tp5, msg::kCfgTp5, {2}), Reply::kNak);

  EXPECT_EQ(rig.call(handle_cfg_inf, msg::kCfgInf, {1, 0, 0, 0, 1, 1, 0, 1, 1, 0}), Reply::kAck);
  rig.call(handle_cfg_inf, msg::kCfgInf, {1});
  EXPECT_EQ(rig.replies()[0].payload, (std::vector<std::uint8_t>{1, 0, 0, 0, 1, 1, 0, 1, 1, 0}));
  EXPECT_EQ(rig.call(handle_cfg_inf, msg::kCfgInf, {2, 0, 0, 0, 1, 1, 0, 1, 1, 0}), Reply::kNak);  // protocolID
  EXPECT_EQ(rig.call(handle_cfg_inf, msg::kCfgInf, {}), Reply::kNak);

  EXPECT_EQ(rig.call(handle_cfg_dat, msg::kCfgDat, std::vector<std::uint8_t>(44, 1)), Reply::kAck);
  rig.call(handle_cfg_dat, msg::kCfgDat, {});
  const auto dat = rig.replies()[0].payload;
  ASSERT_EQ(dat.size(), 52u);  // poll form: datumNum 0xFFFF, "USER", then the set
  EXPECT_EQ(test::u2(dat, 0), 0xFFFFu);
  EXPECT_EQ(dat[2], 'U');
  EXPECT_EQ(dat[51], 1);

  EXPECT_EQ(rig.call(handle_cfg_rinv, msg::kCfgRinv, {0, 'h', 'i'}), Reply::kAck);
  EXPECT_EQ(rig.call(handle_cfg_rinv, msg::kCfgRinv, std::vector<std::uint8_t>(32, 0)), Reply::kNak);
  std::vector<std::uint8_t> fence(20, 0);
  fence[1] = 1;  // one fence
  EXPECT_EQ(rig.call(handle_cfg_geofence, msg::kCfgGeofence, fence), Reply::kAck);
  fence[1] = 2;
  EXPECT_EQ(rig.call(handle_cfg_geofence, msg::kCfgGeofence, fence), Reply::kNak);
  EXPECT_EQ(rig.call(handle_cfg_pwr, msg::kCfgPwr, std::vector<std::uint8_t>(8, 0)), Reply::kAck);
  EXPECT_EQ(rig.call(handle_cfg_pwr, msg::kCfgPwr, {}), Reply::kNak);
}

TEST(UbxHandlers, TableRoutesEveryClass) {
  EXPECT_EQ(find_handler(msg::kCfgPrt), &handle_cfg_prt);
  EXPECT_EQ(find_handler(msg::kCfgRst), &handle_cfg_rst);
  EXPECT_EQ(find_handler(msg::kCfgValset), &handle_cfg_valset);  // an M8 still NAKs it (test_ubx_cfg_val.cpp)
  EXPECT_EQ(find_handler(MsgId{0x06, 0x70}), &handle_cfg_dgnss);  // CFG-DGNSS: an F9P's; an M8N NAKs it
  EXPECT_FALSE(cfg_message_exists(MsgId{0x06, 0x70}, Generation::kM8));
  EXPECT_EQ(find_handler(MsgId{0x06, 0x7F}), &handle_cfg_unknown);
  EXPECT_EQ(find_handler(msg::kMonVer), &handle_mon_ver);
  EXPECT_EQ(find_handler(msg::kNavPvt), &handle_output_poll);
  EXPECT_EQ(find_handler(msg::kMonHw), &handle_output_poll);
  EXPECT_EQ(find_handler(msg::kAckAck), nullptr);
  EXPECT_EQ(find_handler(MsgId{0x0A, 0x06}), nullptr);  // MON-MSGPP: not answered
  HandlerRig rig;
  EXPECT_EQ(rig.call(handle_cfg_unknown, msg::kCfgValget, {}), Reply::kNak);
  EXPECT_EQ(rig.call(handle_output_poll, msg::kNavPvt, {}), Reply::kPollData);
  EXPECT_EQ(rig.replies()[0].payload.size(), 92u);
  EXPECT_EQ(rig.call(handle_output_poll, msg::kNavPvt, {1}), Reply::kNone);      // not a poll
  EXPECT_EQ(rig.call(handle_output_poll, MsgId{0x01, 0x22}, {}), Reply::kNone);  // NAV-CLOCK: not encoded
  EXPECT_EQ(rig.call(handle_mon_ver, msg::kMonVer, {}), Reply::kPollData);
  EXPECT_EQ(rig.call(handle_mon_ver, msg::kMonVer, {0}), Reply::kNone);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

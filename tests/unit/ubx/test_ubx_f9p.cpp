// SPDX-License-Identifier: Apache-2.0
// The ZED-F9P generation: its identity, the keys only it knows (and what
// they leave in Device::hpg_settings()), the legacy CFG messages it keeps
// or dropped, and its high-precision output messages decoded field by field
// from Fix values set here (docs/ubx.md §ZED-F9P).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/common/constants.hpp"
#include "core/protocol/rtcm/rtcm_ublox.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/config/ubx_hpg.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace f9p_test {  // named: the unity build shares one translation unit with test_ubx_cfg_val.cpp

using receiver::CarrierSolution;

constexpr std::uint32_t kDgnssMode = 0x20140011, kDgnssTo = 0x201100C4, kUart2Baud = 0x40530001,
                        kUart2InRtcm = 0x10750004, kUart2OutRtcm = 0x10760004, kTmodeMode = 0x20030001,
                        kTmodeEcefX = 0x40030003, kTmodeEcefXHp = 0x20030006, kTmodeSvinDur = 0x40030010,
                        kRateMeas = 0x30210001, kGpsL2 = 0x10310003, kGpsL1 = 0x10310001,
                        kRelposnedUart1 = 0x2091008E, kHpposllhUart1 = 0x20910034;

DeviceSetup setup_of(Generation g) {
  DeviceSetup s;
  s.mon_ver = mon_ver_of(g);
  return s;
}

void put(std::vector<std::uint8_t>& p, std::uint64_t v, std::size_t bytes) {
  for (std::size_t i = 0; i < bytes; ++i) p.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

std::vector<std::uint8_t> valset(const std::vector<std::pair<std::uint32_t, std::uint64_t>>& kv) {
  std::vector<std::uint8_t> p{0, 1, 0, 0};  // version 0, RAM
  for (const auto& [key, value] : kv) {
    put(p, key, 4);
    put(p, value, ConfigKey::value_bytes_of(key));
  }
  return p;
}

struct Host {
  explicit Host(Device& d) : dev(d) {}
  Device& dev;
  std::string out;
  InputResult last;
  std::vector<test::Frame> send(MsgId id, const std::vector<std::uint8_t>& payload) {
    out.clear();
    last = dev.handle_ubx({}, FrameView{id, payload}, 0.0, out);
    return test::split_frames(out);
  }
  bool acked(MsgId id, const std::vector<std::uint8_t>& payload) {
    const auto f = send(id, payload);
    return !f.empty() && f.back().id == msg::kAckAck;
  }
};

template <class Wire>
Wire only(const std::string& out, MsgId id) {
  const auto frames = test::split_frames(out);
  Wire w{};
  EXPECT_EQ(frames.size(), 1u);
  if (frames.size() != 1) return w;
  EXPECT_EQ(frames[0].id, id);
  EXPECT_EQ(frames[0].payload.size(), sizeof(Wire));
  if (frames[0].payload.size() == sizeof(Wire)) std::memcpy(&w, frames[0].payload.data(), sizeof w);
  return w;
}

std::string ext(const std::vector<std::uint8_t>& p, std::size_t i) {
  return std::string(reinterpret_cast<const char*>(p.data() + 40 + 30 * i));
}

TEST(UbxF9p, MonVerIsAZedF9pWithHpg132) {
  Device d(setup_of(Generation::kF9P));
  Host h(d);
  const auto f = h.send(msg::kMonVer, {});
  ASSERT_EQ(f.size(), 1u);
  const auto& p = f[0].payload;
  ASSERT_EQ(p.size(), 40u + 30u * 6u);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(p.data())), "EXT CORE 1.00 (f4c834)");
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(p.data() + 30)), "00190000");
  EXPECT_EQ(ext(p, 0), "ROM BASE 0x118B2060");
  EXPECT_EQ(ext(p, 1), "FWVER=HPG 1.32");
  EXPECT_EQ(ext(p, 2), "PROTVER=27.31");
  EXPECT_EQ(ext(p, 3), "MOD=ZED-F9P");
  EXPECT_EQ(ext(p, 4), "GPS;GLO;GAL;BDS");
  EXPECT_EQ(ext(p, 5), "SBAS;QZSS");
  EXPECT_EQ(generation_name(Generation::kF9P), "f9p");
}

TEST(UbxF9p, HpgKeysAreTheF9psAndAnUnknownKeyNaksTheWholeValset) {
  Device m9(setup_of(Generation::kM9));
  Host hm9(m9);
  EXPECT_FALSE(hm9.acked(msg::kCfgValset, valset({{kDgnssMode, 3}})));  // PX4's RTK probe: an M9N NAKs it
  EXPECT_FALSE(hm9.acked(msg::kCfgValset, valset({{kGpsL2, 1}})));

  Device d(setup_of(Generation::kF9P));
  Host h(d);
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset({{kDgnssMode, 3}})));
  // A key no generation knows (or an M9-only one the F9P lacks) rejects every pair with it.
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset({{kRateMeas, 200}, {0x10310099, 1}})));
  EXPECT_EQ(d.config().rate.measRate, 1000);
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset({{kDgnssMode, 1}})));  // values 2, 3 only
}

TEST(UbxF9p, HpgSettingsFollowTheKeys) {
  Device d(setup_of(Generation::kF9P));
  const HpgSettings f = d.hpg_settings();
  EXPECT_EQ(f.dgnss_mode, DgnssMode::kRtkFixed);
  EXPECT_DOUBLE_EQ(f.dgnss_timeout_s, 60.0);
  EXPECT_EQ(f.uart2.baud_bps, 38400u);
  EXPECT_EQ(f.uart2.in_proto_mask & proto::kRtcm3, proto::kRtcm3);
  EXPECT_EQ(f.tmode.mode, TimeMode::kDisabled);
  EXPECT_DOUBLE_EQ(f.tmode.svin_min_dur_s, 60.0);

  Host h(d);
  // ECEF X = 4278387.5432 m: 427838754 cm + 32 x 0.1 mm.
  ASSERT_TRUE(h.acked(msg::kCfgValset,
                      valset({{kDgnssMode, 2}, {kDgnssTo, 10}, {kUart2Baud, 460800}, {kUart2InRtcm, 1},
                              {kUart2OutRtcm, 0}, {kTmodeMode, 2}, {kTmodeEcefX, 427838754}, {kTmodeEcefXHp, 32},
                              {kTmodeSvinDur, 120}})));
  EXPECT_TRUE(h.last.hpg_changed);
  const HpgSettings s = d.hpg_settings();
  EXPECT_EQ(s.dgnss_mode, DgnssMode::kRtkFloat);
  EXPECT_DOUBLE_EQ(s.dgnss_timeout_s, 10.0);
  EXPECT_EQ(s.uart2.baud_bps, 460800u);
  EXPECT_EQ(s.uart2.out_proto_mask & proto::kRtcm3, 0);
  EXPECT_EQ(s.tmode.mode, TimeMode::kFixed);
  EXPECT_NEAR(s.tmode.ecef_m[0], 4278387.5432, 1e-6);
  EXPECT_DOUBLE_EQ(s.tmode.svin_min_dur_s, 120.0);
  // Negative HP parts come back signed.
  ASSERT_TRUE(h.acked(msg::kCfgValset, valset({{kTmodeEcefX, static_cast<std::uint32_t>(-5)}, {kTmodeEcefXHp, 0xF6}})));
  EXPECT_NEAR(d.hpg_settings().tmode.ecef_m[0], -0.051, 1e-9);
}

TEST(UbxF9p, SecondBandKeysNeedTheFirst) {
  Device d(setup_of(Generation::kF9P));
  Host h(d);
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset({{kGpsL2, 0}})));   // L1 only: fine
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset({{kGpsL2, 1}})));
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset({{kGpsL1, 0}})));  // L2C alone: not a configuration the F9P runs
}

TEST(UbxF9p, LegacyCfgKeptAndDropped) {
  Device d(setup_of(Generation::kF9P));
  Host h(d);
  // Dropped with protocol 27 on the F9P: CFG-PM2, CFG-RXM, CFG-PMS (polls NAKed).
  for (const MsgId id : {msg::kCfgPm2, msg::kCfgRxm, msg::kCfgPms}) {
    const auto f = h.send(id, {});
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].id, msg::kAckNak);
  }
  // Kept: CFG-RATE (and CFG-PRT, CFG-MSG, CFG-NAV5, CFG-GNSS: test_ubx_cfg_*).
  EXPECT_TRUE(h.acked(msg::kCfgRate, {0xC8, 0x00, 0x01, 0x00, 0x01, 0x00}));
  EXPECT_EQ(d.config().rate.measRate, 200);
  // CFG-DGNSS reads and writes CFG-NAVHPG-DGNSSMODE.
  EXPECT_TRUE(h.acked(msg::kCfgDgnss, {2, 0, 0, 0}));
  EXPECT_EQ(d.hpg_settings().dgnss_mode, DgnssMode::kRtkFloat);
  EXPECT_FALSE(h.acked(msg::kCfgDgnss, {4, 0, 0, 0}));
  auto f = h.send(msg::kCfgDgnss, {});
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].payload[0], 2);
  // CFG-TMODE3 fixed LLH and its poll.
  std::vector<std::uint8_t> t{0, 0};
  put(t, 0x0102, 2);  // fixed, lla
  put(t, 473977420, 4);
  put(t, 85455940, 4);
  put(t, 50000, 4);
  t.push_back(12);
  t.push_back(static_cast<std::uint8_t>(-7));
  t.push_back(3);
  t.push_back(0);
  put(t, 100, 4);
  put(t, 300, 4);
  put(t, 200, 4);
  put(t, 0, 8);
  ASSERT_EQ(t.size(), 40u);
  EXPECT_TRUE(h.acked(msg::kCfgTmode3, t));
  const HpgSettings s = d.hpg_settings();
  EXPECT_EQ(s.tmode.mode, TimeMode::kFixed);
  EXPECT_TRUE(s.tmode.llh);
  EXPECT_NEAR(s.tmode.lat_deg, 47.397742012, 1e-12);
  EXPECT_NEAR(s.tmode.lon_deg, 8.545593993, 1e-12);
  EXPECT_NEAR(s.tmode.height_m, 500.0003, 1e-9);
  EXPECT_DOUBLE_EQ(s.tmode.svin_min_dur_s, 300.0);
  f = h.send(msg::kCfgTmode3, {});
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].payload, t);
  // An M9 has neither.
  Device m9(setup_of(Generation::kM9));
  Host hm9(m9);
  EXPECT_FALSE(hm9.acked(msg::kCfgDgnss, {3, 0, 0, 0}));
}

TEST(UbxF9p, HpSplitKeepsTheSignAndTheTenthMillimetre) {
  EXPECT_EQ(hp_split(1.23456, 1e-4).coarse, 123);
  EXPECT_EQ(hp_split(1.23456, 1e-4).hp, 46);
  EXPECT_EQ(hp_split(-1.23456, 1e-4).coarse, -123);
  EXPECT_EQ(hp_split(-1.23456, 1e-4).hp, -46);
  EXPECT_EQ(hp_split(47.3977420123, 1e-9).coarse, 473977420);
  EXPECT_EQ(hp_split(47.3977420123, 1e-9).hp, 12);
  EXPECT_EQ(hp_split(500.00037, 1e-4, 10).coarse, 500000);
  EXPECT_EQ(hp_split(500.00037, 1e-4, 10).hp, 4);
  EXPECT_EQ(hp_split(std::nan(""), 1e-4).coarse, 0);
}

TEST(UbxF9p, NavPvtCarriesTheRtkState) {
  const UbxEncoder f9p(mon_ver_of(Generation::kF9P));
  receiver::Fix fix = test::sample_fix();
  fix.diff_soln = true;
  fix.carr_soln = CarrierSolution::kFixed;
  fix.corr_age_s = 1.4;
  std::string out;
  f9p.nav_pvt(fix, out);
  auto m = only<wire::NavPvt>(out, msg::kNavPvt);
  EXPECT_EQ(m.flags & 0x03, 0x03);         // gnssFixOK, diffSoln
  EXPECT_EQ(m.flags >> 6, 2);              // carrSoln fixed
  EXPECT_EQ(m.flags3 >> 1 & 0x0F, 2);      // lastCorrectionAge: [1, 2) s
  fix.carr_soln = CarrierSolution::kFloat;
  fix.corr_age_s = 200.0;
  out.clear();
  f9p.nav_pvt(fix, out);
  m = only<wire::NavPvt>(out, msg::kNavPvt);
  EXPECT_EQ(m.flags >> 6, 1);
  EXPECT_EQ(m.flags3 >> 1 & 0x0F, 12);
  fix.diff_soln = false;
  fix.carr_soln = CarrierSolution::kNone;
  fix.corr_age_s = -1.0;
  out.clear();
  f9p.nav_pvt(fix, out);
  m = only<wire::NavPvt>(out, msg::kNavPvt);
  EXPECT_EQ(m.flags, 0x01);
  EXPECT_EQ(m.flags3, 0);
}

TEST(UbxF9p, HighPrecisionPositions) {
  receiver::Fix fix = test::sample_fix();
  fix.h_acc_m = 0.0142;
  fix.v_acc_m = 0.0213;
  std::string out;
  nav_hpposllh(fix, out);
  const auto llh = only<wire::NavHpposllh>(out, msg::kNavHpposllh);
  EXPECT_EQ(llh.flags, 0);
  EXPECT_NEAR((llh.lat + 0.01 * llh.latHp) * 1e-7, fix.lla.lat_rad * kRadToDeg, 1e-9);
  EXPECT_NEAR((llh.lon + 0.01 * llh.lonHp) * 1e-7, fix.lla.lon_rad * kRadToDeg, 1e-9);
  EXPECT_NEAR((llh.height + 0.1 * llh.heightHp) * 1e-3, fix.lla.height_m, 1e-4);
  EXPECT_EQ(llh.hAcc, 142u);
  EXPECT_EQ(llh.vAcc, 213u);
  out.clear();
  nav_hpposecef(fix, out);
  const auto ecef = only<wire::NavHpposecef>(out, msg::kNavHpposecef);
  EXPECT_NEAR((ecef.ecefX + 0.01 * ecef.ecefXHp) * 1e-2, fix.pos_m.x, 1e-4);
  EXPECT_NEAR((ecef.ecefZ + 0.01 * ecef.ecefZHp) * 1e-2, fix.pos_m.z, 1e-4);
  EXPECT_EQ(ecef.pAcc, static_cast<std::uint32_t>(std::lround(std::hypot(0.0142, 0.0213) * 1e4)));
  fix.type = receiver::FixType::kNone;
  out.clear();
  nav_hpposllh(fix, out);
  EXPECT_EQ(only<wire::NavHpposllh>(out, msg::kNavHpposllh).flags, 1);
}

TEST(UbxF9p, RelPosNedVersion1) {
  receiver::Fix fix = test::sample_fix();
  fix.diff_soln = true;
  fix.carr_soln = CarrierSolution::kFixed;
  receiver::RelativePosition& r = fix.rel_pos;
  r.valid = true;
  r.moving_base = true;
  r.carr_soln = CarrierSolution::kFixed;
  r.ref_station_id = 17;
  r.n_m = 0.51234;
  r.e_m = -0.86612;
  r.d_m = 0.0031;
  r.length_m = std::sqrt(r.n_m * r.n_m + r.e_m * r.e_m + r.d_m * r.d_m);
  r.heading_rad = std::atan2(r.e_m, r.n_m) + 2.0 * kPi;
  r.heading_valid = true;
  r.acc_n_m = r.acc_e_m = 0.0041;
  r.acc_d_m = 0.0087;
  r.acc_length_m = 0.0045;
  r.acc_heading_rad = 0.3 * kDegToRad;
  std::string out;
  nav_relposned(fix, out);
  const auto m = only<wire::NavRelposnedV1>(out, msg::kNavRelposned);
  EXPECT_EQ(m.version, 1);
  EXPECT_EQ(m.refStationId, 17);
  EXPECT_EQ(m.iTOW, itow_ms(fix));
  EXPECT_EQ(m.relPosN, 51);
  EXPECT_EQ(m.relPosHPN, 23);
  EXPECT_EQ(m.relPosE, -86);
  EXPECT_EQ(m.relPosHPE, -61);
  EXPECT_NEAR((m.relPosLength + 0.01 * m.relPosHPLength) * 1e-2, r.length_m, 1e-4);
  EXPECT_NEAR(m.relPosHeading * 1e-5, std::fmod(r.heading_rad * kRadToDeg, 360.0), 1e-5);
  EXPECT_EQ(m.accN, 41u);
  EXPECT_EQ(m.accHeading, 30000u);
  // gnssFixOK, diffSoln, relPosValid, carrSoln fixed, isMoving, relPosHeadingValid.
  EXPECT_EQ(m.flags, 0x1u | 0x2u | 0x4u | 2u << 3 | 0x20u | 0x100u);
  // A moving-base rover's time-matched baseline of the previous epoch: its iTOW.
  r.late = true;
  r.t = fix.t - 0.2;
  out.clear();
  nav_relposned(fix, out);
  EXPECT_EQ(only<wire::NavRelposnedV1>(out, msg::kNavRelposned).iTOW + 200u, itow_ms(fix));
  r.late = false;
  r.valid = false;
  r.ref_obs_miss = true;
  out.clear();
  nav_relposned(fix, out);
  const auto lost = only<wire::NavRelposnedV1>(out, msg::kNavRelposned);
  EXPECT_EQ(lost.flags & 0x104u, 0u);  // neither relPosValid nor relPosHeadingValid
  EXPECT_EQ(lost.flags & 0x80u, 0x80u);
  EXPECT_EQ(lost.relPosLength, 0);
}

TEST(UbxF9p, RxmCorForAnRtcmMessage) {
  std::string out;
  rxm_cor_rtcm(4072, 0, true, true, out);
  const auto m = only<wire::RxmCor>(out, msg::kRxmCor);
  EXPECT_EQ(m.version, 1);
  EXPECT_EQ(m.statusInfo & 0x1F, 1u);       // RTCM3
  EXPECT_EQ(m.statusInfo >> 5 & 3, 1u);     // error-free
  EXPECT_EQ(m.statusInfo >> 7 & 3, 2u);     // used
  EXPECT_EQ(m.statusInfo >> 25 & 3, 3u);    // msgType and msgSubType valid
  EXPECT_EQ(m.msgType, 4072);
}

TEST(UbxF9p, BothBandsInNavSigAndMonRf) {
  const UbxEncoder f9p(mon_ver_of(Generation::kF9P));
  const receiver::Fix fix = test::sample_fix();
  std::string out;
  f9p.nav_sig(fix, out);
  auto frames = test::split_frames(out);
  ASSERT_EQ(frames.size(), 1u);
  const auto& p = frames[0].payload;
  const std::size_t n = p[5];
  ASSERT_EQ(p.size(), 8u + 16u * n);
  int gps_l1 = 0, gps_l2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* s = p.data() + 8 + 16 * i;
    if (s[0] == 0 && s[2] == 0) ++gps_l1;
    if (s[0] == 0 && s[2] == 3) ++gps_l2;  // GPS L2 CL
  }
  EXPECT_GT(gps_l1, 0);
  EXPECT_EQ(gps_l1, gps_l2);
  out.clear();
  f9p.mon_rf(fix, {}, out);
  frames = test::split_frames(out);
  ASSERT_EQ(frames.size(), 1u);
  ASSERT_EQ(frames[0].payload.size(), 4u + 2u * 24u);
  EXPECT_EQ(frames[0].payload[1], 2);      // nBlocks
  EXPECT_EQ(frames[0].payload[4 + 24], 1);  // blockId 1: L2/L5
}

TEST(UbxF9p, HpMessagesGoOutWhereEnabledAndOnlyOnTheF9p) {
  EXPECT_TRUE(message_exists(msg::kNavRelposned, Generation::kF9P));
  EXPECT_FALSE(message_exists(msg::kNavRelposned, Generation::kM9));
  EXPECT_FALSE(message_exists(msg::kNavHpposllh, Generation::kM8));
  Device d(setup_of(Generation::kF9P));
  Host h(d);
  ASSERT_TRUE(h.acked(msg::kCfgValset, valset({{kRelposnedUart1, 1}, {kHpposllhUart1, 1}, {0x20910007, 1}})));
  receiver::Fix fix = test::sample_fix();
  fix.rel_pos.valid = true;
  d.on_epoch(fix, 1.0);
  std::string out;
  test::ubx_epoch(d, {}, out);
  std::vector<MsgId> ids;
  for (const auto& f : test::split_frames(out)) ids.push_back(f.id);
  EXPECT_NE(std::find(ids.begin(), ids.end(), msg::kNavRelposned), ids.end());
  EXPECT_NE(std::find(ids.begin(), ids.end(), msg::kNavHpposllh), ids.end());
  EXPECT_NE(std::find(ids.begin(), ids.end(), msg::kNavPvt), ids.end());
  // An M9 NAKs the key (PX4-Autopilot#21914: a NEO-M9N NAKs MSGOUT_UBX_NAV_HPPOSLLH).
  Device m9(setup_of(Generation::kM9));
  Host hm9(m9);
  EXPECT_FALSE(hm9.acked(msg::kCfgValset, valset({{kHpposllhUart1, 1}})));
}

// A moving-base rover whose base epoch comes within the epoch period
// (docs/rtk.md "Relative position"): epoch k's output carries no
// RELPOSNED (held), the arrival sends it alone with epoch k's iTOW, and the
// next epoch's NAV-PVT follows: PVT(k), RELPOSNED(k), PVT(k + 1) on the wire.
TEST(UbxF9p, HeldRelposnedGoesOutWhenItsBaseEpochArrives) {
  Device d(setup_of(Generation::kF9P));
  Host h(d);
  ASSERT_TRUE(h.acked(msg::kCfgValset, valset({{kRelposnedUart1, 1}, {0x20910007, 1}})));
  const auto itow_of = [](const test::Frame& f, std::size_t at) {
    std::uint32_t v = 0;
    std::memcpy(&v, f.payload.data() + at, 4);
    return v;
  };
  const auto frames_of = [](const MessageList& list) {
    std::string bytes;
    for (const auto& m : list.messages()) bytes += list.bytes(m);
    return test::split_frames(bytes);
  };
  receiver::Fix fix = test::sample_fix();
  fix.rel_pos.moving_base = true;
  fix.rel_pos.held = true;
  fix.rel_pos.t = fix.t;
  std::vector<std::uint32_t> pvt_itow;
  MessageList list;
  for (int k = 0; k < 2; ++k) {
    d.on_epoch(fix, 1.0 + 0.2 * k);
    d.compose(Link{}, list);
    int relposned = 0;
    for (const auto& f : frames_of(list)) {
      if (f.id == msg::kNavPvt) pvt_itow.push_back(itow_of(f, 0));
      relposned += f.id == msg::kNavRelposned ? 1 : 0;
    }
    EXPECT_EQ(relposned, 0) << k;  // held for its base epoch
    ASSERT_EQ(pvt_itow.size(), static_cast<std::size_t>(k + 1));
    d.compose_relposned(Link{}, list);
    EXPECT_TRUE(list.messages().empty()) << k;  // nothing until it arrives
    if (k == 1) break;
    receiver::RelativePosition rp;
    rp.valid = rp.moving_base = rp.heading_valid = true;
    rp.carr_soln = receiver::CarrierSolution::kFixed;
    rp.n_m = rp.length_m = 1.0;
    rp.t = fix.t;
    d.on_relative_position(rp);
    d.compose_relposned(Link{}, list);
    const auto got = frames_of(list);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].id, msg::kNavRelposned);
    EXPECT_EQ(itow_of(got[0], 4), pvt_itow[0]);  // the epoch's own NAV-PVT iTOW
    fix.t = fix.t + 0.2;
    fix.rel_pos.t = fix.t;
  }
  EXPECT_EQ(pvt_itow[1], pvt_itow[0] + 200);  // the next epoch's NAV-PVT comes after it
}

// ArduPilot's GPS_TYPE 17 list (docs/ubx.md "ArduPilot F9P"): RTCM 3 out on
// UART1 and CFG-MSGOUT-RTCM_3X 4072.0 and 1077 there; each epoch then
// carries them, framed, the 4072.0 with the fix's position. Off again
// without RTCM 3 in the port's outProtoMask.
TEST(UbxF9p, MovingBaseSendsTheRtcmItsKeysEnable) {
  constexpr std::uint32_t kUart1OutRtcm = 0x10740004, k4072Uart1 = 0x209102FF, k1077Uart1 = 0x209102CD;
  Device d(setup_of(Generation::kF9P));
  Host h(d);
  ASSERT_TRUE(h.acked(msg::kCfgValset, valset({{kUart1OutRtcm, 1}, {k4072Uart1, 1}, {k1077Uart1, 1}})));
  receiver::RawEpoch raw;
  raw.t_rx = time::GpsTime(2190, 345600.0);
  raw.time_valid = true;
  raw.num_meas = 5;
  for (int i = 0; i < raw.num_meas; ++i) {
    receiver::RawMeasurement& m = raw.meas[static_cast<std::size_t>(i)];
    m.sat = SatId::gps(i + 1);
    m.signal = SignalId::kGpsL1CA;
    m.pseudorange_m = 2.1e7 + 1e5 * i;
    m.carrier_phase_cycles = m.pseudorange_m / 0.19029367;
    m.cn0_dbhz = 45.0;
    m.lock_time_s = 60.0;
    m.pseudorange_valid = m.carrier_valid = m.half_cycle_resolved = true;
  }
  const receiver::Fix fix = test::sample_fix();
  const auto rtcm_of = [&](const MessageList& list) {
    std::vector<std::pair<int, std::string>> out;  // message number, frame
    for (const auto& m : list.messages()) {
      if (m.protocol != Protocol::kRtcm3) continue;
      const std::string b(list.bytes(m));
      EXPECT_EQ(static_cast<std::uint8_t>(b[0]), 0xD3);
      out.emplace_back((static_cast<std::uint8_t>(b[3]) << 4) | (static_cast<std::uint8_t>(b[4]) >> 4), b);
    }
    return out;
  };
  d.on_epoch(fix, 1.0, RawSource{&raw, nullptr, {}});
  MessageList list;
  d.compose(Link{}, list);
  const auto got = rtcm_of(list);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].first, 4072);
  EXPECT_EQ(got[1].first, 1077);
  const std::string& f = got[0].second;
  const std::size_t len = (static_cast<std::uint8_t>(f[1]) & 3u) << 8 | static_cast<std::uint8_t>(f[2]);
  const auto pvt = rtcm::decode_reference_pvt(
      std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(f.data()) + 3, len));
  ASSERT_TRUE(pvt.has_value());
  EXPECT_EQ(pvt->tow_ms, 345600000u);
  EXPECT_NEAR(pvt->arp_ecef_m.x, fix.pos_m.x, 1e-4);
  EXPECT_NEAR(pvt->arp_ecef_m.z, fix.pos_m.z, 1e-4);
  ASSERT_TRUE(h.acked(msg::kCfgValset, valset({{kUart1OutRtcm, 0}})));
  raw.t_rx = time::GpsTime(2190, 345601.0);
  d.on_epoch(fix, 2.0, RawSource{&raw, nullptr, {}});
  d.compose(Link{}, list);
  EXPECT_TRUE(rtcm_of(list).empty());
}

TEST(UbxF9p, RateLimitAndCapabilities) {
  const NavRateLimits lim = nav_rate_limits(Generation::kF9P, SystemSet::only(GnssSystem::kGps));
  EXPECT_DOUBLE_EQ(lim.max_nav_rate_hz, 20.0);
  EXPECT_EQ(lim.max_solution_sats, kMaxSatsInView);
  const GnssCapabilities& cap = gnss_capabilities(Generation::kF9P);
  EXPECT_EQ(cap.max_major, 4);
  EXPECT_TRUE(cfg_gnss_valid(factory_cfg_gnss(Generation::kF9P), Generation::kF9P));
  EXPECT_FALSE(cfg_gnss_valid(factory_cfg_gnss(Generation::kF9P), Generation::kM9));  // L2 bits an M9 lacks
}

}  // namespace f9p_test
}  // namespace gnssemu::protocol::ubx

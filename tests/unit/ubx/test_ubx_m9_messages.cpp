// SPDX-License-Identifier: Apache-2.0
// The M9's jamming and spoofing reports (MON-RF, SEC-SIG) decoded field by
// field against the Fix, and which messages each generation has: in the
// epoch, in CFG-MSG and in polls (docs/ubx.md §Generations).
#include <gtest/gtest.h>

#include <cstring>

#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/device/ubx_front_end.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::sample_fix;

/// Monitor on at factory thresholds, first fix behind.
EpochInfo monitoring() {
  EpochInfo info;
  info.itfm.enabled = true;
  info.ttff_ms = 1200;
  return info;
}

struct RfView {
  wire::MonRfHeader head{};
  wire::MonRfBlock block{};
};

RfView mon_rf(const receiver::Fix& f, const EpochInfo& info) {
  std::string out;
  const UbxEncoder m9(mon_ver_of(Generation::kM9));
  const std::size_t n = m9.mon_rf(f, info, out);
  EXPECT_EQ(n, out.size());
  const auto frames = test::split_frames(out);
  RfView v;
  EXPECT_EQ(frames.size(), 1u);
  if (frames.size() != 1) return v;
  EXPECT_EQ(frames[0].id, msg::kMonRf);
  EXPECT_EQ(frames[0].payload.size(), 4u + 24u);  // one block
  std::memcpy(&v.head, frames[0].payload.data(), sizeof v.head);
  std::memcpy(&v.block, frames[0].payload.data() + 4, sizeof v.block);
  return v;
}

wire::MonHw mon_hw(const receiver::Fix& f, const EpochInfo& info) {
  std::string out;
  UbxEncoder().mon_hw(f, info, out);
  const auto frames = test::split_frames(out);
  wire::MonHw m{};
  if (frames.size() == 1) std::memcpy(&m, frames[0].payload.data(), sizeof m);
  return m;
}

wire::SecSigV1 sec_sig(const receiver::Fix& f, const EpochInfo& info) {
  std::string out;
  UbxEncoder(mon_ver_of(Generation::kM9)).sec_sig(f, info, out);
  const auto frames = test::split_frames(out);
  wire::SecSigV1 m{};
  EXPECT_EQ(frames.size(), 1u);
  if (frames.size() != 1) return m;
  EXPECT_EQ(frames[0].id, msg::kSecSig);
  EXPECT_EQ(frames[0].payload.size(), 12u);
  std::memcpy(&m, frames[0].payload.data(), sizeof m);
  return m;
}

/// MON-RF's block carries exactly MON-HW's front end (one derivation).
void expect_same_front_end(const receiver::Fix& f, const EpochInfo& info) {
  const RfView rf = mon_rf(f, info);
  const wire::MonHw hw = mon_hw(f, info);
  EXPECT_EQ(rf.head.version, 0);
  EXPECT_EQ(rf.head.nBlocks, 1);
  EXPECT_EQ(rf.block.blockId, 0);
  EXPECT_EQ(rf.block.flags & 3, (hw.flags >> 2) & 3);
  EXPECT_EQ(rf.block.flags & ~3, 0);
  EXPECT_EQ(rf.block.antStatus, hw.aStatus);
  EXPECT_EQ(rf.block.antPower, hw.aPower);
  EXPECT_EQ(rf.block.noisePerMS, hw.noisePerMS);
  EXPECT_EQ(rf.block.agcCnt, hw.agcCnt);
  EXPECT_EQ(rf.block.jamInd, hw.jamInd);
  EXPECT_EQ(rf.block.postStatus, 0u);
  EXPECT_EQ(rf.block.ofsI, 0);
  EXPECT_EQ(rf.block.ofsQ, 0);
  EXPECT_EQ(rf.block.magI, rf.block.magQ);
}

TEST(UbxM9Messages, MonRfCleanSky) {
  receiver::Fix f = sample_fix();  // 3D fix, no CW, antenna OK
  f.noise_rise_db = 1.0;           // quiet countryside
  const RfView v = mon_rf(f, monitoring());
  EXPECT_EQ(v.block.flags & 3, 1);  // ok
  EXPECT_EQ(v.block.antStatus, 2);  // OK
  EXPECT_EQ(v.block.antPower, 1);   // ON
  EXPECT_EQ(v.block.noisePerMS, 85);
  EXPECT_EQ(v.block.agcCnt, 4890);  // 5000 - 110 per dB of rise: ~60 % gain
  EXPECT_EQ(v.block.jamInd, 12);
  EXPECT_EQ(v.block.magI, 128);
  expect_same_front_end(f, monitoring());
}

TEST(UbxM9Messages, MonRfJammedWithAndWithoutFix) {
  receiver::Fix f = sample_fix();
  f.noise_rise_db = 20.0;
  f.cw_jam_to_noise = 1000.0;  // a CW line 30 dB over the floor
  RfView v = mon_rf(f, monitoring());
  EXPECT_EQ(v.block.flags & 3, 2);  // warning: interference visible, fix OK
  EXPECT_EQ(v.block.noisePerMS, 142);
  EXPECT_EQ(v.block.agcCnt, 2800);
  EXPECT_EQ(v.block.jamInd, 227);  // 7 + 5 * 20 + 4 * 30
  expect_same_front_end(f, monitoring());
  f.type = receiver::FixType::kNone;
  v = mon_rf(f, monitoring());
  EXPECT_EQ(v.block.flags & 3, 3);  // critical: no fix
  expect_same_front_end(f, monitoring());
  // Dead reckoning is no reliable fix either.
  f.type = receiver::FixType::kDeadReckoning;
  EXPECT_EQ(mon_rf(f, monitoring()).block.flags & 3, 3);
  // The fix state the port reports counts (a wrong_fix link fault says no fix).
  f.type = receiver::FixType::k3D;
  EpochInfo info = monitoring();
  info.reported_fix = ReportedFix::kNoFix;
  EXPECT_EQ(mon_rf(f, info).block.flags & 3, 3);
  // A CW line alone, below the broadband threshold, beyond cwThreshold (15 dB).
  f.noise_rise_db = 1.0;
  f.cw_jam_to_noise = 40.0;  // 16.1 dB
  EXPECT_EQ(mon_rf(f, monitoring()).block.flags & 3, 2);
  f.cw_jam_to_noise = 20.0;  // 13.2 dB
  EXPECT_EQ(mon_rf(f, monitoring()).block.flags & 3, 1);
  // The AGC runs out of gain beyond ~45 dB: the ADC magnitude climbs.
  f.noise_rise_db = 55.0;
  v = mon_rf(f, monitoring());
  EXPECT_EQ(v.block.agcCnt, 0);
  EXPECT_GT(v.block.magI, 128);
}

TEST(UbxM9Messages, MonRfAntennaOpenAndShortAndMonitorOff) {
  receiver::Fix f = sample_fix();
  f.noise_rise_db = 30.0;
  f.antenna_status = receiver::AntennaStatus::kOpen;
  RfView v = mon_rf(f, monitoring());
  EXPECT_EQ(v.block.antStatus, 4);    // OPEN
  EXPECT_EQ(v.block.antPower, 1);     // supply stays on
  EXPECT_EQ(v.block.flags & 3, 0);    // antenna disconnected: unknown
  expect_same_front_end(f, monitoring());
  f.antenna_status = receiver::AntennaStatus::kShort;
  v = mon_rf(f, monitoring());
  EXPECT_EQ(v.block.antStatus, 3);    // SHORT
  EXPECT_EQ(v.block.antPower, 0);     // supervisor switched the supply off
  f.antenna_status = receiver::AntennaStatus::kOk;
  EXPECT_EQ(mon_rf(f, EpochInfo{}).block.flags & 3, 0);  // CFG-ITFM disabled (factory)
}

TEST(UbxM9Messages, SecSigVersion1FromTheMonitorAndTheSpoofingDetector) {
  receiver::Fix f = sample_fix();
  wire::SecSigV1 m = sec_sig(f, monitoring());
  EXPECT_EQ(m.version, 1);
  EXPECT_EQ(m.jamFlags, 0x01 | 1 << 1);  // jamDetEnabled, ok
  EXPECT_EQ(m.spfFlags, 0x01 | 1 << 1);  // spfDetEnabled, no spoofing indicated
  for (std::uint8_t r : {m.reserved0[0], m.reserved0[1], m.reserved0[2], m.reserved1[0], m.reserved2[2]}) {
    EXPECT_EQ(r, 0);
  }
  f.noise_rise_db = 25.0;
  EXPECT_EQ(sec_sig(f, monitoring()).jamFlags, 0x01 | 2 << 1);  // warning
  f.type = receiver::FixType::kNone;
  EXPECT_EQ(sec_sig(f, monitoring()).jamFlags, 0x01 | 3 << 1);  // critical
  EXPECT_EQ(sec_sig(f, EpochInfo{}).jamFlags, 0);               // detection off: disabled, unknown
  // Spoofing as NAV-STATUS flags2 says it (one owner: spoof_det_state).
  for (std::uint8_t s = 0; s <= 3; ++s) {
    f.spoof_det_state = s;
    m = sec_sig(f, monitoring());
    EXPECT_EQ((m.spfFlags >> 1) & 7, s);
    EXPECT_EQ(m.spfFlags & 1, s != 0 ? 1 : 0);
    std::string out;
    UbxEncoder().nav_status(f, monitoring(), out);
    EXPECT_EQ((test::split_frames(out)[0].payload[7] >> 3) & 3, s);
  }
}

TEST(UbxM9Messages, PerGenerationTable) {
  EXPECT_TRUE(message_exists(msg::kNavSvinfo, Generation::kM8));
  EXPECT_FALSE(message_exists(msg::kNavSvinfo, Generation::kM9));
  for (MsgId id : {msg::kMonRf, msg::kSecSig}) {
    EXPECT_FALSE(message_exists(id, Generation::kM8));
    EXPECT_TRUE(message_exists(id, Generation::kM9));
  }
  EXPECT_TRUE(message_exists(msg::kMonHw, Generation::kM9));   // MON-HW stays on the M9
  EXPECT_TRUE(message_exists(MsgId{0x01, 0x22}, Generation::kM9));  // ids outside the table are not judged
  // The encoders refuse what the generation lacks.
  std::string out;
  EXPECT_EQ(UbxEncoder().encode(msg::kMonRf, sample_fix(), {}, out), 0u);
  EXPECT_EQ(UbxEncoder().encode(msg::kSecSig, sample_fix(), {}, out), 0u);
  EXPECT_EQ(UbxEncoder(mon_ver_of(Generation::kM9)).encode(msg::kNavSvinfo, sample_fix(), {}, out), 0u);
  EXPECT_TRUE(out.empty());
}

/// A chip of generation g with every periodic message of the table at rate 1
/// on UART1 (set directly: CFG-MSG would NAK the ones it lacks).
Device every_message(Generation g) {
  DeviceSetup setup;
  setup.mon_ver = mon_ver_of(g);
  Device d(setup);
  for (const PeriodicMessage& m : kPeriodicMessages) d.config().set_message_rate(kPortUart1, m.id, 1);
  return d;
}

std::vector<MsgId> epoch_ids(const Device& d) {
  std::string out;
  test::ubx_epoch(d, {}, out);
  std::vector<MsgId> ids;
  for (const auto& fr : test::split_frames(out)) ids.push_back(fr.id);
  return ids;
}

bool has(const std::vector<MsgId>& ids, MsgId id) { return std::find(ids.begin(), ids.end(), id) != ids.end(); }

TEST(UbxM9Messages, EachGenerationSendsOnlyItsMessages) {
  Device m8 = every_message(Generation::kM8);
  Device m9 = every_message(Generation::kM9);
  for (int e = 0; e < 3; ++e) {
    m8.on_epoch(sample_fix(), e);
    m9.on_epoch(sample_fix(), e);
    const auto ids8 = epoch_ids(m8), ids9 = epoch_ids(m9);
    EXPECT_TRUE(has(ids8, msg::kNavSvinfo));
    EXPECT_FALSE(has(ids8, msg::kMonRf));
    EXPECT_FALSE(has(ids8, msg::kSecSig));
    EXPECT_FALSE(has(ids9, msg::kNavSvinfo));
    EXPECT_TRUE(has(ids9, msg::kMonRf));
    EXPECT_TRUE(has(ids9, msg::kSecSig));
    EXPECT_TRUE(has(ids9, msg::kMonHw));
    // MON and SEC after the NAV messages, NAV-EOE last.
    ASSERT_FALSE(ids9.empty());
    EXPECT_EQ(ids9.back(), msg::kNavEoe);
    const auto at = [&](MsgId id) { return std::find(ids9.begin(), ids9.end(), id) - ids9.begin(); };
    EXPECT_LT(at(msg::kMonHw), at(msg::kMonRf));
    EXPECT_LT(at(msg::kMonRf), at(msg::kSecSig));
  }
}

TEST(UbxM9Messages, CfgMsgNaksAndPollsIgnoreWhatTheGenerationLacks) {
  for (const Generation g : {Generation::kM8, Generation::kM9}) {
    SCOPED_TRACE(std::string(generation_name(g)));
    DeviceSetup setup;
    setup.mon_ver = mon_ver_of(g);
    Device d(setup);
    d.on_epoch(sample_fix(), 1.0);
    const bool m9 = g == Generation::kM9;
    const auto send = [&](MsgId id, const std::vector<std::uint8_t>& payload) {
      std::string out;
      const FrameView fv{id, payload};
      const InputResult r = d.handle_ubx({}, fv, 1.0, out);
      return std::make_pair(r.reply, test::split_frames(out));
    };
    // CFG-MSG set (3-byte form) and poll: ACK where the message exists, NAK where not.
    for (const MsgId id : {msg::kMonRf, msg::kSecSig, msg::kNavSvinfo}) {
      const bool exists = message_exists(id, g);
      EXPECT_EQ(send(msg::kCfgMsg, {id.cls, id.id, 1}).first, exists ? Reply::kAck : Reply::kNak);
      EXPECT_EQ(d.message_rate({}, id), exists ? 1 : 0);
      EXPECT_EQ(send(msg::kCfgMsg, {id.cls, id.id}).first, exists ? Reply::kPollData : Reply::kNak);
      EXPECT_EQ(send(msg::kCfgMsg, {id.cls, id.id, 0, 1, 0, 0, 0, 0}).first, exists ? Reply::kAck : Reply::kNak);
    }
    // Polls: data from the last epoch, or nothing at all (an unknown id).
    auto [reply, frames] = send(msg::kMonRf, {});
    EXPECT_EQ(reply, m9 ? Reply::kPollData : Reply::kNone);
    EXPECT_EQ(frames.size(), m9 ? 1u : 0u);
    std::tie(reply, frames) = send(msg::kSecSig, {});
    EXPECT_EQ(reply, m9 ? Reply::kPollData : Reply::kNone);
    EXPECT_EQ(frames.size(), m9 ? 1u : 0u);
    std::tie(reply, frames) = send(msg::kNavSvinfo, {});
    EXPECT_EQ(reply, m9 ? Reply::kNone : Reply::kPollData);
    EXPECT_EQ(frames.size(), m9 ? 0u : 1u);
  }
}

TEST(UbxM9Messages, ItfmSetThroughCfgItfmReachesMonRf) {
  DeviceSetup setup;
  setup.mon_ver = mon_ver_of(Generation::kM9);
  Device d(setup);
  d.config().set_message_rate(kPortUart1, msg::kMonRf, 1);
  receiver::Fix f = sample_fix();
  f.noise_rise_db = 12.0;
  d.on_epoch(f, 1.0);
  std::string out;
  test::ubx_epoch(d, {}, out);
  auto frames = test::split_frames(out);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].payload[5] & 3, 0);  // factory: monitor disabled
  // Enable with bbThreshold 15 dB: 11 dB above normal is below it.
  std::string reply;
  const std::vector<std::uint8_t> itfm = {0xFF, 0xAC, 0x62, 0xAD, 0x1E, 0x03, 0x00, 0x00};
  EXPECT_EQ(d.handle_ubx({}, FrameView{msg::kCfgItfm, itfm}, 1.5, reply).reply, Reply::kAck);
  d.on_epoch(f, 2.0);
  out.clear();
  test::ubx_epoch(d, {}, out);
  frames = test::split_frames(out);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].payload[5] & 3, 1);
  f.noise_rise_db = 17.0;  // 16 dB above normal
  d.on_epoch(f, 3.0);
  out.clear();
  test::ubx_epoch(d, {}, out);
  EXPECT_EQ(test::split_frames(out)[0].payload[5] & 3, 2);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

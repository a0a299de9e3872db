// SPDX-License-Identifier: Apache-2.0
// RTCM 3 on a u-blox port: frames interleaved with UBX and NMEA reach the
// device's corrections only where the port's inProtoMask has RTCM3, each
// message answered by an RXM-RTCM (IDF9 §5.15.5) where the host enabled it;
// bad CRCs, unknown messages and truncated frames are counted and the UBX
// around them still answered.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/protocol/rtcm/rtcm_frame.hpp"
#include "core/protocol/rtcm/rtcm_msm.hpp"
#include "core/protocol/rtcm/rtcm_station.hpp"
#include "core/protocol/ubx/wire/ubx_decoder.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace rtcm_input_test {

using test::frame_bytes;

/// A host on UART1 of output 0 that keeps every reply.
struct RtcmHost : DecoderSink {
  explicit RtcmHost(Device& d) : dev(d) {}
  Device& dev;
  StreamDecoder decoder;
  std::string tx;
  void send(const std::string& bytes) { decoder.feed(bytes, *this); }
  void on_ubx(const FrameView& f) override { dev.handle_ubx({}, f, 0.0, tx); }
  void on_nmea(std::string_view s) override { dev.handle_nmea({}, s, tx); }
  void on_rtcm(std::span<const std::uint8_t> p, bool crc_ok) override { dev.handle_rtcm({}, p, crc_ok, tx); }
  std::vector<test::Frame> rxm_rtcm() const {
    std::vector<test::Frame> out;
    for (const test::Frame& f : test::split_frames(tx))
      if (f.id == msg::kRxmRtcm) out.push_back(f);
    return out;
  }
};

DeviceSetup rtcm_port() {
  DeviceSetup s;
  OutputSetup o;
  o.protocols_in = proto::kUbx | proto::kNmea | proto::kRtcm3;
  s.outputs.push_back(o);
  return s;
}

/// A station message, a two-system MSM7 epoch at GPS (2300, 345600.5).
std::string corrections_bytes() {
  std::string out;
  rtcm::StationInfo st;
  st.station_id = 42;
  st.arp_ecef_m = Ecef{4e6, 5e5, 4.9e6};
  rtcm::append_station(st, false, out);
  receiver::RawEpoch e;
  e.t_rx = time::GpsTime(2300, 345600.5);
  e.time_valid = true;
  for (GnssSystem sys : {GnssSystem::kGps, GnssSystem::kGalileo}) {
    for (int n = 1; n <= 5; ++n) {
      receiver::RawMeasurement& m = e.meas[static_cast<std::size_t>(e.num_meas++)];
      m.sat = SatId(sys, n);
      m.signal = *signal_of(sys, 0);
      m.pseudorange_m = 2.2e7 + n * 1e5;
      m.carrier_phase_cycles = m.pseudorange_m / 0.19;
      m.cn0_dbhz = 45.0;
      m.lock_time_s = 30.0;
      m.pseudorange_valid = m.carrier_valid = true;
    }
  }
  rtcm::MsmEncoder enc(42, rtcm::MsmKind::kMsm7);
  enc.append_epoch(e, SystemSet::all(), out);
  return out;
}

receiver::Fix fix_at(time::GpsTime t) {
  receiver::Fix f = test::sample_fix();
  f.t = t;
  f.time_valid = true;
  return f;
}

TEST(UbxRtcmInput, TakenWhereThePortHasRtcm3AndReportedByRxmRtcm) {
  Device d(rtcm_port());
  d.on_epoch(fix_at(time::GpsTime(2300, 345600.0)), 1.0);
  RtcmHost h(d);
  h.send(frame_bytes(msg::kCfgMsg, {0x02, 0x32, 1}));  // RXM-RTCM on this port
  ASSERT_EQ(test::split_frames(h.tx).back().id, msg::kAckAck);
  std::string bad = corrections_bytes().substr(0, 25);  // the 1005 ...
  bad[10] = static_cast<char>(bad[10] ^ 0x40);           // ... corrupted
  std::array<std::uint8_t, 3> unknown{0x3E, 0x70, 0x00};  // message 999
  std::string unknown_frame;
  rtcm::append_frame(unknown, unknown_frame);
  h.send("junk" + bad + frame_bytes(msg::kMonVer, {}) + "$PUBX,40,GLL,0,0,0,0,0,0*5C\r\n" + unknown_frame +
         corrections_bytes());
  const std::vector<test::Frame> reports = h.rxm_rtcm();
  ASSERT_EQ(reports.size(), 5u);  // bad 1005, 999, 1005, 1077, 1097
  const auto msg_type = [](const test::Frame& f) { return test::u2(f.payload, 6); };
  EXPECT_EQ(reports[0].payload[0], 0x02);  // version
  EXPECT_EQ(reports[0].payload[1] & 0x01, 0x01);  // crcFailed
  EXPECT_EQ(msg_type(reports[1]), 999);
  EXPECT_EQ((reports[1].payload[1] >> 1) & 3, 1);  // not used
  EXPECT_EQ(msg_type(reports[2]), 1005);
  EXPECT_EQ((reports[2].payload[1] >> 1) & 3, 2);  // used
  EXPECT_EQ(test::u2(reports[2].payload, 4), 42);  // refStation
  EXPECT_EQ(msg_type(reports[3]), 1077);
  EXPECT_EQ(msg_type(reports[4]), 1097);
  // MON-VER was answered in between; the corrections hold station and epoch.
  bool mon_ver = false;
  for (const test::Frame& f : test::split_frames(h.tx)) mon_ver = mon_ver || f.id == msg::kMonVer;
  EXPECT_TRUE(mon_ver);
  const receiver::Corrections& c = d.corrections();
  EXPECT_TRUE(c.station.position_valid);
  EXPECT_EQ(c.station.station_id, 42);
  ASSERT_TRUE(c.obs_valid);
  EXPECT_EQ(c.obs.num_meas, 10);
  EXPECT_EQ(c.obs_received, time::GpsTime(2300, 345600.0));
  EXPECT_EQ(d.rtcm_input().stats().crc_failed, 1u);
  EXPECT_EQ(d.rtcm_input().decoder_stats().unknown_messages, 1u);
}

TEST(UbxRtcmInput, F9pReportsEachCorrectionMessageInRxmCor) {
  DeviceSetup s = rtcm_port();
  s.mon_ver = mon_ver_of(Generation::kF9P);
  Device d(s);
  d.on_epoch(fix_at(time::GpsTime(2300, 345600.0)), 1.0);
  RtcmHost h(d);
  h.send(frame_bytes(msg::kCfgMsg, {0x02, 0x34, 1}));  // RXM-COR on this port
  ASSERT_EQ(test::split_frames(h.tx).back().id, msg::kAckAck);
  h.send(corrections_bytes());
  std::vector<test::Frame> cor;
  for (const test::Frame& f : test::split_frames(h.tx))
    if (f.id == msg::kRxmCor) cor.push_back(f);
  EXPECT_TRUE(h.rxm_rtcm().empty());  // RXM-RTCM stays off
  ASSERT_EQ(cor.size(), 3u);          // 1005, 1077, 1097
  const auto msg_type = [](const test::Frame& f) { return test::u2(f.payload, 8); };
  EXPECT_EQ(msg_type(cor[0]), 1005);
  EXPECT_EQ(msg_type(cor[1]), 1077);
  EXPECT_EQ(msg_type(cor[2]), 1097);
  const std::uint32_t status = test::u4(cor[1].payload, 4);
  EXPECT_EQ(status & 0x1Fu, 1u);         // protocol RTCM3
  EXPECT_EQ((status >> 7) & 3u, 2u);     // msgUsed: used
}

TEST(UbxRtcmInput, IgnoredOnAPortWithoutRtcm3) {
  Device d(DeviceSetup{});  // an M8N's UART1: UBX, NMEA, RTCM 2
  RtcmHost h(d);
  h.send(frame_bytes(msg::kCfgMsg, {0x02, 0x32, 1}) + corrections_bytes());
  EXPECT_TRUE(h.rxm_rtcm().empty());
  EXPECT_FALSE(d.corrections().obs_valid);
  EXPECT_FALSE(d.corrections().station.position_valid);
  EXPECT_EQ(d.rtcm_input().stats().ignored, 3u);
}

TEST(UbxRtcmInput, OutageFaultLosesFrames) {
  Device d(rtcm_port());
  d.rtcm_input().set_outage(true);
  RtcmHost h(d);
  h.send(corrections_bytes());
  EXPECT_FALSE(d.corrections().obs_valid);
  EXPECT_EQ(d.rtcm_input().stats().outage, 3u);
  d.rtcm_input().set_outage(false);
  h.send(corrections_bytes());
  EXPECT_TRUE(d.corrections().obs_valid);
}

TEST(UbxRtcmInput, StaleFaultKeepsTheCorrectionsAsTheyWere) {
  Device d(rtcm_port());
  d.on_epoch(fix_at(time::GpsTime(2300, 345600.0)), 1.0);
  RtcmHost h(d);
  h.send(corrections_bytes());
  const std::uint32_t revision = d.corrections().revision;
  d.on_epoch(fix_at(time::GpsTime(2300, 345601.0)), 2.0);
  d.rtcm_input().set_stale(true);
  h.send(corrections_bytes());
  EXPECT_EQ(d.corrections().revision, revision);
  EXPECT_EQ(d.corrections().obs_received, time::GpsTime(2300, 345600.0));
  EXPECT_EQ(d.rtcm_input().stats().stale, 3u);
}

TEST(UbxRtcmInput, TruncatedFrameDoesNotHideTheUbxAfterIt) {
  Device d(rtcm_port());
  RtcmHost h(d);
  const std::string c = corrections_bytes();
  // A frame cut short: the UBX poll behind it is read as its tail, the CRC
  // fails, and the rescan finds the poll.
  const std::string cut = c.substr(25, 40);
  h.send(cut + frame_bytes(msg::kMonVer, {}));
  h.decoder.on_idle(h);
  while (h.decoder.pending_bytes() > 0) h.decoder.on_idle(h);
  bool mon_ver = false;
  for (const test::Frame& f : test::split_frames(h.tx)) mon_ver = mon_ver || f.id == msg::kMonVer;
  EXPECT_TRUE(mon_ver);
  EXPECT_FALSE(d.corrections().obs_valid);
}

}  // namespace rtcm_input_test
}  // namespace gnssemu::protocol::ubx

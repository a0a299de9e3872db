// SPDX-License-Identifier: Apache-2.0
// The emulated M8 (Device) as one host sees it: the PX4 and ArduPilot UBX start-up sequences
// (DESIGN.md §4, shared/reference/ubx.md §5-6) replayed byte for byte, the
// request bytes built from what those drivers send, the expected replies
// computed independently (Python struct + Fletcher) and written as hex.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "core/protocol/ubx/wire/ubx_decoder.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::frame_bytes;
using test::from_hex;
using test::to_hex;

/// One host talking to one port: bytes in -> decoder -> device -> bytes out.
class Host : public DecoderSink {
public:
  explicit Host(Device& r, std::uint8_t port = kPortUart1) : r_(r), port_(port) {}
  /// Send bytes; returns the hex of everything the receiver answered.
  std::string send(const std::string& bytes) {
    tx_.clear();
    results_.clear();
    decoder_.feed(bytes, *this);
    return to_hex(tx_);
  }
  std::string send(MsgId id, const std::vector<std::uint8_t>& payload) { return send(frame_bytes(id, payload)); }
  const InputResult& last() const { return results_.back(); }
  void on_ubx(const FrameView& f) override { results_.push_back(r_.handle_ubx({0, port_}, f, 0.0, tx_)); }
  void on_nmea(std::string_view s) override { results_.push_back(r_.handle_nmea({0, port_}, s, tx_)); }

private:
  Device& r_;
  std::uint8_t port_;
  StreamDecoder decoder_;
  std::string tx_;
  std::vector<InputResult> results_;
};

const std::string kAckPrt = "B5 62 05 01 02 00 06 00 0E 37";
const std::string kAckRate = "B5 62 05 01 02 00 06 08 16 3F";
const std::string kAckNav5 = "B5 62 05 01 02 00 06 24 32 5B";
const std::string kAckMsg = "B5 62 05 01 02 00 06 01 0F 38";
const std::string kAckGnss = "B5 62 05 01 02 00 06 3E 4C 75";
const std::string kAckSbas = "B5 62 05 01 02 00 06 16 24 4D";
const std::string kMonVer =
    "B5 62 0A 04 A0 00 52 4F 4D 20 43 4F 52 45 20 33 2E 30 31 20 28 31 30 37 38 38 38 29 00 00 00 00 00 00 00 00 "
    "30 30 30 38 30 30 30 30 00 00 46 57 56 45 52 3D 53 50 47 20 33 2E 30 31 00 00 00 00 00 00 00 00 00 00 00 00 "
    "00 00 00 00 50 52 4F 54 56 45 52 3D 31 38 2E 30 30 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 47 50 "
    "53 3B 47 4C 4F 3B 47 41 4C 3B 42 44 53 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 53 42 41 53 3B 49 4D 45 "
    "53 3B 51 5A 53 53 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 41 D2";

std::vector<std::uint8_t> cfg_prt(std::uint8_t port, std::uint32_t mode, std::uint32_t baud, std::uint16_t in,
                                  std::uint16_t out) {
  wire::CfgPrt w{};
  w.portID = port;
  w.mode = mode;
  w.baudRate = baud;
  w.inProtoMask = in;
  w.outProtoMask = out;
  const auto* b = reinterpret_cast<const std::uint8_t*>(&w);
  return {b, b + sizeof w};
}

TEST(UbxDevice, Px4StartupSequence) {
  Device r({});
  Host px4(r);
  // 1. CFG-VALSET (RAM, UART1 baud and protocols): an M8 does not know it.
  EXPECT_EQ(px4.send(msg::kCfgValset, {0, 1, 0, 0, 0x01, 0x00, 0x52, 0x40, 0x00, 0xC2, 0x01, 0x00}),
            "B5 62 05 00 02 00 06 8A 97 BC");
  // 2. CFG-PRT at the current baud (UBX in/out only): ACK.
  EXPECT_EQ(px4.send(msg::kCfgPrt, cfg_prt(1, 0x8D0, 9600, 0x01, 0x01)), kAckPrt);
  EXPECT_EQ(px4.last().new_baud_bps, 0u);
  EXPECT_TRUE(px4.last().ports_changed);
  //    then the target baud: ACK at the old rate, switch after it is sent.
  EXPECT_EQ(px4.send(msg::kCfgPrt, cfg_prt(1, 0x8D0, 115200, 0x01, 0x01)), kAckPrt);
  EXPECT_EQ(px4.last().new_baud_bps, 115200u);
  EXPECT_EQ(r.port({0, kPortUart1}).baud_bps, 115200u);
  // 3. MON-VER poll: the M8 version, no ACK.
  EXPECT_EQ(px4.send(msg::kMonVer, {}), kMonVer);
  // 4. CFG-RATE 200 ms, navRate 1, UTC.
  EXPECT_EQ(px4.send(msg::kCfgRate, {0xC8, 0x00, 0x01, 0x00, 0x00, 0x00}), kAckRate);
  EXPECT_TRUE(px4.last().nav_rate_changed);
  EXPECT_DOUBLE_EQ(r.config().nav_period_s(), 0.2);
  // 5. CFG-NAV5 mask 0x0005: airborne < 4 g, auto 2D/3D.
  std::vector<std::uint8_t> nav5(36, 0);
  nav5[0] = 0x05;
  nav5[2] = 8;
  nav5[3] = 3;
  EXPECT_EQ(px4.send(msg::kCfgNav5, nav5), kAckNav5);
  EXPECT_TRUE(px4.last().nav_config_changed);
  EXPECT_EQ(r.config().nav5.dynModel, 8);
  EXPECT_EQ(r.config().nav5.minElev, 5);  // not in the mask: kept
  // 6. CFG-MSG (current port) NAV-PVT 1, NAV-STATUS 1, NAV-DOP 1, NAV-SVINFO 5, MON-HW 2.
  const std::vector<std::vector<std::uint8_t>> msgs = {
      {0x01, 0x07, 1}, {0x01, 0x03, 1}, {0x01, 0x04, 1}, {0x01, 0x30, 5}, {0x0A, 0x09, 2}};
  for (const auto& m : msgs) {
    EXPECT_EQ(px4.send(msg::kCfgMsg, m), kAckMsg);
    EXPECT_TRUE(px4.last().rates_changed);
  }
  EXPECT_EQ(r.stats().naks, 1u);
  EXPECT_EQ(r.stats().acks, 9u);

  // Epochs: NAV-PVT with gnssFixOK every epoch, SVINFO every 5th, MON-HW every 2nd, no NMEA.
  receiver::Fix f = test::sample_fix();
  int pvt = 0, svinfo = 0, hw = 0, status = 0, dop = 0;
  for (int e = 0; e < 10; ++e) {
    r.on_epoch(f, 1.0 + 0.2 * e);
    f.t = f.t + 0.2;
    std::string out;
    test::ubx_epoch(r, {0, kPortUart1}, out);
    const auto frames = test::split_frames(out);
    for (const auto& fr : frames) {
      if (fr.id == msg::kNavPvt) {
        ++pvt;
        EXPECT_EQ(fr.payload[21] & 1, 1);  // gnssFixOK
        EXPECT_EQ(fr.payload[20], 3);
      }
      svinfo += fr.id == msg::kNavSvinfo;
      hw += fr.id == msg::kMonHw;
      status += fr.id == msg::kNavStatus;
      dop += fr.id == msg::kNavDop;
    }
    // Order within the epoch: STATUS, DOP, PVT (NAV ids ascending).
    ASSERT_GE(frames.size(), 3u);
    EXPECT_EQ(frames[0].id, msg::kNavStatus);
    EXPECT_EQ(frames[1].id, msg::kNavDop);
    EXPECT_EQ(frames[2].id, msg::kNavPvt);
    const auto n = r.nmea_due({0, kPortUart1});
    EXPECT_TRUE(n.empty());  // NMEA off in outProtoMask
  }
  EXPECT_EQ(pvt, 10);
  EXPECT_EQ(status, 10);
  EXPECT_EQ(dop, 10);
  EXPECT_EQ(svinfo, 2);
  EXPECT_EQ(hw, 5);
}

TEST(UbxDevice, ArduPilotPollAndCompareSequence) {
  Device r({});
  Host ap(r);
  // CFG-PRT poll (current port): UART1 9600 8N1, UBX+NMEA+RTCM2 in, UBX+NMEA out; then ACK.
  EXPECT_EQ(ap.send(msg::kCfgPrt, {}),
            "B5 62 06 00 14 00 01 00 00 00 C0 08 00 00 80 25 00 00 07 00 03 00 00 00 00 00 92 B5 " + kAckPrt);
  // CFG-MSG poll NAV-PVT: off everywhere -> set rate 1 -> read back 1 on UART1.
  EXPECT_EQ(ap.send(msg::kCfgMsg, {0x01, 0x07}), "B5 62 06 01 08 00 01 07 00 00 00 00 00 00 17 DC " + kAckMsg);
  EXPECT_EQ(ap.send(msg::kCfgMsg, {0x01, 0x07, 1}), kAckMsg);
  EXPECT_EQ(ap.send(msg::kCfgMsg, {0x01, 0x07}), "B5 62 06 01 08 00 01 07 00 01 00 00 00 00 18 E1 " + kAckMsg);
  // CFG-RATE poll: 1000 ms, 1, GPS -> set 200 ms UTC -> read back.
  EXPECT_EQ(ap.send(msg::kCfgRate, {}), "B5 62 06 08 06 00 E8 03 01 00 01 00 01 39 " + kAckRate);
  EXPECT_EQ(ap.send(msg::kCfgRate, {0xC8, 0x00, 0x01, 0x00, 0x00, 0x00}), kAckRate);
  EXPECT_EQ(ap.send(msg::kCfgRate, {}), "B5 62 06 08 06 00 C8 00 01 00 00 00 DD 68 " + kAckRate);
  // CFG-NAV5 poll: M8 defaults -> set dynModel 8 (mask 1) -> read back.
  EXPECT_EQ(ap.send(msg::kCfgNav5, {}),
            "B5 62 06 24 24 00 FF FF 00 03 00 00 00 00 10 27 00 00 05 00 FA 00 FA 00 64 00 5E 01 00 3C 00 00 00 00 "
            "00 00 00 00 00 00 00 00 7E 3C " + kAckNav5);
  std::vector<std::uint8_t> nav5(36, 0);
  nav5[0] = 0x01;
  nav5[2] = 8;
  EXPECT_EQ(ap.send(msg::kCfgNav5, nav5), kAckNav5);
  EXPECT_EQ(ap.send(msg::kCfgNav5, {}),
            "B5 62 06 24 24 00 FF FF 08 03 00 00 00 00 10 27 00 00 05 00 FA 00 FA 00 64 00 5E 01 00 3C 00 00 00 00 "
            "00 00 00 00 00 00 00 00 86 4C " + kAckNav5);
  // CFG-GNSS poll (60 bytes: 32 channels, 7 blocks) -> disable GLONASS -> read back.
  std::string gnss = ap.send(msg::kCfgGnss, {});
  auto frames = test::split_frames(from_hex(gnss));
  ASSERT_EQ(frames.size(), 2u);
  ASSERT_EQ(frames[0].payload.size(), 60u);
  EXPECT_EQ(frames[0].payload[1], 32);
  EXPECT_EQ(frames[0].payload[3], 7);
  EXPECT_EQ(frames[0].payload[4 + 8 * 6], 6);               // GLONASS block
  EXPECT_EQ(test::u4(frames[0].payload, 4 + 8 * 6 + 4), 0x01010001u);  // enabled
  EXPECT_EQ(to_hex(frame_bytes(frames[1].id, frames[1].payload)), kAckGnss);
  EXPECT_EQ(ap.send(msg::kCfgGnss, {0, 32, 32, 1, 6, 8, 14, 0, 0x00, 0x00, 0x01, 0x01}), kAckGnss);
  frames = test::split_frames(from_hex(ap.send(msg::kCfgGnss, {})));
  ASSERT_EQ(frames[0].payload.size(), 60u);  // merged by gnssId, still 7 blocks
  EXPECT_EQ(test::u4(frames[0].payload, 4 + 8 * 6 + 4), 0x01010000u);  // GLONASS now off
  EXPECT_EQ(test::u4(frames[0].payload, 4 + 4), 0x01010001u);          // GPS untouched
  // CFG-SBAS poll -> disable -> read back.
  EXPECT_EQ(ap.send(msg::kCfgSbas, {}), "B5 62 06 16 08 00 01 03 03 00 00 00 00 00 2B B9 " + kAckSbas);
  EXPECT_EQ(ap.send(msg::kCfgSbas, {0, 3, 3, 0, 0, 0, 0, 0}), kAckSbas);
  EXPECT_EQ(ap.send(msg::kCfgSbas, {}), "B5 62 06 16 08 00 00 03 03 00 00 00 00 00 2A B1 " + kAckSbas);
  // MON-VER read back.
  EXPECT_EQ(ap.send(msg::kMonVer, {}), kMonVer);
  // CFG-TP5 poll answered too (ArduPilot polls it on some boards): 32 bytes + ACK.
  frames = test::split_frames(from_hex(ap.send(msg::kCfgTp5, {})));
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].payload.size(), 32u);
  EXPECT_EQ(r.stats().naks, 0u);
}

TEST(UbxDevice, ArduPilotPubx41ProbeSwitchesBaudAndProtocols) {
  Device r({});
  Host ap(r);
  EXPECT_EQ(ap.send("$PUBX,41,1,0007,0001,230400,0*18\r\n"), "");  // no answer to PUBX
  EXPECT_EQ(ap.last().new_baud_bps, 230400u);
  EXPECT_TRUE(ap.last().ports_changed);
  EXPECT_EQ(r.port({0, kPortUart1}).out_proto_mask, proto::kUbx);
  EXPECT_EQ(r.port({0, kPortUart1}).in_proto_mask, 0x0007);
  // Same command again: nothing changes, no baud switch.
  ap.send("$PUBX,41,1,0007,0001,230400,0*18\r\n");
  EXPECT_EQ(ap.last().new_baud_bps, 0u);
  EXPECT_FALSE(ap.last().ports_changed);
  // A bad baud is ignored.
  ap.send("$PUBX,41,1,0007,0001,12345,0*2C\r\n");
  EXPECT_EQ(r.port({0, kPortUart1}).baud_bps, 230400u);
}

TEST(UbxDevice, CfgMsgLongFormSetsAllPortsAndRatesApplyPerPort) {
  Device r({});
  Host uart(r, kPortUart1), usb(r, kPortUsb);
  EXPECT_EQ(uart.send(msg::kCfgMsg, {0x01, 0x07, 0, 1, 0, 2, 0, 0}), kAckMsg);
  EXPECT_EQ(r.message_rate({0, kPortUart1}, msg::kNavPvt), 1);
  EXPECT_EQ(r.message_rate({0, kPortUsb}, msg::kNavPvt), 2);
  // Short form from USB changes only USB.
  EXPECT_EQ(usb.send(msg::kCfgMsg, {0x01, 0x07, 3}), kAckMsg);
  EXPECT_EQ(r.message_rate({0, kPortUart1}, msg::kNavPvt), 1);
  EXPECT_EQ(r.message_rate({0, kPortUsb}, msg::kNavPvt), 3);
  // NMEA GGA off on UART1 only.
  EXPECT_EQ(uart.send(msg::kCfgMsg, {0xF0, 0x00, 0}), kAckMsg);
  receiver::Fix f = test::sample_fix();
  int usb_pvt = 0;
  for (int e = 0; e < 6; ++e) {
    r.on_epoch(f, e);
    std::string out;
    test::ubx_epoch(r, {0, kPortUsb}, out);
    usb_pvt += static_cast<int>(test::split_frames(out).size());
    EXPECT_FALSE(r.nmea_due({0, kPortUart1}).has(nmea::Sentence::kGga));
    EXPECT_TRUE(r.nmea_due({0, kPortUart1}).has(nmea::Sentence::kRmc));
    EXPECT_TRUE(r.nmea_due({0, kPortUsb}).has(nmea::Sentence::kGga));
  }
  EXPECT_EQ(usb_pvt, 2);  // every 3rd epoch
  // Bad lengths and non-output classes are NAKed.
  EXPECT_EQ(uart.send(msg::kCfgMsg, {0x01, 0x07, 1, 1}), "B5 62 05 00 02 00 06 01 0E 33");
  EXPECT_EQ(uart.send(msg::kCfgMsg, {0x06, 0x00, 1}), "B5 62 05 00 02 00 06 01 0E 33");
}

TEST(UbxDevice, NakVersionedConfigAndUnknownCfg) {
  Device r({});
  Host h(r);
  EXPECT_EQ(h.send(msg::kCfgValget, {0, 0, 0, 0, 0x01, 0x00, 0x21, 0x30}), "B5 62 05 00 02 00 06 8B 98 BD");
  EXPECT_EQ(h.last().reply, Reply::kNak);
  EXPECT_EQ(h.send(MsgId{0x06, 0x8C}, {0, 1, 0, 0}).substr(0, 23), "B5 62 05 00 02 00 06 8C");
  EXPECT_EQ(h.send(MsgId{0x06, 0x70}, {1, 2}).substr(0, 23), "B5 62 05 00 02 00 06 70");  // CFG-DGNSS: not an M8N
  DeviceSetup lenient;
  lenient.ack_unknown_cfg = true;
  Device r2(lenient);
  Host h2(r2);
  EXPECT_EQ(h2.send(MsgId{0x06, 0x70}, {1, 2}).substr(0, 23), "B5 62 05 01 02 00 06 70");
  EXPECT_EQ(h2.send(msg::kCfgValset, {0, 1, 0, 0}).substr(0, 23), "B5 62 05 00 02 00 06 8A");  // still NAK
}

TEST(UbxDevice, WrongLengthsAreNaked) {
  Device r({});
  Host h(r);
  EXPECT_EQ(h.send(msg::kCfgRate, {1, 2, 3}).substr(0, 14), "B5 62 05 00 02");
  EXPECT_EQ(h.send(msg::kCfgNav5, std::vector<std::uint8_t>(35, 0)).substr(0, 14), "B5 62 05 00 02");
  EXPECT_EQ(h.send(msg::kCfgPrt, std::vector<std::uint8_t>(19, 0)).substr(0, 14), "B5 62 05 00 02");
  EXPECT_EQ(h.send(msg::kCfgCfg, std::vector<std::uint8_t>(11, 0)).substr(0, 14), "B5 62 05 00 02");
  EXPECT_EQ(h.send(msg::kCfgRate, {0x0A, 0x00, 0x01, 0x00, 0x00, 0x00}).substr(0, 14), "B5 62 05 00 02");  // 10 ms
  std::vector<std::uint8_t> nav5(36, 0);
  nav5[0] = 0x01;
  nav5[2] = 1;  // reserved dynamic model
  EXPECT_EQ(h.send(msg::kCfgNav5, nav5).substr(0, 14), "B5 62 05 00 02");
  EXPECT_EQ(h.send(msg::kCfgPrt, {2}).substr(0, 14), "B5 62 05 00 02");  // no UART2 on a NEO-M8N
  EXPECT_EQ(r.config().rate.measRate, 1000);
  EXPECT_EQ(r.stats().naks, 7u);
}

TEST(UbxDevice, EveryPollAnsweredAtItsLength) {
  Device r({});
  Host h(r);
  const struct {
    MsgId id;
    std::vector<std::uint8_t> poll;
    std::size_t len;
  } cases[] = {
      {msg::kCfgPrt, {}, 20},    {msg::kCfgPrt, {3}, 20},   {msg::kCfgPrt, {0}, 20},  {msg::kCfgMsg, {1, 2}, 8},
      {msg::kCfgRate, {}, 6},    {msg::kCfgNav5, {}, 36},   {msg::kCfgNavx5, {}, 40}, {msg::kCfgGnss, {}, 60},
      {msg::kCfgSbas, {}, 8},    {msg::kCfgTp5, {}, 32},    {msg::kCfgTp5, {1}, 32},  {msg::kCfgInf, {0}, 10},
      {msg::kCfgInf, {1}, 10},   {msg::kCfgItfm, {}, 8},    {msg::kCfgPm2, {}, 44},   {msg::kCfgRxm, {}, 2},
      {msg::kCfgUsb, {}, 108},   {msg::kCfgAnt, {}, 4},     {msg::kCfgOdo, {}, 20},   {msg::kCfgNmea, {}, 20},
      {msg::kCfgPms, {}, 8},     {msg::kCfgRinv, {}, 23},   {msg::kCfgLogfilter, {}, 12},
      {msg::kCfgDat, {}, 52},    {msg::kCfgGeofence, {}, 8},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(to_hex(frame_bytes(c.id, c.poll)));
    const auto frames = test::split_frames(from_hex(h.send(c.id, c.poll)));
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].id, c.id);
    EXPECT_EQ(frames[0].payload.size(), c.len);
    EXPECT_EQ(frames[1].id, msg::kAckAck);
    EXPECT_EQ(frames[1].payload, (std::vector<std::uint8_t>{c.id.cls, c.id.id}));
  }
  // Sets round-trip: what was set is what a poll returns.
  std::vector<std::uint8_t> itfm = {0xF3, 0xAC, 0x62, 0xAD, 0x1E, 0x03, 0x00, 0x00};  // enabled
  EXPECT_EQ(h.send(msg::kCfgItfm, itfm), "B5 62 05 01 02 00 06 39 47 70");
  auto frames = test::split_frames(from_hex(h.send(msg::kCfgItfm, {})));
  EXPECT_EQ(frames[0].payload, itfm);
  std::vector<std::uint8_t> tp5(32, 0);
  tp5[0] = 1;
  tp5[4] = 0x77;
  EXPECT_EQ(h.send(msg::kCfgTp5, tp5).substr(0, 14), "B5 62 05 01 02");
  frames = test::split_frames(from_hex(h.send(msg::kCfgTp5, {1})));
  EXPECT_EQ(frames[0].payload, tp5);
  // NAV and MON polls: data, no ACK.
  r.on_epoch(test::sample_fix(), 5.0);
  frames = test::split_frames(from_hex(h.send(msg::kNavPvt, {})));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].payload.size(), 92u);
  frames = test::split_frames(from_hex(h.send(msg::kNavSvinfo, {})));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].payload[5] & 7, 4);  // chipGen M8
  frames = test::split_frames(from_hex(h.send(msg::kMonHw, {})));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].payload.size(), 60u);
  EXPECT_EQ((frames[0].payload[22] >> 2) & 3, 1);  // ITFM now enabled: jamming state ok
}

TEST(UbxDevice, CfgCfgSaveLoadClearAndReset) {
  Device r({});
  Host h(r);
  EXPECT_EQ(h.send(msg::kCfgRate, {0xC8, 0x00, 0x01, 0x00, 0x01, 0x00}), kAckRate);
  EXPECT_EQ(h.send(msg::kCfgMsg, {0x01, 0x07, 1}), kAckMsg);
  // Save everything, change again, then load: back to the saved values.
  EXPECT_EQ(h.send(msg::kCfgCfg, {0, 0, 0, 0, 0xFF, 0xFF, 0, 0, 0, 0, 0, 0, 0x17}), "B5 62 05 01 02 00 06 09 17 40");
  EXPECT_EQ(h.send(msg::kCfgRate, {0x64, 0x00, 0x01, 0x00, 0x01, 0x00}), kAckRate);
  EXPECT_DOUBLE_EQ(r.config().nav_period_s(), 0.1);
  h.send(msg::kCfgCfg, {0, 0, 0, 0, 0, 0, 0, 0, 0xFF, 0xFF, 0, 0});
  EXPECT_TRUE(h.last().nav_rate_changed);
  EXPECT_DOUBLE_EQ(r.config().nav_period_s(), 0.2);
  // A baud change, then a software reset: RAM config lost, saved loaded,
  // the port goes back to the saved baud. No ACK for CFG-RST.
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x8C0, 115200, 7, 3)), kAckPrt);
  EXPECT_EQ(h.send(msg::kCfgRst, {0xFF, 0xFF, 0x01, 0x00}), "");
  EXPECT_EQ(h.last().reply, Reply::kReset);
  EXPECT_TRUE(h.last().reset.has_value());
  EXPECT_EQ(h.last().reset->nav_bbr_mask, 0xFFFF);
  EXPECT_EQ(h.last().new_baud_bps, 9600u);
  EXPECT_EQ(r.message_rate({0, kPortUart1}, msg::kNavPvt), 1);  // saved
  // Clear the saved config to factory and load it.
  h.send(msg::kCfgCfg, {0xFF, 0xFF, 0, 0, 0, 0, 0, 0, 0xFF, 0xFF, 0, 0});
  EXPECT_TRUE(r.config() == DeviceConfig::factory_defaults());
  EXPECT_EQ(r.message_rate({0, kPortUart1}, msg::kNavPvt), 0);
  EXPECT_DOUBLE_EQ(r.config().nav_period_s(), 1.0);
}

TEST(UbxDevice, RepliesFollowThePortsProtocolMasks) {
  Device r({});
  Host h(r);
  // NMEA-only output: the ACK for this very change is not sent (UBX output off).
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x8C0, 9600, 0x07, 0x02)), "");
  EXPECT_EQ(r.port({0, kPortUart1}).out_proto_mask, proto::kNmea);
  EXPECT_EQ(h.send(msg::kMonVer, {}), "");
  r.on_epoch(test::sample_fix(), 1.0);
  std::string out;
  EXPECT_EQ(test::ubx_epoch(r, {0, kPortUart1}, out), 0u);
  // gpsd's way back to binary: PUBX,41 with UBX+NMEA out.
  h.send("$PUBX,41,1,0007,0003,9600,0*10\r\n");
  EXPECT_EQ(r.port({0, kPortUart1}).out_proto_mask, proto::kUbx | proto::kNmea);
  EXPECT_EQ(h.send(msg::kMonVer, {}), kMonVer);
  // UBX input off: UBX commands are not even parsed.
  h.send("$PUBX,41,1,0002,0003,9600,0*15\r\n");
  EXPECT_EQ(h.send(msg::kMonVer, {}), "");
  // NMEA standard poll asks for one sentence now.
  h.send("$EIGPQ,RMC*3A\r\n");
  EXPECT_TRUE(h.last().nmea_poll.has(nmea::Sentence::kRmc));
  EXPECT_FALSE(h.last().nmea_poll.has(nmea::Sentence::kGga));
}

TEST(UbxDevice, StatusCountsTtffAndUptime) {
  Device r({});
  r.config().set_message_rate(kPortUart1, msg::kNavStatus, 1);
  receiver::Fix none = test::sample_fix();
  none.type = receiver::FixType::kNone;
  const auto status = [&](double up, const receiver::Fix& f) {
    r.on_epoch(f, up);
    std::string out;
    test::ubx_epoch(r, {0, kPortUart1}, out);
    const auto fr = test::split_frames(out);
    wire::NavStatus s{};
    EXPECT_EQ(fr.size(), 1u);
    std::memcpy(&s, fr[0].payload.data(), sizeof s);
    return s;
  };
  EXPECT_EQ(status(1.0, none).ttff, 0u);
  const auto s = status(27.5, test::sample_fix());
  EXPECT_EQ(s.ttff, 27500u);
  EXPECT_EQ(s.msss, 27500u);
  EXPECT_EQ(status(40.0, test::sample_fix()).ttff, 27500u);
}

TEST(UbxDevice, ResetKeepsWhatNavBbrMaskKeeps) {
  // CFG-RST navBbrMask (UBX-13003221): b0 eph, b1 alm, b4 pos, b8 rtc.
  const Reset hot{0x0000, ResetMode::kGnssOnly}, warm{0x0001, ResetMode::kGnssOnly},
      cold{0xFFFF, ResetMode::kHardware}, no_pos{0x0010, ResetMode::kSoftware};
  EXPECT_TRUE(hot.keeps_ephemeris() && hot.keeps_almanac() && hot.keeps_position() && hot.keeps_time());
  EXPECT_FALSE(warm.keeps_ephemeris());
  EXPECT_TRUE(warm.keeps_almanac() && warm.keeps_position() && warm.keeps_time());
  EXPECT_FALSE(cold.keeps_ephemeris() || cold.keeps_almanac() || cold.keeps_position() || cold.keeps_time());
  EXPECT_TRUE(no_pos.keeps_ephemeris() && no_pos.keeps_time());
  EXPECT_FALSE(no_pos.keeps_position());
  EXPECT_EQ(no_pos.start(), StartKind::kWarm);
}

TEST(UbxDevice, StartsWithTheReceiversNav5) {
  // The configured dynamic model and static hold, read back by a CFG-NAV5 poll.
  DeviceSetup setup;
  setup.dyn_model = 4;
  setup.static_hold_thresh_cm_s = 50;
  setup.static_hold_max_dist_m = 20;
  Device r(setup);
  EXPECT_EQ(r.config().nav5.dynModel, 4);
  EXPECT_EQ(r.saved().nav5.dynModel, 4);
  EXPECT_EQ(r.config().nav5.staticHoldThresh, 50);
  EXPECT_EQ(r.config().nav5.staticHoldMaxDist, 20);
  Host h(r);
  const std::string poll = h.send(msg::kCfgNav5, {});
  EXPECT_EQ(poll.substr(0, 17), "B5 62 06 24 24 00");
  EXPECT_EQ(poll.substr(24, 2), "04");  // payload byte 2: dynModel
  // A host's change is reported so the receiver can follow it.
  std::vector<std::uint8_t> nav5(36, 0);
  nav5[0] = 0x01;  // mask: dyn
  nav5[2] = 7;     // airborne < 2 g
  EXPECT_EQ(h.send(msg::kCfgNav5, nav5), kAckNav5);
  EXPECT_TRUE(h.last().nav_config_changed);
  EXPECT_EQ(r.config().nav5.dynModel, 7);
}

TEST(UbxDevice, Pubx40SetsNmeaRatesPerPort) {
  Device r({});
  Host h(r);
  h.send("$PUBX,40,GSV,0,5,0,1,0,0*5D\r\n");
  EXPECT_TRUE(h.last().rates_changed);
  EXPECT_EQ(r.message_rate({0, kPortUart1}, msg::kNmeaGsv), 5);
  EXPECT_EQ(r.message_rate({0, kPortUsb}, msg::kNmeaGsv), 1);
  EXPECT_EQ(r.message_rate({0, kPortDdc}, msg::kNmeaGsv), 0);
}

TEST(UbxDevice, CfgPrtNaksWhatTheLineCannotBeSetTo) {
  // The daemon's lines run 8N1 at the standard u-blox rates; a baud or frame
  // format it cannot set must not be ACKed and then silently misapplied.
  Device r({});
  Host h(r);
  const std::string nak = "B5 62 05 00 02 00 06 00 0D 32";
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x8D0, 100000, 1, 1)), nak);  // not a u-blox rate
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x8D0, 14400, 1, 1)), nak);
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x8D0, 0, 1, 1)), nak);
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x8D0, 1843200, 1, 1)), nak);
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x880, 9600, 1, 1)), nak);           // 7 data bits
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x0C0, 9600, 1, 1)), nak);           // even parity
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x8C0 | 0x2000, 9600, 1, 1)), nak);  // 2 stop bits
  EXPECT_EQ(r.port({0, kPortUart1}).baud_bps, 9600u);
  EXPECT_EQ(r.port({0, kPortUart1}).in_proto_mask, 0x07);  // nothing applied
  for (std::uint32_t b : {4800u, 19200u, 57600u, 230400u, 460800u, 921600u}) {
    EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(1, 0x8C0, b, 7, 3)), kAckPrt) << b;
    EXPECT_EQ(h.last().new_baud_bps, b);
  }
  // USB and DDC blocks carry no baud: still ACKed.
  EXPECT_EQ(h.send(msg::kCfgPrt, cfg_prt(3, 0, 0, 7, 3)), kAckPrt);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

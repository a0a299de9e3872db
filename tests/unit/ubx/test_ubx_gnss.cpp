// SPDX-License-Identifier: Apache-2.0
// Multi-GNSS on the UBX side: NAV-SAT / NAV-SVINFO / NAV-SIG numbering, the
// other systems' time messages against a real log, CFG-GNSS and CFG-SIGNAL
// with the chip's rules (including the exact bytes PX4 and ArduPilot send),
// MON-GNSS, MON-HW2 at a host's rate, and the navigation-rate limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/common/error.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/config/ubx_gnss.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx::gnss_test {
namespace {

using test::Frame;
using test::split_frames;

DeviceSetup setup_of(Generation g) {
  DeviceSetup s;
  s.mon_ver = mon_ver_of(g);
  return s;
}

/// A host on UART1 of output 0: sends one frame, returns the frames the device answered.
struct Host {
  explicit Host(Device& device) : d(device) {}
  Device& d;
  InputResult last;
  std::vector<Frame> send(MsgId id, const std::vector<std::uint8_t>& payload) {
    std::string out;
    last = d.handle_ubx(Link{}, FrameView{id, payload}, 0.0, out);
    return split_frames(out);
  }
  bool acked(MsgId id, const std::vector<std::uint8_t>& payload) {
    const auto f = send(id, payload);
    return !f.empty() && f.back().id == msg::kAckAck;
  }
  std::vector<std::uint8_t> poll(MsgId id) {
    const auto f = send(id, {});
    return f.empty() ? std::vector<std::uint8_t>{} : f.front().payload;
  }
};

void put_u4(std::vector<std::uint8_t>& p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
/// A CFG-GNSS block: gnssId, resTrkCh, maxTrkCh, flags.
void block(std::vector<std::uint8_t>& p, std::uint8_t id, std::uint8_t res, std::uint8_t max, std::uint32_t flags) {
  p.insert(p.end(), {id, res, max, 0});
  put_u4(p, flags);
}
/// VALSET version 0 to RAM with one-byte (L) values, as PX4's cfgValset<uint8_t> builds it.
std::vector<std::uint8_t> valset_l(std::initializer_list<std::pair<std::uint32_t, std::uint8_t>> kv) {
  std::vector<std::uint8_t> p{0, 0x01, 0, 0};
  for (const auto& [key, value] : kv) {
    put_u4(p, key);
    p.push_back(value);
  }
  return p;
}

constexpr SystemSet set_of(std::initializer_list<GnssSystem> systems) {
  SystemSet s;
  for (const GnssSystem g : systems) s = s.with(g);
  return s;
}
using enum GnssSystem;

receiver::SatInfo sat(SatId id, double cn0, bool used) {
  receiver::SatInfo s;
  s.sat = id;
  s.el_rad = 0.5;
  s.az_rad = 1.0;
  s.cn0_dbhz = cn0;
  s.healthy = s.above_mask = true;
  s.tracked = cn0 > 0.0;
  s.used = used;
  s.residual_m = 1.25;
  return s;
}

/// sample_fix() with one satellite of every system (and a BeiDou GEO and MEO), in SatId order.
receiver::Fix multi_fix() {
  receiver::Fix f = test::sample_fix();
  const receiver::SatInfo list[] = {sat(SatId::gps(3), 41, true),
                                    sat(SatId(kGlonass, 5), 35, true),
                                    sat(SatId(kGalileo, 11), 38, true),
                                    sat(SatId(kBeiDou, 3), 40, false),
                                    sat(SatId(kBeiDou, 20), 39, true),
                                    sat(SatId(kQzss, 2), 36, true),
                                    sat(SatId(kSbas, 23), 44, false)};
  f.num_sats = 0;
  for (const auto& s : list) f.sats[static_cast<std::size_t>(f.num_sats++)] = s;
  f.sats[1].glonass_channel = -4;
  return f;
}

TEST(UbxGnss, NavSatListsEverySystemByGnssIdWithNativeSvIds) {
  std::string out;
  UbxEncoder(mon_ver_of(Generation::kM8)).nav_sat(multi_fix(), out);
  const auto f = split_frames(out);
  ASSERT_EQ(f.size(), 1u);
  ASSERT_EQ(f[0].payload[5], 7);  // numSvs
  // (gnssId, svId) in u-blox order: GPS, SBAS, Galileo, BeiDou, QZSS, GLONASS (pygpsdata-MIXED.log order).
  const std::pair<int, int> want[] = {{0, 3}, {1, 123}, {2, 11}, {3, 3}, {3, 20}, {5, 2}, {6, 5}};
  for (std::size_t i = 0; i < 7; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(f[0].payload[8 + 12 * i], want[i].first);
    EXPECT_EQ(f[0].payload[8 + 12 * i + 1], want[i].second);
  }
}

TEST(UbxGnss, NavSvinfoNumbersAsTheM8) {
  std::string out;
  UbxEncoder(mon_ver_of(Generation::kM8)).nav_svinfo(multi_fix(), out);
  const auto f = split_frames(out);
  ASSERT_EQ(f.size(), 1u);
  ASSERT_EQ(f[0].payload[4], 7);
  // GPS 3, SBAS 123, Galileo E11 = 221, C03 = 161 (159-163), C20 = 47 (33-64), QZSS J02 = 194, R05 = 69.
  const int want[] = {3, 123, 221, 161, 47, 194, 69};
  for (std::size_t i = 0; i < 7; ++i) EXPECT_EQ(f[0].payload[8 + 12 * i + 1], want[i]) << i;
  EXPECT_EQ(svinfo_svid(SatId(kBeiDou, 40)), 0);  // the M8 has no SVINFO number for C38+
}

TEST(UbxGnss, NavSigCarriesSignalFrequencyAndUse) {
  std::string out;
  UbxEncoder(mon_ver_of(Generation::kM9)).nav_sig(multi_fix(), out);
  const auto f = split_frames(out);
  ASSERT_EQ(f.size(), 1u);
  const auto& p = f[0].payload;
  ASSERT_EQ(p[4], 0);  // version
  ASSERT_EQ(p[5], 7);
  const auto sig = [&](std::size_t i) {
    wire::NavSigSig s{};
    std::memcpy(&s, p.data() + 8 + 16 * i, sizeof s);
    return s;
  };
  EXPECT_EQ(sig(0).sigFlags, 0x29);  // GPS used: healthy, prUsed, doUsed (as the F9T/M10 logs)
  EXPECT_EQ(sig(0).prRes, 13);       // 1.25 m in 0.1 m
  EXPECT_EQ(sig(1).sigFlags, 0x01);  // SBAS tracked, not used
  EXPECT_EQ(sig(3).sigId, 1);        // C03 is a GEO: B1I D2
  EXPECT_EQ(sig(4).sigId, 0);        // C20: B1I D1
  EXPECT_EQ(sig(6).gnssId, 6);
  EXPECT_EQ(sig(6).freqId, 3);       // k = -4 -> 3 (slot 2 in the SPG 5.10 log)
  EXPECT_EQ(sig(6).cno, 35);
}

TEST(UbxGnss, NavSigQualityIndFollowsTracking) {
  // u-blox's qualityInd (UBX-18010854 NAV-SIG): 7 code and carrier locked, 4 code
  // locked (our weak-signal state below 30 dB-Hz), 1 signal searched, 0 no signal.
  receiver::Fix fix = multi_fix();
  fix.sats[2].cn0_dbhz = 25.0;  // E11 weak: code lock only
  fix.sats[5].cn0_dbhz = 0.0;   // J02 above the mask, not tracked
  fix.sats[5].tracked = fix.sats[5].used = false;
  std::string out;
  UbxEncoder(mon_ver_of(Generation::kM9)).nav_sig(fix, out);
  const auto f = split_frames(out);
  ASSERT_EQ(f.size(), 1u);
  const auto& p = f[0].payload;
  std::map<std::pair<int, int>, wire::NavSigSig> by_sat;
  for (std::size_t i = 0; i < p[5]; ++i) {
    wire::NavSigSig sg{};
    std::memcpy(&sg, p.data() + 8 + 16 * i, sizeof sg);
    by_sat[{sg.gnssId, sg.svId}] = sg;
  }
  EXPECT_EQ(by_sat.at({0, 3}).qualityInd, 7);   // G03 at 41 dB-Hz, used
  EXPECT_EQ(by_sat.at({2, 11}).qualityInd, 4);  // E11 at 25 dB-Hz
  EXPECT_EQ(by_sat.at({2, 11}).cno, 25);
  if (by_sat.count({5, 2}) != 0) {
    EXPECT_EQ(by_sat.at({5, 2}).qualityInd, 1);  // searched, no signal
    EXPECT_EQ(by_sat.at({5, 2}).cno, 0);
    EXPECT_EQ(by_sat.at({5, 2}).sigFlags & 0x38, 0);  // nothing used
  }
  // NAV-SAT (the same derivation) agrees for every satellite NAV-SIG lists.
  out.clear();
  UbxEncoder(mon_ver_of(Generation::kM9)).nav_sat(fix, out);
  const auto sat_frames = split_frames(out);
  ASSERT_EQ(sat_frames.size(), 1u);
  const auto& q = sat_frames[0].payload;
  for (std::size_t i = 0; i < q[5]; ++i) {
    const std::uint8_t* sv = q.data() + 8 + 12 * i;
    std::uint32_t flags = 0;
    std::memcpy(&flags, sv + 8, 4);
    const auto it = by_sat.find({sv[0], sv[1]});
    if (it != by_sat.end()) {
      EXPECT_EQ(flags & 7u, it->second.qualityInd) << int(sv[0]) << " " << int(sv[1]);
    }
  }
}

/// The epoch of pygpsdata-MIXED.log's NAV-TIMEGPS iTOW 473621000 (2020-10-23 11:33:23 UTC).
receiver::Fix mixed_log_epoch() {
  receiver::Fix f = test::sample_fix();
  f.t = time::GpsTime(2128, 473621.000050126);
  f.leap_seconds = 18;
  return f;
}

TEST(UbxGnss, TimeMessagesMatchTheRealLog) {
  const UbxEncoder enc(mon_ver_of(Generation::kM8));
  const receiver::Fix fix = mixed_log_epoch();
  std::string out;
  enc.nav_timeglo(fix, out);
  enc.nav_timebds(fix, out);
  enc.nav_timegal(fix, out);
  const auto f = split_frames(out);
  ASSERT_EQ(f.size(), 3u);
  wire::NavTimeglo glo{};
  wire::NavTimeSow bds{}, gal{};
  std::memcpy(&glo, f[0].payload.data(), sizeof glo);
  std::memcpy(&bds, f[1].payload.data(), sizeof bds);
  std::memcpy(&gal, f[2].payload.data(), sizeof gal);
  // The log: GLO TOD 52403 Nt 297 N4 7 valid 3; BDS SOW 473607 fSOW 50126 week 772 leapS 4;
  // GAL galTow 473621 fGalTow 50126 galWno 1104 leapS 18 (fTOD there is 50080: the receiver's
  // GLONASS-GPS time offset, not modelled).
  EXPECT_EQ(glo.iTOW, 473621000u);
  EXPECT_EQ(glo.TOD, 52403u);
  EXPECT_NEAR(glo.fTOD, 50126, 1);
  EXPECT_EQ(glo.Nt, 297);
  EXPECT_EQ(glo.N4, 7);
  EXPECT_EQ(glo.valid, 3);
  EXPECT_EQ(bds.sow, 473607u);
  EXPECT_NEAR(bds.fSow, 50126, 1);
  EXPECT_EQ(bds.week, 772);
  EXPECT_EQ(bds.leapS, 4);
  EXPECT_EQ(bds.valid, 7);
  EXPECT_EQ(gal.sow, 473621u);
  EXPECT_EQ(gal.week, 1104);
  EXPECT_EQ(gal.leapS, 18);
  EXPECT_EQ(gal.valid, 7);
}

TEST(UbxGnss, GlonassDayFollowsUtcPlusThreeHours) {
  receiver::Fix fix = mixed_log_epoch();
  // 2020-12-31 22:30:00 UTC is 2021-01-01 01:30 GLONASST: day 367 of the 2020-2023 period.
  fix.t = time::GpsTime(2138, 4 * 86400 + 22.5 * 3600 + 18);
  std::string out;
  UbxEncoder(mon_ver_of(Generation::kM8)).nav_timeglo(fix, out);
  wire::NavTimeglo glo{};
  std::memcpy(&glo, split_frames(out)[0].payload.data(), sizeof glo);
  EXPECT_EQ(glo.TOD, 5400u);
  EXPECT_EQ(glo.Nt, 367);
  EXPECT_EQ(glo.N4, 7);
}

TEST(UbxGnss, FactorySetsAndMonGnss) {
  Device m8(setup_of(Generation::kM8));
  Device m9(setup_of(Generation::kM9));
  EXPECT_EQ(m8.enabled_systems(), set_of({kGps, kGlonass, kQzss, kSbas}));
  EXPECT_EQ(m9.enabled_systems(), SystemSet::all());
  Host h8{m8}, h9{m9};
  // version, supported, default, enabled, simultaneous.
  EXPECT_EQ(h8.poll(msg::kMonGnss), (std::vector<std::uint8_t>{1, 0x0F, 0x03, 0x03, 3, 0, 0, 0}));
  EXPECT_EQ(h9.poll(msg::kMonGnss), (std::vector<std::uint8_t>{1, 0x0F, 0x0F, 0x0F, 4, 0, 0, 0}));
}

/// The M8 CFG-GNSS PX4 (PX4-GPSDrivers src/ubx.cpp, configureDevicePreV27) sends for its
/// GPS_1_GNSS mask: bit 0 GPS+QZSS, 1 SBAS, 2 Galileo, 3 BeiDou, 4 GLONASS. msgVer 0,
/// numTrkChHw 0, numTrkChUse 0xFF, 7 blocks in its order; disabled systems all zero.
std::vector<std::uint8_t> px4_cfg_gnss(unsigned mask) {
  std::vector<std::uint8_t> p{0, 0, 0xFF, 7};
  const bool gps = mask & 1, sbas = mask & 2, gal = mask & 4, bds = mask & 8, glo = mask & 16;
  block(p, 0, gps ? 8 : 0, gps ? 16 : 0, gps ? 0x00010001 : 0);
  block(p, 5, 0, gps ? 3 : 0, gps ? 0x00010001 : 0);
  block(p, 1, sbas ? 1 : 0, sbas ? 3 : 0, sbas ? 0x00010001 : 0);
  block(p, 2, gal ? 4 : 0, gal ? 8 : 0, gal ? 0x00010001 : 0);
  block(p, 3, bds ? 8 : 0, bds ? 16 : 0, bds ? 0x00010001 : 0);
  block(p, 6, glo ? 8 : 0, glo ? 14 : 0, glo ? 0x00010001 : 0);
  block(p, 4, 0, 0, 0);
  return p;
}

TEST(UbxGnss, Px4GnssMaskOnTheM8) {
  Device d(setup_of(Generation::kM8));
  Host h{d};
  // GPS + SBAS + GLONASS (mask 19): ACK, applied, the engine restarts.
  EXPECT_TRUE(h.acked(msg::kCfgGnss, px4_cfg_gnss(1 | 2 | 16)));
  EXPECT_TRUE(h.last.gnss_changed);
  EXPECT_EQ(d.enabled_systems(), set_of({kGps, kQzss, kSbas, kGlonass}));
  // GPS + Galileo + BeiDou (mask 13): three major GNSS, accepted.
  EXPECT_TRUE(h.acked(msg::kCfgGnss, px4_cfg_gnss(1 | 4 | 8)));
  EXPECT_EQ(d.enabled_systems(), set_of({kGps, kQzss, kGalileo, kBeiDou}));
  EXPECT_EQ(h.poll(msg::kMonGnss)[3], 0x0D);  // MON-GNSS follows: GPS, BeiDou, Galileo
  // Everything (mask 31): four major GNSS, more than an M8 runs at once: NAK, old set kept.
  const auto before = h.poll(msg::kCfgGnss);
  EXPECT_FALSE(h.acked(msg::kCfgGnss, px4_cfg_gnss(31)));
  EXPECT_FALSE(h.last.gnss_changed);
  EXPECT_EQ(h.poll(msg::kCfgGnss), before);
  EXPECT_EQ(d.enabled_systems(), set_of({kGps, kQzss, kGalileo, kBeiDou}));
}

/// ArduPilot's CFG-GNSS for GPS_GNSS_MODE (AP_GPS_UBLOX.cpp, MSG_CFG_GNSS): it polls CFG-GNSS,
/// then per polled block: a wanted system gets resTrkCh (numTrkChHw - 3) / (2 * systems other
/// than SBAS) and maxTrkCh numTrkChHw (Galileo on an M8: 8; SBAS 1/3) and the enable bit, the
/// others 0/0 without it; sigCfgMask and numTrkChUse stay as polled.
std::vector<std::uint8_t> ardupilot_cfg_gnss(std::vector<std::uint8_t> polled, unsigned mode) {
  unsigned count = 0;
  for (unsigned i = 0; i < 7; ++i) count += ((mode >> i) & 1u) && i != 1 ? 1 : 0;
  const std::uint8_t hw = polled[1];
  for (std::size_t b = 0; b < polled[3]; ++b) {
    std::uint8_t* blk = polled.data() + 4 + 8 * b;
    if ((mode >> blk[0]) & 1u) {
      blk[1] = blk[0] == 1 ? 1 : static_cast<std::uint8_t>((hw - 3) / (count * 2));
      blk[2] = blk[0] == 1 ? 3 : blk[0] == 2 ? 8 : hw;
      blk[4] |= 0x01;
    } else {
      blk[1] = blk[2] = 0;
      blk[4] &= 0xFE;
    }
  }
  return polled;
}

TEST(UbxGnss, ArduPilotGnssModeOnTheM8) {
  Device d(setup_of(Generation::kM8));
  Host h{d};
  // 67 = GPS + SBAS + GLONASS: 7/32 each, QZSS switched off with GPS on (a recommendation, not a rule).
  auto set = ardupilot_cfg_gnss(h.poll(msg::kCfgGnss), 67);
  EXPECT_EQ(set[4 + 1], 7);
  EXPECT_TRUE(h.acked(msg::kCfgGnss, set));
  EXPECT_EQ(d.enabled_systems(), set_of({kGps, kSbas, kGlonass}));
  EXPECT_EQ(h.poll(msg::kCfgGnss), set);  // its read-back check passes
  // 5 = GPS + Galileo.
  EXPECT_TRUE(h.acked(msg::kCfgGnss, ardupilot_cfg_gnss(h.poll(msg::kCfgGnss), 5)));
  EXPECT_EQ(d.enabled_systems(), set_of({kGps, kGalileo}));
  // 77 = GPS + Galileo + BeiDou + GLONASS: four major GNSS: NAK.
  const auto before = h.poll(msg::kCfgGnss);
  EXPECT_FALSE(h.acked(msg::kCfgGnss, ardupilot_cfg_gnss(before, 77)));
  EXPECT_EQ(h.poll(msg::kCfgGnss), before);
}

TEST(UbxGnss, CfgGnssImpossibleValuesAreNaked) {
  Device d(setup_of(Generation::kM8));
  Host h{d};
  const auto factory = h.poll(msg::kCfgGnss);
  const auto nak = [&](std::vector<std::uint8_t> p, const char* why) {
    EXPECT_FALSE(h.acked(msg::kCfgGnss, p)) << why;
    EXPECT_EQ(h.poll(msg::kCfgGnss), factory) << why;
  };
  std::vector<std::uint8_t> p{0, 32, 32, 1};
  block(p, 0, 8, 3, 0x00010001);
  nak(p, "maxTrkCh 3 < 4 for a major GNSS (and < resTrkCh)");
  p = {0, 32, 32, 1};
  block(p, 0, 40, 40, 0x00010001);
  nak(p, "more channels than the chip has");
  p = {0, 32, 33, 1};
  block(p, 0, 8, 16, 0x00010001);
  nak(p, "numTrkChUse above numTrkChHw");
  p = {0, 32, 32, 2};
  block(p, 0, 20, 32, 0x00010001);
  block(p, 6, 20, 32, 0x00010001);
  nak(p, "sum of reserved channels above numTrkChUse");
  p = {0, 32, 32, 1};
  block(p, 0, 8, 16, 0x00000001);
  nak(p, "an enabled system without a signal");
  p = {0, 32, 32, 1};
  block(p, 0, 8, 16, 0x00110001);
  nak(p, "GPS L2C: a signal the M8 lacks");
  p = {0, 32, 32, 1};
  block(p, 7, 0, 8, 0x00010001);
  nak(p, "unknown gnssId 7 (NavIC)");
  p = {0, 32, 32, 2};
  block(p, 0, 0, 0, 0);
  block(p, 6, 0, 0, 0);
  nak(p, "no major GNSS left");
  p = {0, 32, 32, 2};
  block(p, 2, 4, 8, 0x00010001);
  block(p, 3, 8, 16, 0x00010001);
  nak(p, "GPS + GLONASS + Galileo + BeiDou");
  EXPECT_EQ(d.stats().acks, 0u);
}

constexpr std::uint32_t kKeyGps = 0x1031001F, kKeyQzss = 0x10310024, kKeyGal = 0x10310021, kKeyGalE1 = 0x10310007,
                        kKeyBds = 0x10310022, kKeyGlo = 0x10310025, kKeySbas = 0x10310020, kKeySbasL1 = 0x10310005,
                        kKeyQzssL1s = 0x10310014;

TEST(UbxGnss, Px4SignalKeysOnTheM9) {
  Device d(setup_of(Generation::kM9));
  Host h{d};
  // PX4 (configureDevice, GPS_1_GNSS = GPS + GLONASS): one VALSET with the five ENA keys, then SBAS alone.
  EXPECT_TRUE(h.acked(msg::kCfgValset,
                      valset_l({{kKeyGps, 1}, {kKeyQzss, 1}, {kKeyGal, 0}, {kKeyBds, 0}, {kKeyGlo, 1}})));
  EXPECT_TRUE(h.last.gnss_changed);
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset_l({{kKeySbas, 0}})));
  EXPECT_EQ(d.enabled_systems(), set_of({kGps, kQzss, kGlonass}));
  EXPECT_EQ(h.poll(msg::kMonGnss)[3], 0x03);
  // SBAS back on, as PX4 sends it: SBAS_ENA and SBAS_L1CA_ENA.
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset_l({{kKeySbas, 1}, {kKeySbasL1, 1}})));
  EXPECT_TRUE(d.enabled_systems().has(kSbas));
  // PX4-GPSDrivers after #181 adds QZSS_L1S_ENA, which a NEO-M9N does not know: the whole VALSET is NAKed.
  const SystemSet before = d.enabled_systems();
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset_l({{kKeyGps, 1}, {kKeyQzss, 1}, {kKeyQzssL1s, 1}, {kKeyGal, 1}})));
  EXPECT_EQ(d.enabled_systems(), before);
}

TEST(UbxGnss, M9SignalConfigurationMustBeRunnable) {
  Device d(setup_of(Generation::kM9));
  Host h{d};
  // Galileo on without its only signal: NAK, nothing applied.
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset_l({{kKeyGalE1, 0}})));
  EXPECT_TRUE(d.enabled_systems().has(kGalileo));
  // Off together: fine.
  EXPECT_TRUE(h.acked(msg::kCfgValset, valset_l({{kKeyGal, 0}, {kKeyGalE1, 0}})));
  EXPECT_FALSE(d.enabled_systems().has(kGalileo));
  // Every major GNSS off: NAK.
  EXPECT_FALSE(h.acked(msg::kCfgValset, valset_l({{kKeyGps, 0}, {kKeyBds, 0}, {kKeyGlo, 0}})));
  EXPECT_TRUE(d.enabled_systems().has(kGps));
  // The M8 has no configuration interface at all.
  Device m8(setup_of(Generation::kM8));
  Host h8{m8};
  EXPECT_FALSE(h8.acked(msg::kCfgValset, valset_l({{kKeyGal, 1}})));
}

TEST(UbxGnss, NavRateLimits) {
  // NEO-M8 data sheet: 18 Hz with one GNSS, 10 Hz with more.
  EXPECT_EQ(nav_rate_limits(Generation::kM8, set_of({kGps, kQzss, kSbas})).max_nav_rate_hz, 18.0);
  EXPECT_EQ(nav_rate_limits(Generation::kM8, set_of({kGps, kGlonass})).max_nav_rate_hz, 10.0);
  // NEO-M9N: the solution keeps 16 satellites above 8 Hz.
  const NavRateLimits m9 = Device(setup_of(Generation::kM9)).nav_rate_limits();
  EXPECT_EQ(m9.max_solution_sats, 16);
  EXPECT_EQ(m9.sat_cap_above_hz, 8.0);
  Device m8(setup_of(Generation::kM8));
  Host h{m8};
  EXPECT_TRUE(h.acked(msg::kCfgGnss, px4_cfg_gnss(1)));  // GPS + QZSS only
  EXPECT_EQ(m8.nav_rate_limits().max_nav_rate_hz, 18.0);
}

TEST(UbxGnss, ChannelLimitsFollowCfgGnss) {
  // Factory M8: 32 channels; maxTrkCh GPS 16, SBAS 3, QZSS 3, GLONASS 14; Galileo and BeiDou off.
  Device d(setup_of(Generation::kM8));
  ChannelLimits lim = d.channel_limits();
  EXPECT_EQ(lim.total, 32);
  const auto of = [&](GnssSystem s) { return lim.per_system[static_cast<std::size_t>(s)]; };
  EXPECT_EQ(of(kGps), 16);
  EXPECT_EQ(of(kSbas), 3);
  EXPECT_EQ(of(kQzss), 3);
  EXPECT_EQ(of(kGlonass), 14);
  EXPECT_EQ(of(kGalileo), 0);
  EXPECT_EQ(of(kBeiDou), 0);
  // ArduPilot's GPS + Galileo: Galileo gets its 8, GLONASS none.
  Host h{d};
  EXPECT_TRUE(h.acked(msg::kCfgGnss, ardupilot_cfg_gnss(h.poll(msg::kCfgGnss), 5)));
  lim = d.channel_limits();
  EXPECT_EQ(of(kGalileo), 8);
  EXPECT_EQ(of(kGlonass), 0);
  EXPECT_EQ(of(kGps), 32);
}

TEST(UbxGnss, MonHw2AtTheRateAHostSets) {
  Device d(setup_of(Generation::kM8));
  Host h{d};
  // ArduPilot: CFG-MSG MON-HW2 at 5.
  EXPECT_TRUE(h.acked(msg::kCfgMsg, {0x0A, 0x0B, 5}));
  int sent = 0;
  for (int epoch = 0; epoch < 10; ++epoch) {
    d.on_epoch(test::sample_fix(), epoch);
    std::string out;
    test::ubx_epoch(d, Link{}, out);
    for (const Frame& f : split_frames(out)) {
      if (f.id != msg::kMonHw2) continue;
      ++sent;
      ASSERT_EQ(f.payload.size(), 28u);  // ArduPilot logs only this length
      EXPECT_EQ(f.payload[1], f.payload[3]);  // magI = magQ: the MON-HW front end
    }
  }
  EXPECT_EQ(sent, 2);
  EXPECT_EQ(h.poll(msg::kMonHw2).size(), 28u);
}

TEST(UbxGnss, SavedConfigurationSurvivesARestart) {
  DeviceSetup s = setup_of(Generation::kM8);
  std::string state;
  {
    Device d(s);
    Host h{d};
    // ArduPilot's configuration: 5 Hz, UBX only at 230400, NAV-PVT on; then CFG-CFG save (all sections).
    EXPECT_TRUE(h.acked(msg::kCfgRate, {0xC8, 0x00, 0x01, 0x00, 0x00, 0x00}));
    EXPECT_TRUE(h.acked(msg::kCfgPrt, {0x01, 0x00, 0x00, 0x00, 0xC0, 0x08, 0x00, 0x00, 0x00, 0x84, 0x03, 0x00,
                                       0x01, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00}));
    EXPECT_TRUE(h.acked(msg::kCfgMsg, {0x01, 0x07, 1}));
    EXPECT_FALSE(h.last.saved_changed);
    EXPECT_TRUE(h.acked(msg::kCfgCfg, {0, 0, 0, 0, 0xFF, 0xFF, 0, 0, 0, 0, 0, 0}));
    EXPECT_TRUE(h.last.saved_changed);
    state = d.saved().to_text();
  }
  // Power cycle: a new chip loads the state file.
  Device d2(s);
  EXPECT_EQ(d2.epoch_period_s(), 1.0);
  DeviceConfig loaded = DeviceConfig::factory_defaults(1, Generation::kM8);
  loaded.read_text(state, "state.txt");
  d2.load_saved(loaded);
  EXPECT_DOUBLE_EQ(d2.epoch_period_s(), 0.2);
  EXPECT_EQ(d2.port(Link{}).baud_bps, 230400u);
  EXPECT_EQ(d2.port(Link{}).out_proto_mask, proto::kUbx);
  EXPECT_EQ(d2.message_rate(Link{}, msg::kNavPvt), 1);
  EXPECT_TRUE(d2.config() == d2.saved());
  // CFG-CFG clear + load: back to the factory's, and the state file must follow (saved_changed).
  Host h2{d2};
  EXPECT_TRUE(h2.acked(msg::kCfgCfg, {0xFF, 0xFF, 0, 0, 0, 0, 0, 0, 0xFF, 0xFF, 0, 0}));
  EXPECT_TRUE(h2.last.saved_changed);
  EXPECT_EQ(d2.config().rate.measRate, 1000);
  // On the M9, a VALSET to BBR/Flash changes the saved configuration too; to RAM it does not.
  Device m9(setup_of(Generation::kM9));
  Host h9{m9};
  EXPECT_TRUE(h9.acked(msg::kCfgValset, valset_l({{kKeyGal, 0}, {kKeyGalE1, 0}})));
  EXPECT_FALSE(h9.last.saved_changed);
  std::vector<std::uint8_t> to_flash = valset_l({{kKeyGal, 0}, {kKeyGalE1, 0}});
  to_flash[1] = 0x06;  // BBR + Flash
  EXPECT_TRUE(h9.acked(msg::kCfgValset, to_flash));
  EXPECT_TRUE(h9.last.saved_changed);
  EXPECT_FALSE(enabled_systems(m9.saved()).has(kGalileo));
}

TEST(UbxGnss, StateTextRoundTripsAndRejectsGarbage) {
  DeviceConfig c = DeviceConfig::factory_defaults(2, Generation::kM9);
  c.rate.measRate = 125;
  c.set_message_rate(1, msg::kNavSat, 10);
  c.set_plain_value(3, 1);
  DeviceConfig back = DeviceConfig::factory_defaults(2, Generation::kM9);
  back.read_text(c.to_text(), "s");
  EXPECT_TRUE(back == c);
  for (const char* bad : {"hello\n", "gnssemu-ubx-state 1\ncfg-rate 10 1 0\n", "gnssemu-ubx-state 1\nblock 1 7 0 zz\n",
                          "gnssemu-ubx-state 1\nwhat 1\n", "gnssemu-ubx-state 1\nport 1 3 1 0 0 0 0 0 0 0\n"}) {
    DeviceConfig x = DeviceConfig::factory_defaults(2, Generation::kM9);
    EXPECT_THROW(x.read_text(bad, "s"), Error) << bad;
    EXPECT_TRUE(x == DeviceConfig::factory_defaults(2, Generation::kM9)) << bad;
  }
}

}  // namespace
}  // namespace gnssemu::protocol::ubx::gnss_test

namespace gnssemu::protocol::ubx::gnss_test {
namespace {

/// Every NAV-SAT entry of the pyubx2 MIXED log (an M8: GPS, SBAS, GLONASS) has
/// the NAV-SVINFO svid of the same epoch, in the same place, that
/// svinfo_svid() gives its (gnssId, svId): the M8 numbering is the log's.
TEST(UbxGnss, SvinfoNumbersMatchTheRealLog) {
  std::ifstream in(std::string(GNSSEMU_TEST_DATA) + "/receiver-logs/pygpsdata-MIXED-excerpt.log", std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::map<std::uint32_t, std::vector<std::uint8_t>> svinfo;  // iTOW -> svids
  int compared = 0;
  for (const Frame& f : split_frames(ss.str())) {
    if (f.payload.size() < 8) continue;
    std::uint32_t itow = 0;
    std::memcpy(&itow, f.payload.data(), 4);
    if (f.id == msg::kNavSvinfo) {
      for (std::size_t i = 0; i < f.payload[4]; ++i) svinfo[itow].push_back(f.payload[8 + 12 * i + 1]);
    } else if (f.id == msg::kNavSat && svinfo.count(itow) != 0) {
      const auto& ids = svinfo[itow];
      ASSERT_EQ(ids.size(), f.payload[5]);
      for (std::size_t i = 0; i < ids.size(); ++i) {
        const std::uint8_t gnss_id = f.payload[8 + 12 * i], sv_id = f.payload[8 + 12 * i + 1];
        const auto sys = system_of_gnss_id(gnss_id);
        ASSERT_TRUE(sys.has_value());
        const auto id = *sys == GnssSystem::kSbas ? SatId::from_prn(*sys, sv_id) : std::optional<SatId>(SatId(*sys, sv_id));
        ASSERT_TRUE(id && id->valid());
        EXPECT_EQ(svinfo_svid(*id), ids[i]) << int(gnss_id) << " " << int(sv_id);
        EXPECT_EQ(ubx_sv_id(*id), sv_id);
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 50);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx::gnss_test

namespace gnssemu::protocol::ubx::gnss_test {
namespace {

TEST(UbxGnss, CfgNmeaEveryFormAndKeyReachesTheSettings) {
  Device m8(setup_of(Generation::kM8));
  EXPECT_EQ(m8.nmea_settings().nmea_version, 0x40);  // NMEA 4.0 from the factory (the M8 logs)
  EXPECT_EQ(Device(setup_of(Generation::kM9)).nmea_settings().nmea_version, 0x41);
  Host h{m8};
  // Version 1 (20 bytes): NMEA 4.11, 12 SVs, compat + limit82, Galileo filtered, extended numbering, GN main talker.
  std::vector<std::uint8_t> v1{0x00, 0x4B, 12, 0x05, 0x04, 0, 0, 0, 1, 3, 1, 1, 'G', 'B', 0, 0, 0, 0, 0, 0};
  EXPECT_TRUE(h.acked(msg::kCfgNmea, v1));
  EXPECT_TRUE(h.last.nmea_config_changed);
  CfgNmeaSettings s = m8.nmea_settings();
  EXPECT_EQ(s.nmea_version, 0x4B);
  EXPECT_EQ(s.max_svs, 12);
  EXPECT_TRUE(s.compat && s.limit82 && !s.consider);
  EXPECT_EQ(s.gnss_to_filter, 0x04u);
  EXPECT_EQ(s.sv_numbering, 1);
  EXPECT_EQ(s.main_talker_id, 3);
  EXPECT_EQ(s.gsv_talker_id, 1);
  // The 4-byte form sets only its prefix.
  EXPECT_TRUE(h.acked(msg::kCfgNmea, {0x00, 0x23, 0, 0x02}));
  s = m8.nmea_settings();
  EXPECT_EQ(s.nmea_version, 0x23);
  EXPECT_TRUE(s.consider && !s.compat);
  EXPECT_EQ(s.main_talker_id, 3);
  // The M9's keys: CFG-NMEA-SVNUMBERING, -MAXSVS, -MAINTALKERID.
  Device m9(setup_of(Generation::kM9));
  Host h9{m9};
  EXPECT_TRUE(h9.acked(msg::kCfgValset, valset_l({{0x20930007, 1}, {0x20930002, 16}, {0x20930031, 7}})));
  EXPECT_TRUE(h9.last.nmea_config_changed);
  EXPECT_EQ(m9.nmea_settings().sv_numbering, 1);
  EXPECT_EQ(m9.nmea_settings().max_svs, 16);
  EXPECT_EQ(m9.nmea_settings().main_talker_id, 7);
  EXPECT_FALSE(h9.acked(msg::kCfgValset, valset_l({{0x20930002, 10}})));  // MAXSVS only 0, 8, 12, 16
}

}  // namespace
}  // namespace gnssemu::protocol::ubx::gnss_test

namespace gnssemu::protocol::ubx::gnss_test {
namespace {

/// The NMEA sentence heads ("GNGGA", "GLGSA") of one epoch of d's output 0 with a GPS-only fix.
std::vector<std::string> nmea_heads(Device& d) {
  d.on_epoch(sample_fix(), 10.0);
  MessageList list;
  d.compose({}, list);
  std::vector<std::string> heads;
  for (const MessageList::Message& m : list.messages()) {
    const std::string_view b = list.bytes(m);
    if (!b.empty() && b[0] == '$') heads.emplace_back(b.substr(1, 5));
  }
  return heads;
}

bool has(const std::vector<std::string>& v, std::string_view s) { return std::find(v.begin(), v.end(), s) != v.end(); }

TEST(UbxGnss, CfgGnssAndCfgNmeaChangeTheSentences) {
  // A GPS + GLONASS sky on an M8 (factory: GPS, GLONASS, QZSS, SBAS): GLONASS has
  // its own GSA even with no GLONASS satellite in the fix, and the combined
  // sentences talk GN, as the M8 log does.
  DeviceSetup setup = setup_of(Generation::kM8);
  setup.sky_systems = set_of({kGps, kGlonass});
  Device d(setup);
  std::vector<std::string> heads = nmea_heads(d);
  EXPECT_TRUE(has(heads, "GNGGA") && has(heads, "GNGSA")) << ::testing::PrintToString(heads);
  // GLONASS off (PX4's GPS_1_GNSS = GPS + SBAS): GPS alone, GP talker, one GSA.
  Host h{d};
  ASSERT_TRUE(h.acked(msg::kCfgGnss, px4_cfg_gnss(1 | 2)));
  heads = nmea_heads(d);
  EXPECT_TRUE(has(heads, "GPGGA") && has(heads, "GPGSA") && !has(heads, "GNGSA")) << ::testing::PrintToString(heads);
  // CFG-NMEA main talker GN (3): every combined sentence says GN again.
  ASSERT_TRUE(h.acked(msg::kCfgNmea, {0x00, 0x41, 0, 0x02, 0, 0, 0, 0, 0, 3, 0, 0}));
  heads = nmea_heads(d);
  EXPECT_TRUE(has(heads, "GNGGA") && has(heads, "GNRMC")) << ::testing::PrintToString(heads);
  // A sky without GLONASS: an enabled system the world does not model stays silent.
  DeviceSetup gps_sky = setup;
  gps_sky.sky_systems = set_of({kGps});
  Device g(gps_sky);
  heads = nmea_heads(g);
  EXPECT_TRUE(has(heads, "GPGGA") && !has(heads, "GNGSA")) << ::testing::PrintToString(heads);
}

/// The NMEA sentences (without '$' and checksum) of one epoch of fix.
std::vector<std::string> nmea_epoch(Device& d, const receiver::Fix& fix) {
  d.on_epoch(fix, 10.0);
  MessageList list;
  d.compose({}, list);
  std::vector<std::string> out;
  for (const MessageList::Message& m : list.messages()) {
    const std::string_view b = list.bytes(m);
    if (!b.empty() && b[0] == '$') out.emplace_back(b.substr(1, b.find('*') - 1));
  }
  return out;
}

/// Comma-separated fields of a sentence (the first: talker and type).
std::vector<std::string> fields_of(const std::string& s) {
  std::vector<std::string> f;
  std::stringstream in(s);
  for (std::string x; std::getline(in, x, ',');) f.push_back(x);
  if (!s.empty() && s.back() == ',') f.emplace_back();
  return f;
}

/// Every satellite number GSV names.
std::vector<int> gsv_numbers(const std::vector<std::string>& epoch) {
  std::vector<int> n;
  for (const std::string& s : epoch) {
    if (s.substr(2, 3) != "GSV") continue;
    const std::vector<std::string> f = fields_of(s);
    for (std::size_t i = 4; i + 3 < f.size(); i += 4) {
      if (!f[i].empty()) n.push_back(std::stoi(f[i]));
    }
  }
  return n;
}

TEST(UbxGnss, CfgNmeaPollReportsTheConfiguredVersion) {
  // CFG-NMEA is the chip's: a poll reports the version the first output prints
  // (its factory one, or [[output]] nmea_version), so a host reads what it gets.
  for (const auto& [g, v, want] : {std::tuple{Generation::kM8, nmea::NmeaVersion::k40, 0x40},
                                   std::tuple{Generation::kM8, nmea::NmeaVersion::k411, 0x4B},
                                   std::tuple{Generation::kM9, nmea::NmeaVersion::k410, 0x41},
                                   std::tuple{Generation::kM9, nmea::NmeaVersion::k23, 0x23}}) {
    DeviceSetup setup = setup_of(g);
    setup.outputs.resize(1);
    setup.outputs[0].nmea_version = v;
    setup.outputs[0].protocols_in = setup.outputs[0].protocols_out = 0x03;
    Device d(setup);
    Host h{d};
    const auto p = h.poll(msg::kCfgNmea);
    ASSERT_GE(p.size(), 2u);
    EXPECT_EQ(p[1], want) << static_cast<int>(g);
  }
}

TEST(UbxGnss, CfgNmeaVersionAndNumberingChangeTheSentences) {
  // A NEO-M9N (factory NMEA 4.10, strict numbering) with GPS, GLONASS,
  // Galileo and BeiDou satellites in the fix.
  Device d(setup_of(Generation::kM9));
  receiver::Fix fix = sample_fix();
  ASSERT_GE(fix.num_sats, 6);
  fix.sats[3].sat = SatId(GnssSystem::kGalileo, 5);
  fix.sats[4].sat = SatId(GnssSystem::kBeiDou, 20);
  fix.sats[5].sat = SatId(GnssSystem::kGlonass, 7);
  const auto count = [](const std::vector<std::string>& e, std::string_view head) {
    return std::count_if(e.begin(), e.end(), [&](const std::string& s) { return s.substr(0, 5) == head; });
  };
  const auto has_number = [](const std::vector<int>& v, int n) { return std::find(v.begin(), v.end(), n) != v.end(); };
  std::vector<std::string> e = nmea_epoch(d, fix);
  // 4.10: a GSA per system with its systemId (18 fields), a GSV per talker with
  // a signalId, Galileo and BeiDou numbered within their own talkers.
  EXPECT_GE(count(e, "GNGSA"), 4) << ::testing::PrintToString(e);
  for (const std::string& s : e) {
    if (s.substr(2, 3) == "GSA") {
      EXPECT_EQ(fields_of(s).size(), 19u) << s;
    }
  }
  ASSERT_EQ(count(e, "GAGSV"), 1) << ::testing::PrintToString(e);
  EXPECT_EQ(count(e, "GBGSV"), 1);
  EXPECT_TRUE(has_number(gsv_numbers(e), 5) && has_number(gsv_numbers(e), 20) && has_number(gsv_numbers(e), 71))
      << ::testing::PrintToString(e);
  // CFG-NMEA nmeaVersion 4.0 (0x40), strict: no systemId, no signalId, and
  // Galileo and BeiDou have no NMEA 4.0 number, so they leave GSV and GSA
  // (their GSV says 0 in view).
  Host h{d};
  ASSERT_TRUE(h.acked(msg::kCfgNmea, {0x00, 0x40, 0, 0x02, 0, 0, 0, 0, 0, 0, 0, 0}));
  e = nmea_epoch(d, fix);
  for (const std::string& s : e) {
    if (s.substr(2, 3) == "GSA") {
      EXPECT_EQ(fields_of(s).size(), 18u) << s;
    }
  }
  for (const std::string& s : e) {
    if (s.substr(0, 5) == "GAGSV" || s.substr(0, 5) == "GBGSV") {
      EXPECT_EQ(fields_of(s)[3], "00") << s;  // the system is on, its satellites unnumbered
    }
  }
  std::vector<int> n = gsv_numbers(e);
  EXPECT_TRUE(has_number(n, 71) && !has_number(n, 305) && !has_number(n, 420)) << ::testing::PrintToString(n);
  // svNumbering extended (1): Galileo 301-336 and BeiDou 401-437 come back.
  ASSERT_TRUE(h.acked(msg::kCfgNmea, {0x00, 0x40, 0, 0x02, 0, 0, 0, 0, 1, 0, 0, 0}));
  n = gsv_numbers(nmea_epoch(d, fix));
  EXPECT_TRUE(has_number(n, 305) && has_number(n, 420)) << ::testing::PrintToString(n);
  // NMEA 2.3 (0x23): GSV without the 4.10 signalId (4 + 4n fields).
  ASSERT_TRUE(h.acked(msg::kCfgNmea, {0x00, 0x23, 0, 0x02, 0, 0, 0, 0, 0, 0, 0, 0}));
  e = nmea_epoch(d, fix);
  for (const std::string& s : e) {
    if (s.substr(2, 3) == "GSV") {
      EXPECT_EQ((fields_of(s).size() - 4) % 4, 0u) << s;
    }
  }
  // Back to 4.10: the signalId returns (4 + 4n + 1 fields).
  ASSERT_TRUE(h.acked(msg::kCfgNmea, {0x00, 0x41, 0, 0x02, 0, 0, 0, 0, 0, 0, 0, 0}));
  e = nmea_epoch(d, fix);
  for (const std::string& s : e) {
    if (s.substr(2, 3) == "GSV") {
      EXPECT_EQ((fields_of(s).size() - 4) % 4, 1u) << s;
    }
  }
}

}  // namespace
}  // namespace gnssemu::protocol::ubx::gnss_test

// SPDX-License-Identifier: Apache-2.0
// RXM-RAWX and RXM-SFRBX: every field at its offset and encoding (IDF9
// §5.15.3, §5.15.6; shared/reference/rtk-raw.md §1.1, §1.3), the sigId
// each generation reports, and the device sending them only from raw
// firmware, at the rates CFG-MSG and CFG-VALSET set.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/navmsg/beidou_d2.hpp"
#include "core/protocol/navmsg/galileo_inav.hpp"
#include "core/protocol/navmsg/glonass_nav.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/wire/ubx_rxm.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::split_frames;

template <class T>
T at(const std::vector<std::uint8_t>& p, std::size_t off) {
  T v;
  std::memcpy(&v, p.data() + off, sizeof v);
  return v;
}

receiver::RawEpoch sample_raw() {
  receiver::RawEpoch r;
  r.t_rx = time::GpsTime(2190, 345600.0000123);
  r.time_valid = true;
  r.leap_seconds = 18;
  r.leap_seconds_valid = true;
  receiver::RawMeasurement& g = r.meas[0];
  g.sat = SatId::gps(5);
  g.signal = SignalId::kGpsL1CA;
  g.pseudorange_m = 21234567.891;
  g.carrier_phase_cycles = 111587654.321;
  g.doppler_hz = -1234.5;
  g.cn0_dbhz = 44.6;
  g.lock_time_s = 70.0;  // saturates at 64.5 s
  g.pseudorange_sigma_m = 0.32;  // 0.01 * 2^5
  g.carrier_sigma_cycles = 0.012;  // 0.004 * 3
  g.doppler_sigma_hz = 0.016;  // 0.002 * 2^3
  g.pseudorange_valid = g.carrier_valid = g.half_cycle_resolved = true;
  receiver::RawMeasurement& k = r.meas[1];
  k.sat = SatId(GnssSystem::kGlonass, 12);
  k.signal = SignalId::kGloL1OF;
  k.glonass_channel = -1;
  k.pseudorange_m = 20000000.0;
  k.lock_time_s = 1.234;
  k.cn0_dbhz = 38.2;
  k.pseudorange_valid = true;  // carrier not (yet) locked
  receiver::RawMeasurement& c = r.meas[2];
  c.sat = SatId(GnssSystem::kBeiDou, 3);  // GEO: D2
  c.signal = SignalId::kBdsB1I;
  c.pseudorange_m = 36000000.0;
  c.carrier_phase_cycles = 187456789.25;
  c.pseudorange_valid = c.carrier_valid = true;
  c.half_cycle_resolved = c.half_cycle_subtracted = true;
  receiver::RawMeasurement& j = r.meas[3];
  j.sat = SatId(GnssSystem::kQzss, 2);
  j.signal = SignalId::kQzsL1CA;
  r.num_meas = 4;
  return r;
}

TEST(RxmRawx, HeaderAndMeasurementFields) {
  std::string out;
  const std::size_t n = rxm_rawx(sample_raw(), Generation::kM8, out);
  EXPECT_EQ(n, 8 + 16 + 4 * 32u);
  const auto frames = split_frames(out);
  ASSERT_EQ(frames.size(), 1u);  // sync, length and checksum right
  const auto& p = frames[0].payload;
  EXPECT_EQ(frames[0].id, msg::kRxmRawx);
  EXPECT_DOUBLE_EQ(at<double>(p, 0), 345600.0000123);
  EXPECT_EQ(at<std::uint16_t>(p, 8), 2190);
  EXPECT_EQ(p[10], 18);
  EXPECT_EQ(p[11], 4);
  EXPECT_EQ(p[12], 1);  // leapSec valid, no clock reset
  EXPECT_EQ(p[13], 1);  // version
  const std::size_t g = 16, k = 48, c = 80, j = 112;
  EXPECT_DOUBLE_EQ(at<double>(p, g), 21234567.891);
  EXPECT_DOUBLE_EQ(at<double>(p, g + 8), 111587654.321);
  EXPECT_FLOAT_EQ(at<float>(p, g + 16), -1234.5f);
  EXPECT_EQ(p[g + 20], 0);  // gnssId GPS
  EXPECT_EQ(p[g + 21], 5);
  EXPECT_EQ(p[g + 22], 0);
  EXPECT_EQ(p[g + 23], 0);
  EXPECT_EQ(at<std::uint16_t>(p, g + 24), kRawxMaxLocktimeMs);
  EXPECT_EQ(p[g + 26], 45);
  EXPECT_EQ(p[g + 27], 5);
  EXPECT_EQ(p[g + 28], 3);
  EXPECT_EQ(p[g + 29], 3);
  EXPECT_EQ(p[g + 30], 0x07);  // prValid, cpValid, halfCyc
  // GLONASS: gnssId 6, slot, freqId k + 7; no carrier: cpMes 0, locktime 0, cpStdev invalid.
  EXPECT_EQ(p[k + 20], 6);
  EXPECT_EQ(p[k + 21], 12);
  EXPECT_EQ(p[k + 23], 6);
  EXPECT_DOUBLE_EQ(at<double>(p, k + 8), 0.0);
  EXPECT_EQ(at<std::uint16_t>(p, k + 24), 0);
  EXPECT_EQ(p[k + 28], 15);
  EXPECT_EQ(p[k + 30], 0x01);
  // BeiDou GEO on an M8: sigId byte reserved (0); subHalfCyc; cpMes half a
  // cycle behind, as RTKLIB's decode_rxmrawx expects of u-blox (it adds 0.5).
  EXPECT_DOUBLE_EQ(at<double>(p, c + 8), 187456789.25 - 0.5);
  EXPECT_EQ(p[c + 20], 3);
  EXPECT_EQ(p[c + 22], 0);
  EXPECT_EQ(p[c + 30], 0x0F);
  // QZSS svId 1-10; nothing valid.
  EXPECT_EQ(p[j + 20], 5);
  EXPECT_EQ(p[j + 21], 2);
  EXPECT_EQ(p[j + 30], 0);
}

TEST(RxmRawx, SigIdOnTheM9FromTheSignalTable) {
  receiver::RawEpoch r = sample_raw();
  r.meas[4] = r.meas[0];
  r.meas[4].signal = SignalId::kGpsL2CL;
  r.meas[5] = r.meas[0];
  r.meas[5].sat = SatId(GnssSystem::kGalileo, 11);
  r.meas[5].signal = SignalId::kGalE5bQ;
  r.num_meas = 6;
  std::string out;
  rxm_rawx(r, Generation::kM9, out);
  const auto p = split_frames(out).at(0).payload;
  EXPECT_EQ(p[16 + 22], 0);       // GPS L1C/A
  EXPECT_EQ(p[80 + 22], 1);       // BeiDou B1I D2 (GEO)
  EXPECT_EQ(p[144 + 22], 3);      // GPS L2CL
  EXPECT_EQ(p[176 + 20], 2);      // Galileo
  EXPECT_EQ(p[176 + 22], 6);      // E5bQ
}

TEST(RxmRawx, StdevIndices) {
  EXPECT_EQ(rawx_pr_stdev(0.0), 0);
  EXPECT_EQ(rawx_pr_stdev(0.01), 0);
  EXPECT_EQ(rawx_pr_stdev(0.04), 2);
  EXPECT_EQ(rawx_pr_stdev(1e9), 15);
  EXPECT_EQ(rawx_cp_stdev(0.0, true), 1);
  EXPECT_EQ(rawx_cp_stdev(0.02, true), 5);
  EXPECT_EQ(rawx_cp_stdev(1.0, true), 14);
  EXPECT_EQ(rawx_cp_stdev(0.01, false), 15);
  EXPECT_EQ(rawx_do_stdev(0.002), 0);
  EXPECT_EQ(rawx_do_stdev(0.5), 8);
}

TEST(RxmRawx, NothingWithoutTime) {
  receiver::RawEpoch r = sample_raw();
  r.time_valid = false;
  std::string out;
  EXPECT_EQ(rxm_rawx(r, Generation::kM8, out), 0u);
  EXPECT_TRUE(out.empty());
}

TEST(RxmSfrbx, HeaderAndWords) {
  const std::uint32_t words[4] = {0x01020304, 0x05060708, 0x090A0B0C, 0x0D0E0F10};
  std::string out;
  rxm_sfrbx(SatId(GnssSystem::kGlonass, 7), 3, words, Generation::kM9, out);
  rxm_sfrbx(SatId(GnssSystem::kGalileo, 7), 0, words, Generation::kM9, out);
  rxm_sfrbx(SatId(GnssSystem::kGalileo, 7), 0, words, Generation::kM8, out);
  const auto f = split_frames(out);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].id, msg::kRxmSfrbx);
  const auto& p = f[0].payload;
  ASSERT_EQ(p.size(), 8 + 16u);
  EXPECT_EQ(p[0], 6);
  EXPECT_EQ(p[1], 7);
  EXPECT_EQ(p[3], 10);  // freqId k + 7
  EXPECT_EQ(p[4], 4);
  EXPECT_EQ(p[6], 2);  // version
  EXPECT_EQ(at<std::uint32_t>(p, 8), 0x01020304u);
  EXPECT_EQ(at<std::uint32_t>(p, 20), 0x0D0E0F10u);
  EXPECT_EQ(f[1].payload[2], 1);  // E1-B on an M9
  EXPECT_EQ(f[2].payload[2], 0);  // reserved on an M8
}

/// A device on raw firmware with nav data, RXM-RAWX and RXM-SFRBX at rate 1 via CFG-MSG.
struct RawRig {
  orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  orbit::EphemerisStore store{nav.ephemerides};
  Device d;
  explicit RawRig(bool raw_firmware) : d([&] {
    DeviceSetup s;
    s.raw_firmware = raw_firmware;
    return s;
  }()) {}
  InputResult cfg_msg(MsgId id, std::uint8_t rate) {
    const std::uint8_t p[3] = {id.cls, id.id, rate};
    std::string out;
    return d.handle_ubx({}, FrameView{msg::kCfgMsg, p}, 0.0, out);
  }
  /// The UBX frames of an epoch at GPS time t with G01..G03 tracked for 60 s.
  std::vector<test::Frame> epoch(const time::GpsTime& t) {
    raw.t_rx = t;
    raw.time_valid = true;
    raw.num_meas = 3;
    for (int i = 0; i < 3; ++i) {
      receiver::RawMeasurement& m = raw.meas[static_cast<std::size_t>(i)];
      m.sat = SatId::gps(i + 1);
      m.pseudorange_m = 2.1e7;  // 70 ms
      m.pseudorange_valid = m.carrier_valid = true;
      m.lock_time_s = 60.0;
    }
    d.on_epoch(test::sample_fix(), t - time::GpsTime(2190, 0.0), RawSource{&raw, &store, {}});
    std::string out;
    test::ubx_epoch(d, {}, out);
    return split_frames(out);
  }
  receiver::RawEpoch raw;
};

int count(const std::vector<test::Frame>& f, MsgId id) {
  int n = 0;
  for (const auto& x : f) n += x.id == id;
  return n;
}

TEST(RxmDevice, CfgMsgEnablesRawxAndSfrbxOnRawFirmware) {
  RawRig rig(true);
  EXPECT_EQ(rig.cfg_msg(msg::kRxmRawx, 1).reply, Reply::kAck);
  EXPECT_EQ(rig.cfg_msg(msg::kRxmSfrbx, 1).reply, Reply::kAck);
  // 2022-01-01 00:00 is GPS week 2190 day 6; an epoch at tow 518406.05 s
  // sees the subframe that ended at 518406 (subframe 1 of a frame).
  int sfrbx = 0, rawx = 0;
  for (int s = 0; s < 30; ++s) {
    const auto f = rig.epoch(time::GpsTime(2190, 518401.05 + s));
    rawx += count(f, msg::kRxmRawx);
    sfrbx += count(f, msg::kRxmSfrbx);
    for (const auto& x : f) {
      if (x.id != msg::kRxmSfrbx) continue;
      EXPECT_EQ(x.payload.size(), 48u);
      EXPECT_EQ(at<std::uint32_t>(x.payload, 8) >> 22 & 0xFF, 0x8Bu);
    }
  }
  EXPECT_EQ(rawx, 30);
  // 30 s = five subframe ends per satellite; of them subframes 1-3 are sent
  // (subframe 4 only on page 18, 5 never).
  EXPECT_EQ(sfrbx, 3 * 3);
}

/// SFRBX payloads rxm_sfrbx_due sends for one satellite tracked at 1 Hz over
/// [t0, t0 + seconds), 70 ms away, locked throughout.
std::vector<std::string> sfrbx_of(const orbit::EphemerisStore& store, SatId sat, int channel, const time::GpsTime& t0,
                                  int seconds, int leap_s) {
  std::vector<std::string> out;
  receiver::RawEpoch raw;
  raw.time_valid = true;
  raw.num_meas = 1;
  receiver::RawMeasurement& m = raw.meas[0];
  m.sat = sat;
  m.signal = *signal_of(sat.system, 0);
  m.glonass_channel = channel;
  m.pseudorange_m = 2.1e7;
  m.pseudorange_valid = m.carrier_valid = true;
  m.lock_time_s = 100.0;
  MessageList list;
  for (int s = 0; s < seconds; ++s) {
    raw.t_rx = t0 + s;
    list.clear();
    rxm_sfrbx_due(RawSource{&raw, &store, {nullptr, nullptr, leap_s}}, 1.0, Generation::kM9, list);
    for (const auto& msg : list.messages()) {
      const std::string_view f = list.bytes(msg);
      out.emplace_back(f.substr(6, f.size() - 8));
    }
  }
  return out;
}

TEST(RxmSfrbxDue, GlonassSendsStringsOneToFiveOfEveryFrame) {
  const orbit::NavData nav =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  const orbit::EphemerisStore store{nav.ephemerides};
  const orbit::Ephemeris* eph = nullptr;
  for (const orbit::Ephemeris& e : nav.ephemerides) {
    if (e.sat.system == GnssSystem::kGlonass && e.glo_channel < 0) {
      eph = &e;
      break;
    }
  }
  ASSERT_NE(eph, nullptr);
  // 60 s from 5 min after tb: two whole 30-s frames of the GLONASST day.
  const std::vector<std::string> p = sfrbx_of(store, eph->sat, eph->glo_channel, eph->toe + 300.0, 60, 18);
  ASSERT_EQ(p.size(), 10u);
  std::array<navmsg::GlonassString, 5> strings{};
  for (std::size_t i = 0; i < p.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(static_cast<std::uint8_t>(p[i][0]), 6);  // gnssId GLONASS
    EXPECT_EQ(static_cast<int>(p[i][1]), eph->sat.number);
    EXPECT_EQ(static_cast<int>(p[i][3]), eph->glo_channel + 7);  // freqId
    EXPECT_EQ(static_cast<int>(p[i][4]), 4);                     // numWords
    navmsg::GlonassString s{};
    for (std::size_t w = 0; w < 4; ++w) std::memcpy(&s[w], p[i].data() + 8 + 4 * w, 4);
    EXPECT_EQ(s[0] >> 27, i % 5 + 1);  // string number
    EXPECT_EQ(s[2] >> 11 & 0xFF, navmsg::glonass_hamming(s));
    strings[i % 5] = s;
    if (i % 5 == 4) {
      const auto d = navmsg::decode_glonass_strings(strings, eph->glo_channel, 18);
      ASSERT_TRUE(d.has_value());
      const orbit::Ephemeris* sel = store.select(eph->sat, eph->toe + 300.0);
      ASSERT_NE(sel, nullptr);
      EXPECT_EQ(d->eph.toe, sel->toe);
      EXPECT_NEAR(d->eph.pos_m.x, sel->pos_m.x, 0.25);
      EXPECT_NEAR(d->eph.tau_n_s, sel->tau_n_s, 1e-9);
    }
  }
}

TEST(RxmSfrbxDue, GalileoSendsWordTypesZeroToSixOnE1b) {
  const orbit::NavData nav =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  const orbit::EphemerisStore store{nav.ephemerides};
  const SatId sat(GnssSystem::kGalileo, 2);
  // 30 s from a subframe start (GST tow a multiple of 30 s).
  const time::GpsTime t0(2296, 266400.0 + 0.05);
  const std::vector<std::string> p = sfrbx_of(store, sat, 0, t0, 30, 18);
  ASSERT_EQ(p.size(), 13u);  // 15 page pairs less the two almanac words
  std::array<navmsg::InavPagePair, 7> pairs{};
  std::array<int, 7> seen{};
  for (const std::string& m : p) {
    EXPECT_EQ(static_cast<int>(m[0]), 2);  // gnssId Galileo
    EXPECT_EQ(static_cast<int>(m[1]), 2);
    EXPECT_EQ(static_cast<int>(m[2]), 1);  // sigId E1-B on the M9
    EXPECT_EQ(static_cast<int>(m[4]), 9);  // numWords
    navmsg::InavPagePair w{};
    for (std::size_t i = 0; i < 8; ++i) std::memcpy(&w[i], m.data() + 8 + 4 * i, 4);
    const auto type = static_cast<std::size_t>(w[0] >> 24 & 0x3F);  // after even/odd and page type
    ASSERT_LE(type, 6u);
    pairs[type] = w;
    ++seen[type];
  }
  for (std::size_t t = 1; t <= 6; ++t) EXPECT_EQ(seen[t], 1) << t;
  const auto d = navmsg::decode_galileo_inav(pairs);
  ASSERT_TRUE(d.has_value());
  const orbit::Ephemeris* sel = store.select(sat, t0);
  ASSERT_NE(sel, nullptr);
  EXPECT_EQ(d->eph.iode, sel->iode);
  EXPECT_EQ(d->eph.toe, sel->toe);
  EXPECT_NEAR(d->eph.sqrt_a_sqrtm, sel->sqrt_a_sqrtm, std::ldexp(1.0, -19));
}

TEST(RxmSfrbxDue, BeidouGeoSendsD2PagesOneToTenOfSubframeOne) {
  const orbit::NavData nav =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  const orbit::EphemerisStore store{nav.ephemerides};
  const orbit::Ephemeris* eph = nullptr;
  for (const orbit::Ephemeris& e : nav.ephemerides) {
    if (is_beidou_geo(e.sat)) {
      eph = &e;
      break;
    }
  }
  ASSERT_NE(eph, nullptr);
  // 60 s at 1 Hz from 10 min after toe: two 30-s page cycles, one page every
  // 3-s frame (its subframe 1 ends 0.6 s into the frame: 70 ms of flight later).
  const time::GpsTime t0 = eph->toe + 600.0 + 0.05;
  const std::vector<std::string> p = sfrbx_of(store, eph->sat, 0, t0, 60, 18);
  ASSERT_EQ(p.size(), 20u);
  std::array<navmsg::D1Subframe, navmsg::kD2Pages> pages{};
  int prev_page = 0, decoded = 0;
  for (const std::string& m : p) {
    EXPECT_EQ(static_cast<int>(m[0]), 3);  // gnssId BeiDou
    EXPECT_EQ(static_cast<int>(m[1]), eph->sat.number);
    EXPECT_EQ(static_cast<int>(m[2]), 1);   // sigId B1I D2 on the M9
    EXPECT_EQ(static_cast<int>(m[4]), 10);  // numWords
    navmsg::D1Subframe w{};
    for (std::size_t i = 0; i < 10; ++i) std::memcpy(&w[i], m.data() + 8 + 4 * i, 4);
    EXPECT_EQ(w[0] >> 12 & 7, 1u);  // FraID: subframe 1 only
    const int page = static_cast<int>(w[1] >> 14 & 0xF);
    ASSERT_TRUE(page >= 1 && page <= navmsg::kD2Pages) << page;
    if (prev_page != 0) {
      EXPECT_EQ(page, prev_page % navmsg::kD2Pages + 1);  // no page skipped
    }
    prev_page = page;
    pages[static_cast<std::size_t>(page - 1)] = w;
    if (page == navmsg::kD2Pages) {
      const auto d = navmsg::decode_beidou_d2(pages, eph->sat.number);
      ASSERT_TRUE(d.has_value());
      const orbit::Ephemeris* sel = store.select(eph->sat, t0);
      ASSERT_NE(sel, nullptr);
      EXPECT_EQ(d->eph.toe, sel->toe);
      EXPECT_EQ(d->eph.iode, sel->iode & 0x1F);
      EXPECT_NEAR(d->eph.sqrt_a_sqrtm, sel->sqrt_a_sqrtm, std::ldexp(1.0, -19));
      EXPECT_NEAR(d->eph.omega0_rad, sel->omega0_rad, std::ldexp(navmsg::kSemicircle_rad, -31));
      ++decoded;
    }
  }
  EXPECT_EQ(decoded, 2);
}

TEST(RxmDevice, StandardFirmwareStaysSilent) {
  RawRig rig(false);
  EXPECT_EQ(rig.cfg_msg(msg::kRxmRawx, 1).reply, Reply::kAck);
  EXPECT_EQ(rig.cfg_msg(msg::kRxmSfrbx, 1).reply, Reply::kAck);
  for (int s = 0; s < 8; ++s) {
    const auto f = rig.epoch(time::GpsTime(2190, 518401.05 + s));
    EXPECT_EQ(count(f, msg::kRxmRawx) + count(f, msg::kRxmSfrbx), 0);
  }
}

TEST(RxmDevice, ValsetKeysOnTheM9) {
  DeviceSetup s;
  s.mon_ver = mon_ver_of(Generation::kM9);
  s.raw_firmware = true;
  Device d(s);
  // CFG-VALSET RAM: MSGOUT-UBX_RXM_RAWX_UART1 = 1, MSGOUT-UBX_RXM_SFRBX_UART1 = 2.
  const std::uint8_t p[] = {0, 1, 0, 0, 0xA5, 0x02, 0x91, 0x20, 1, 0x32, 0x02, 0x91, 0x20, 2};
  std::string out;
  EXPECT_EQ(d.handle_ubx({}, FrameView{msg::kCfgValset, p}, 0.0, out).reply, Reply::kAck);
  EXPECT_EQ(d.message_rate({}, msg::kRxmRawx), 1);
  EXPECT_EQ(d.message_rate({}, msg::kRxmSfrbx), 2);
}


// A ZED-F9P (HPG firmware: RAWX on every F9P) as a host enables it with
// CFG-VALSET: two signals per satellite in one RXM-RAWX, the F9 sigIds of
// the signal table (IDF9 §5.15.3 table; the F9P log in multi-gnss.md §8 has
// GPS 0/3, GLONASS 0/2, Galileo 0/6, BeiDou 0), and SFRBX from the L1 band only.
TEST(RxmDevice, F9pTwoBandRawxAndSfrbxByValset) {
  const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store{nav.ephemerides};
  DeviceSetup s;
  s.mon_ver = mon_ver_of(Generation::kF9P);
  s.raw_firmware = true;
  Device d(s);
  // CFG-VALSET RAM: MSGOUT-UBX_RXM_RAWX_UART1 (0x209102A5) = 1, MSGOUT-UBX_RXM_SFRBX_UART1 (0x20910232) = 1.
  const std::uint8_t p[] = {0, 1, 0, 0, 0xA5, 0x02, 0x91, 0x20, 1, 0x32, 0x02, 0x91, 0x20, 1};
  std::string reply;
  ASSERT_EQ(d.handle_ubx({}, FrameView{msg::kCfgValset, p}, 0.0, reply).reply, Reply::kAck);

  struct Row {
    SatId sat;
    SignalId signal;
    int gnss_id, sig_id;
  };
  const Row rows[] = {
      {SatId::gps(1), SignalId::kGpsL1CA, 0, 0},
      {SatId::gps(1), SignalId::kGpsL2CL, 0, 3},
      {SatId(GnssSystem::kGlonass, 5), SignalId::kGloL1OF, 6, 0},
      {SatId(GnssSystem::kGlonass, 5), SignalId::kGloL2OF, 6, 2},
      {SatId(GnssSystem::kGalileo, 11), SignalId::kGalE1C, 2, 0},
      {SatId(GnssSystem::kGalileo, 11), SignalId::kGalE5bQ, 2, 6},
      {SatId(GnssSystem::kBeiDou, 20), SignalId::kBdsB1I, 3, 0},   // MEO: D1
      {SatId(GnssSystem::kBeiDou, 20), SignalId::kBdsB2I, 3, 2},
      {SatId(GnssSystem::kBeiDou, 3), SignalId::kBdsB2I, 3, 3},    // GEO: D2
  };
  receiver::RawEpoch raw;
  raw.time_valid = true;
  raw.leap_seconds = 18;
  raw.leap_seconds_valid = true;
  for (const Row& r : rows) {
    receiver::RawMeasurement& m = raw.meas[static_cast<std::size_t>(raw.num_meas++)];
    m.sat = r.sat;
    m.signal = r.signal;
    m.glonass_channel = r.sat.system == GnssSystem::kGlonass ? -4 : 0;
    m.pseudorange_m = 2.1e7;
    m.pseudorange_valid = m.carrier_valid = true;
    m.lock_time_s = 60.0;
  }
  int rawx = 0, sfrbx = 0;
  for (int k = 0; k < 30; ++k) {
    raw.t_rx = time::GpsTime(2190, 518401.05 + k);
    d.on_epoch(test::sample_fix(), k, RawSource{&raw, &store, {}});
    std::string out;
    test::ubx_epoch(d, {}, out);
    for (const test::Frame& f : split_frames(out)) {
      if (f.id == msg::kRxmSfrbx) {
        ++sfrbx;
        EXPECT_EQ(f.payload[0], 0);  // GPS: the only system with broadcast data in this nav file
        EXPECT_EQ(f.payload[2], 0);  // sigId L1C/A: LNAV, not the L2 pilot
        continue;
      }
      if (f.id != msg::kRxmRawx) continue;
      ++rawx;
      ASSERT_EQ(f.payload[11], std::size(rows));  // numMeas
      EXPECT_EQ(f.payload[13], 1);               // version
      for (std::size_t i = 0; i < std::size(rows); ++i) {
        const std::size_t q = 16 + 32 * i;
        EXPECT_EQ(f.payload[q + 20], rows[i].gnss_id) << i;
        EXPECT_EQ(f.payload[q + 22], rows[i].sig_id) << i;
      }
      EXPECT_EQ(f.payload[16 + 32 * 2 + 23], 3);  // GLONASS freqId k + 7
    }
  }
  EXPECT_EQ(rawx, 30);
  // G01 over 30 s: subframes 1-3 of the five that end (as on the M8 above).
  EXPECT_EQ(sfrbx, 3);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

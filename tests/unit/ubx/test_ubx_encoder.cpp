// SPDX-License-Identifier: Apache-2.0
// Encoders: every field of each message from a known Fix, with the scalings
// of UBX-13003221 (ubx.md §3), plus no-fix, non-finite and week-end cases.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::sample_fix;

template <class Wire>
Wire encode_one(std::size_t (UbxEncoder::*fn)(const receiver::Fix&, std::string&) const, const receiver::Fix& f,
                MsgId id) {
  const UbxEncoder enc;
  std::string out;
  const std::size_t n = (enc.*fn)(f, out);
  EXPECT_EQ(n, out.size());
  const auto frames = test::split_frames(out);
  EXPECT_EQ(frames.size(), 1u);
  Wire w{};
  if (frames.size() == 1) {
    EXPECT_EQ(frames[0].id, id);
    EXPECT_EQ(frames[0].payload.size(), sizeof(Wire));
    std::memcpy(&w, frames[0].payload.data(), std::min(sizeof w, frames[0].payload.size()));
  }
  return w;
}

TEST(UbxEncoder, NavPvtFieldsFromTheFix) {
  const receiver::Fix f = sample_fix();
  const auto m = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  EXPECT_EQ(m.iTOW, 561618250u);
  // GPS week 2190, TOW 561618.25 s, 18 leap seconds -> 2022-01-01 12:00:00.25 UTC.
  EXPECT_EQ(m.year, 2022);
  EXPECT_EQ(m.month, 1);
  EXPECT_EQ(m.day, 1);
  EXPECT_EQ(m.hour, 12);
  EXPECT_EQ(m.min, 0);
  EXPECT_EQ(m.sec, 0);
  EXPECT_EQ(m.nano, 250000000);
  EXPECT_EQ(m.valid, 0x07);
  EXPECT_EQ(m.tAcc, 23u);
  EXPECT_EQ(m.fixType, 3);
  EXPECT_EQ(m.flags, 0x01);
  EXPECT_EQ(m.numSV, 9);
  EXPECT_EQ(m.lat, 472852330);
  EXPECT_EQ(m.lon, 85652650);
  EXPECT_EQ(m.height, 547600);
  EXPECT_EQ(m.hMSL, 499600);  // height - geoid_sep_m (48 m)
  EXPECT_EQ(m.hAcc, 2140u);   // hypot(1.3, 1.7) m
  EXPECT_EQ(m.vAcc, 2200u);
  EXPECT_EQ(m.velN, 631);
  EXPECT_EQ(m.velE, 13385);
  EXPECT_EQ(m.velD, 420);
  EXPECT_EQ(m.gSpeed, 13400);
  EXPECT_EQ(m.headMot, 8730000);
  EXPECT_EQ(m.sAcc, 210u);
  EXPECT_EQ(m.headAcc, 89792u);  // 0.21 / 13.4 rad in deg
  EXPECT_EQ(m.pDOP, 194);
  EXPECT_EQ(m.flags3, 0);
}

TEST(UbxEncoder, HeadAccIs180DegWhenStandingAndFollowsSpeedWhenMoving) {
  // docs/ubx.md: headAcc = sAcc / gSpeed (rad -> deg), capped at 180 deg.
  // atan2 stopped at 90 deg while the doc promised 180 when standing.
  receiver::Fix f = sample_fix();
  f.speed_m_s = 0.0;
  f.vel_enu_m_s = {0.0, 0.0, 0.0};
  EXPECT_EQ(encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt).headAcc, 18000000u);
  EXPECT_EQ(encode_one<wire::NavVelned>(&UbxEncoder::nav_velned, f, msg::kNavVelned).cAcc, 18000000u);
  f.speed_m_s = 0.21;  // gSpeed = sAcc: one radian
  EXPECT_EQ(encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt).headAcc, 5729578u);
  f.speed_m_s = 0.05;  // crawling: capped
  EXPECT_EQ(encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt).headAcc, 18000000u);
}

TEST(UbxEncoder, PosllhVelnedSolAgreeWithPvt) {
  const receiver::Fix f = sample_fix();
  const auto pvt = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  const auto llh = encode_one<wire::NavPosllh>(&UbxEncoder::nav_posllh, f, msg::kNavPosllh);
  EXPECT_EQ(llh.iTOW, pvt.iTOW);
  EXPECT_EQ(llh.lat, pvt.lat);
  EXPECT_EQ(llh.lon, pvt.lon);
  EXPECT_EQ(llh.height, pvt.height);
  EXPECT_EQ(llh.hMSL, pvt.hMSL);
  EXPECT_EQ(llh.hAcc, pvt.hAcc);
  EXPECT_EQ(llh.vAcc, pvt.vAcc);
  const auto vel = encode_one<wire::NavVelned>(&UbxEncoder::nav_velned, f, msg::kNavVelned);
  EXPECT_EQ(vel.velN, 63);  // cm/s
  EXPECT_EQ(vel.velE, 1339);
  EXPECT_EQ(vel.velD, 42);
  EXPECT_EQ(vel.gSpeed, 1340u);
  EXPECT_EQ(vel.speed, static_cast<std::uint32_t>(std::lround(std::hypot(13.4, 0.42) * 100)));
  EXPECT_EQ(vel.heading, pvt.headMot);
  EXPECT_EQ(vel.sAcc, 21u);
  EXPECT_EQ(vel.cAcc, pvt.headAcc);
  const auto sol = encode_one<wire::NavSol>(&UbxEncoder::nav_sol, f, msg::kNavSol);
  EXPECT_EQ(sol.iTOW, pvt.iTOW);
  EXPECT_EQ(sol.fTOW, 0);
  EXPECT_EQ(sol.week, 2190);
  EXPECT_EQ(sol.gpsFix, 3);
  EXPECT_EQ(sol.flags, 0x0D);  // gpsFixOK, WKNSET, TOWSET
  EXPECT_EQ(sol.ecefX, static_cast<std::int32_t>(std::lround(f.pos_m.x * 100)));
  EXPECT_EQ(sol.ecefY, static_cast<std::int32_t>(std::lround(f.pos_m.y * 100)));
  EXPECT_EQ(sol.ecefZ, static_cast<std::int32_t>(std::lround(f.pos_m.z * 100)));
  EXPECT_EQ(sol.pAcc, static_cast<std::uint32_t>(std::lround(std::hypot(2.14009, 2.2) * 100)));
  EXPECT_EQ(sol.ecefVZ, static_cast<std::int32_t>(std::lround(f.vel_m_s.z * 100)));
  EXPECT_EQ(sol.pDOP, 194);
  EXPECT_EQ(sol.numSV, 9);
  // ECEF velocity magnitude equals the ENU one (rotation).
  EXPECT_NEAR(f.vel_m_s.norm(), std::hypot(13.4, 0.42), 1e-9);
}

TEST(UbxEncoder, StatusDopTime) {
  const receiver::Fix f = sample_fix();
  const UbxEncoder enc;
  std::string out;
  enc.nav_status(f, EpochInfo{12345, 3000, ItfmSettings{false}, std::nullopt}, out);
  auto fr = test::split_frames(out);
  ASSERT_EQ(fr.size(), 1u);
  wire::NavStatus st{};
  std::memcpy(&st, fr[0].payload.data(), sizeof st);
  EXPECT_EQ(st.gpsFix, 3);
  EXPECT_EQ(st.flags, 0x0D);
  EXPECT_EQ(st.ttff, 3000u);
  EXPECT_EQ(st.msss, 12345u);

  const auto dop = encode_one<wire::NavDop>(&UbxEncoder::nav_dop, f, msg::kNavDop);
  EXPECT_EQ(dop.gDOP, 210);
  EXPECT_EQ(dop.pDOP, 194);
  EXPECT_EQ(dop.tDOP, 90);
  EXPECT_EQ(dop.vDOP, 154);
  EXPECT_EQ(dop.hDOP, 118);
  EXPECT_EQ(dop.nDOP, 155);  // sigma_n / sigma_uere = 1.7 / 1.1
  EXPECT_EQ(dop.eDOP, 118);  // 1.3 / 1.1

  const auto tg = encode_one<wire::NavTimegps>(&UbxEncoder::nav_timegps, f, msg::kNavTimegps);
  EXPECT_EQ(tg.iTOW, 561618250u);
  EXPECT_EQ(tg.week, 2190);
  EXPECT_EQ(tg.leapS, 18);
  EXPECT_EQ(tg.valid, 0x07);
  const auto tu = encode_one<wire::NavTimeutc>(&UbxEncoder::nav_timeutc, f, msg::kNavTimeutc);
  EXPECT_EQ(tu.year, 2022);
  EXPECT_EQ(tu.hour, 12);
  EXPECT_EQ(tu.nano, 250000000);
  EXPECT_EQ(tu.valid, 0x37);  // validTOW, validWKN, validUTC, utcStandard 3 (USNO)
}

TEST(UbxEncoder, NavSatPerSatellite) {
  const receiver::Fix f = sample_fix();
  const UbxEncoder enc;
  std::string out;
  enc.nav_sat(f, out);
  const auto fr = test::split_frames(out);
  ASSERT_EQ(fr.size(), 1u);
  const auto& p = fr[0].payload;
  ASSERT_EQ(p.size(), 8u + 12u * 10u);
  EXPECT_EQ(p[4], 1);   // version
  EXPECT_EQ(p[5], 10);  // numSvs
  int used = 0;
  for (int i = 0; i < 10; ++i) {
    const auto& s = f.sats[static_cast<std::size_t>(i)];
    const std::size_t o = 8 + 12 * static_cast<std::size_t>(i);
    SCOPED_TRACE(s.sat.prn());
    EXPECT_EQ(p[o], 0);  // GPS
    EXPECT_EQ(p[o + 1], s.sat.prn());
    EXPECT_EQ(p[o + 2], s.tracked ? std::lround(s.cn0_dbhz) : 0);
    EXPECT_EQ(static_cast<std::int8_t>(p[o + 3]), std::lround(s.el_rad * kRadToDeg));
    EXPECT_EQ(test::u2(p, o + 4), std::lround(s.az_rad * kRadToDeg));
    const std::uint32_t flags = test::u4(p, o + 8);
    EXPECT_EQ((flags >> 3) & 1, s.used ? 1u : 0u);
    EXPECT_EQ((flags >> 4) & 3, 1u);          // healthy
    EXPECT_EQ((flags >> 8) & 7, 1u);          // orbit from ephemeris
    EXPECT_EQ((flags >> 11) & 1, 1u);         // ephAvail
    EXPECT_EQ(flags & 7, s.tracked ? 7u : 0u);  // all tracked sats here are >= 30 dB-Hz
    const auto prres = static_cast<std::int16_t>(test::u2(p, o + 6));
    EXPECT_EQ(prres, s.used ? std::lround(s.residual_m * 10) : 0);
    used += s.used;
  }
  EXPECT_EQ(used, f.num_used);
}

TEST(UbxEncoder, NavSvinfoChipGenM8AndChannels) {
  receiver::Fix f = sample_fix();
  f.sats[1].healthy = false;  // PRN 7
  f.sats[1].used = false;
  const UbxEncoder enc;
  std::string out;
  enc.nav_svinfo(f, out);
  const auto fr = test::split_frames(out);
  ASSERT_EQ(fr.size(), 1u);
  const auto& p = fr[0].payload;
  ASSERT_EQ(p.size(), 8u + 12u * 10u);
  EXPECT_EQ(p[4], 10);      // numCh
  EXPECT_EQ(p[5] & 7, 4);   // chipGen u-blox 8 (ArduPilot reads this)
  EXPECT_EQ(p[8 + 12 * 1 + 2], 0x10);  // PRN 7: unhealthy, not used
  EXPECT_EQ(p[8 + 12 * 4 + 0], 255);   // PRN 16 not tracked: no channel
  EXPECT_EQ(p[8 + 12 * 4 + 4], 0);     // and no C/N0
  EXPECT_EQ(p[8 + 12 * 0 + 2], 0x0D);  // PRN 3 used: svUsed, orbitAvail, orbitEph
  EXPECT_EQ(test::i4(p, 8 + 12 * 0 + 8), std::lround(f.sats[0].residual_m * 100));
}

TEST(UbxEncoder, EphemerisAndSmoothingFlagsFollowTheReceiver) {
  receiver::Fix f = sample_fix();
  f.sats[0].ephemeris = false;  // PRN 3: tracked, its ephemeris still downloading
  f.sats[2].smoothed = true;    // carrier-smoothed pseudorange
  const UbxEncoder enc;
  std::string sat, svinfo;
  enc.nav_sat(f, sat);
  enc.nav_svinfo(f, svinfo);
  const auto sat_frames = test::split_frames(sat), svinfo_frames = test::split_frames(svinfo);
  ASSERT_EQ(sat_frames.size(), 1u);
  ASSERT_EQ(svinfo_frames.size(), 1u);
  const auto& p = sat_frames[0].payload;
  const std::uint32_t no_eph = test::u4(p, 8 + 8), smoothed = test::u4(p, 8 + 24 + 8);
  EXPECT_EQ((no_eph >> 8) & 7, 0u);   // orbitSource: none
  EXPECT_EQ((no_eph >> 11) & 1, 0u);  // ephAvail
  EXPECT_EQ((no_eph >> 12) & 1, 1u);  // almAvail
  EXPECT_EQ((smoothed >> 7) & 1, 1u);
  EXPECT_EQ((test::u4(p, 8 + 12 + 8) >> 7) & 1, 0u);
  const auto& q = svinfo_frames[0].payload;
  EXPECT_EQ(q[8 + 2] & 0x2C, 0x24);             // orbitAvail + orbitAlm, no orbitEph
  EXPECT_EQ(q[8 + 24 + 2] & 0x80, 0x80);        // smoothed
}

TEST(UbxEncoder, DeadReckoningIsFixType1WithoutGnssFixOk) {
  receiver::Fix f = sample_fix();
  f.type = receiver::FixType::kDeadReckoning;
  const UbxEncoder enc;
  std::string pvt, status;
  enc.nav_pvt(f, pvt);
  enc.nav_status(f, EpochInfo{}, status);
  const auto pf = test::split_frames(pvt), sf = test::split_frames(status);
  ASSERT_EQ(pf.size(), 1u);
  ASSERT_EQ(sf.size(), 1u);
  EXPECT_EQ(pf[0].payload[20], 1);         // fixType: dead reckoning only
  EXPECT_EQ(pf[0].payload[21] & 1, 0);     // gnssFixOK not set
  EXPECT_NE(test::i4(pf[0].payload, 28), 0);  // the extrapolated latitude is reported
  EXPECT_EQ(sf[0].payload[4], 1);          // gpsFix
  EXPECT_EQ(sf[0].payload[5] & 1, 0);      // gpsFixOk
}

TEST(UbxEncoder, NoFixIsFlaggedNotFaked) {
  receiver::Fix f = sample_fix();
  f.type = receiver::FixType::kNone;
  const auto m = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  EXPECT_EQ(m.fixType, 0);
  EXPECT_EQ(m.flags & 1, 0);
  EXPECT_EQ(m.numSV, 0);
  EXPECT_EQ(m.lat, 0);
  EXPECT_EQ(m.lon, 0);
  EXPECT_EQ(m.hAcc, 0xFFFFFFFFu);
  EXPECT_EQ(m.pDOP, 9999);
  EXPECT_EQ(m.valid, 0x07);  // time is still known
  EXPECT_EQ(m.flags3 & 1, 1);
  const auto dop = encode_one<wire::NavDop>(&UbxEncoder::nav_dop, f, msg::kNavDop);
  EXPECT_EQ(dop.hDOP, 9999);
}

TEST(UbxEncoder, NoTimeMeansNoDateAndNoFix) {
  receiver::Fix f = sample_fix();
  f.time_valid = false;
  const auto m = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  EXPECT_EQ(m.valid, 0);
  EXPECT_EQ(m.year, 0);
  EXPECT_EQ(m.fixType, 0);
  const auto tg = encode_one<wire::NavTimegps>(&UbxEncoder::nav_timegps, f, msg::kNavTimegps);
  EXPECT_EQ(tg.valid, 0);
}

TEST(UbxEncoder, NonFiniteInputsNeverReachTheWire) {
  receiver::Fix f = sample_fix();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  f.lla.lat_rad = nan;
  const auto m = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  EXPECT_EQ(m.fixType, 0);  // a position that is not a number is no fix
  f = sample_fix();
  f.h_acc_m = nan;
  f.speed_m_s = std::numeric_limits<double>::infinity();
  f.vel_enu_m_s = Enu(nan, 1, 1);
  f.dop.pdop = nan;
  f.sats[0].cn0_dbhz = nan;
  f.sats[0].az_rad = nan;
  const auto m2 = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  EXPECT_EQ(m2.fixType, 3);
  EXPECT_EQ(m2.hAcc, 0xFFFFFFFFu);
  EXPECT_EQ(m2.pDOP, 9999);
  EXPECT_EQ(m2.velN, 0);
  EXPECT_EQ(m2.gSpeed, 0);  // speed not finite and velocity NaN: nothing to report
  std::string out;
  UbxEncoder().nav_sat(f, out);
  const auto fr = test::split_frames(out);
  ASSERT_EQ(fr.size(), 1u);
  EXPECT_EQ(fr[0].payload[8 + 2], 0);  // cno
  EXPECT_EQ(test::u2(fr[0].payload, 8 + 4), 0);
}

TEST(UbxEncoder, ItowRollsIntoTheNextWeek) {
  receiver::Fix f = sample_fix();
  f.t = time::GpsTime(2190, 604799.9996);  // rounds to 604800000 ms
  const auto m = encode_one<wire::NavSol>(&UbxEncoder::nav_sol, f, msg::kNavSol);
  EXPECT_EQ(m.iTOW, 0u);
  EXPECT_EQ(m.week, 2191);
  EXPECT_EQ(m.fTOW, -400000);  // tow - iTOW, ns
  const auto pvt = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  // 2022-01-02 00:00:00 GPS = 2022-01-01 23:59:42 UTC, with fTOW -0.4 ms.
  EXPECT_EQ(pvt.day, 1);
  EXPECT_EQ(pvt.hour, 23);
  EXPECT_EQ(pvt.min, 59);
  EXPECT_EQ(pvt.sec, 42);
  EXPECT_EQ(pvt.nano, -400000);
}

// 2D fix: NAV-DOP carries the solver's values, unavailable ones as 9999.
TEST(UbxEncoder, TwoDimensionalFixDops) {
  receiver::Fix f = sample_fix();
  f.type = receiver::FixType::k2D;
  f.dop.hdop = 1.5;
  f.dop.tdop = 0.9;
  f.dop.vdop = f.dop.pdop = f.dop.gdop = receiver::Dop::kNoDop;
  const auto dop = encode_one<wire::NavDop>(&UbxEncoder::nav_dop, f, msg::kNavDop);
  EXPECT_EQ(dop.gDOP, 9999);
  EXPECT_EQ(dop.pDOP, 9999);
  EXPECT_EQ(dop.vDOP, 9999);
  EXPECT_EQ(dop.hDOP, 150);
  EXPECT_EQ(dop.tDOP, 90);
  const auto pvt = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  EXPECT_EQ(pvt.fixType, 2);
  EXPECT_EQ(pvt.pDOP, 9999);
}

// u-blox reports sec 60 in NAV-PVT / NAV-TIMEUTC during an inserted leap
// second (UBX-13003221: sec 0..60): GPS 2017-01-01 00:00:17.5, count 17.
TEST(UbxEncoder, InsertedLeapSecondIsSecondSixty) {
  receiver::Fix f = sample_fix();
  f.t = time::GpsTime::from_calendar({2017, 1, 1, 0, 0, 17.5});
  f.leap_seconds = 17;
  f.in_leap_second = true;
  const auto pvt = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  EXPECT_EQ(pvt.year, 2016);
  EXPECT_EQ(pvt.month, 12);
  EXPECT_EQ(pvt.day, 31);
  EXPECT_EQ(pvt.hour, 23);
  EXPECT_EQ(pvt.min, 59);
  EXPECT_EQ(pvt.sec, 60);
  EXPECT_EQ(pvt.nano, 500000000);
  const auto tu = encode_one<wire::NavTimeutc>(&UbxEncoder::nav_timeutc, f, msg::kNavTimeutc);
  EXPECT_EQ(tu.day, 31);
  EXPECT_EQ(tu.hour, 23);
  EXPECT_EQ(tu.min, 59);
  EXPECT_EQ(tu.sec, 60);
  // One second later the new count applies: 2017-01-01 00:00:00.5.
  f.t = f.t + 1.0;
  f.leap_seconds = 18;
  f.in_leap_second = false;
  const auto next = encode_one<wire::NavPvt>(&UbxEncoder::nav_pvt, f, msg::kNavPvt);
  EXPECT_EQ(next.year, 2017);
  EXPECT_EQ(next.hour, 0);
  EXPECT_EQ(next.sec, 0);
  EXPECT_EQ(next.nano, 500000000);
}

TEST(UbxEncoder, MonVerIsAnM8AndConfigurable) {
  std::string out;
  UbxEncoder().mon_ver(out);
  auto fr = test::split_frames(out);
  ASSERT_EQ(fr.size(), 1u);
  ASSERT_EQ(fr[0].payload.size(), 40u + 4u * 30u);
  const char* p = reinterpret_cast<const char*>(fr[0].payload.data());
  EXPECT_STREQ(p, "ROM CORE 3.01 (107888)");
  EXPECT_STREQ(p + 30, "00080000");
  EXPECT_STREQ(p + 40, "FWVER=SPG 3.01");
  EXPECT_STREQ(p + 70, "PROTVER=18.00");
  EXPECT_STREQ(p + 100, "GPS;GLO;GAL;BDS");
  EXPECT_STREQ(p + 130, "SBAS;IMES;QZSS");

  MonVerConfig c;
  c.protocol_version = 23.01;
  c.extensions = {"GPS;GLO"};
  out.clear();
  UbxEncoder(c).mon_ver(out);
  fr = test::split_frames(out);
  ASSERT_EQ(fr[0].payload.size(), 40u + 3u * 30u);
  EXPECT_STREQ(reinterpret_cast<const char*>(fr[0].payload.data()) + 70, "PROTVER=23.01");
}

TEST(UbxEncoder, MonVerConfigValidated) {
  MonVerConfig c;
  c.protocol_version = 27.0;  // would make PX4 switch to CFG-VALSET
  EXPECT_THROW(UbxEncoder{c}, Error);
  c = {};
  c.hw_version = "M8";
  EXPECT_THROW(UbxEncoder{c}, Error);
  c = {};
  c.sw_version = std::string(30, 'x');
  EXPECT_THROW(UbxEncoder{c}, Error);
}

TEST(UbxEncoder, MonHwJammingFollowsNoiseRiseAndTheFix) {
  const auto hw = [](double rise, bool itfm, bool has_fix = true, std::uint32_t ttff_ms = 1000) {
    receiver::Fix f = sample_fix();
    f.noise_rise_db = rise;
    if (!has_fix) f.type = receiver::FixType::kNone;
    std::string out;
    UbxEncoder().mon_hw(f, EpochInfo{0, ttff_ms, ItfmSettings{itfm}, std::nullopt}, out);
    const auto fr = test::split_frames(out);
    wire::MonHw m{};
    EXPECT_EQ(fr.size(), 1u);
    EXPECT_EQ(fr[0].payload.size(), 60u);
    std::memcpy(&m, fr[0].payload.data(), sizeof m);
    return m;
  };
  const auto quiet = hw(1.0, true), jammed = hw(40.0, true), off = hw(40.0, false);
  EXPECT_LT(quiet.jamInd, 20);
  EXPECT_GT(jammed.jamInd, 200);
  EXPECT_GT(quiet.agcCnt, jammed.agcCnt);
  EXPECT_LT(quiet.noisePerMS, jammed.noisePerMS);
  EXPECT_EQ((quiet.flags >> 2) & 3, 1);                     // ok
  EXPECT_EQ((jammed.flags >> 2) & 3, 2);                    // warning: interference visible, fix OK
  EXPECT_EQ((hw(40.0, true, false).flags >> 2) & 3, 3);     // critical: interference and no fix
  EXPECT_EQ((off.flags >> 2) & 3, 0);                       // monitor disabled: unknown
  EXPECT_EQ((hw(40.0, true, true, 0).flags >> 2) & 3, 0);   // no good first fix yet: unknown
  // bbThreshold 3 dB above the quiet floor (1 dB): 3.9 dB of rise is not yet interference, 4 dB is.
  EXPECT_EQ((hw(3.9, true).flags >> 2) & 3, 1);
  EXPECT_EQ((hw(4.0, true).flags >> 2) & 3, 2);
  EXPECT_EQ(quiet.aStatus, 2);
}

TEST(UbxEncoder, EncodeDispatchCoversEveryOutputMessage) {
  const receiver::Fix f = sample_fix();
  const UbxEncoder enc;
  const MsgId ids[] = {msg::kNavPvt, msg::kNavPosllh, msg::kNavStatus, msg::kNavDop, msg::kNavSol,
                       msg::kNavVelned, msg::kNavTimegps, msg::kNavTimeutc, msg::kNavSat, msg::kNavSvinfo,
                       msg::kNavEoe, msg::kMonHw, msg::kMonVer};
  std::size_t total = 0;
  std::string out;
  for (MsgId id : ids) {
    EXPECT_TRUE(UbxEncoder::can_encode(id));
    const std::size_t n = enc.encode(id, f, {}, out);
    EXPECT_GT(n, 8u);
    total += n;
  }
  EXPECT_EQ(out.size(), total);
  EXPECT_LE(total, kMaxEpochBytes);
  EXPECT_EQ(test::split_frames(out).size(), std::size(ids));
  EXPECT_FALSE(UbxEncoder::can_encode(msg::kCfgPrt));
  EXPECT_EQ(enc.encode(msg::kCfgPrt, f, {}, out), 0u);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx

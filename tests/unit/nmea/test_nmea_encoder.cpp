// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/protocol/nmea/nmea_format.hpp"
#include "nmea_test_util.hpp"

namespace gnssemu::protocol::nmea {
namespace {

using test::parse_sentence;
using test::sample_fix_3d;
using test::Sentence;
using test::split_lines;

NmeaConfig all_sentences(NmeaVersion v) {
  NmeaConfig c;
  c.version = v;
  c.sentences.set(nmea::Sentence::kGst);
  c.sentences.set(nmea::Sentence::kZda);
  return c;
}

std::vector<std::string> encode(const receiver::Fix& f, const NmeaConfig& c) {
  std::string out;
  const std::size_t n = NmeaEncoder(c).encode_epoch(f, out);
  EXPECT_EQ(n, out.size());
  EXPECT_GE(out.size(), 2u);
  EXPECT_EQ(out.substr(out.size() - 2), "\r\n");
  auto lines = split_lines(out);
  if (!lines.empty() && lines.back().empty()) lines.pop_back();
  return lines;
}

// Framing rules every emitted sentence must keep.
void expect_well_formed(const std::vector<std::string>& lines) {
  for (const auto& l : lines) {
    SCOPED_TRACE(l);
    EXPECT_LE(l.size() + 2, kMaxSentenceLength);
    EXPECT_TRUE(nmea_checksum_ok(l));
    EXPECT_EQ(l.substr(0, 3), "$GP");
    EXPECT_EQ(l.find_first_of("\r\n"), std::string::npos);
    EXPECT_EQ(l.find("nan"), std::string::npos);
    EXPECT_EQ(l.find("inf"), std::string::npos);
    EXPECT_EQ(l.find(",-0.0"), std::string::npos);
    // Upper-case hex checksum.
    const std::string hh = l.substr(l.size() - 2);
    for (char c : hh) EXPECT_TRUE((c >= '0' && c <= '9') || (c >= 'A' && c <= 'F'));
  }
}

std::vector<std::string> types(const std::vector<std::string>& lines) {
  std::vector<std::string> t;
  for (const auto& l : lines) {
    const std::string ty = parse_sentence(l).type;
    if (t.empty() || t.back() != ty) t.push_back(ty);
  }
  return t;
}

TEST(NmeaEncoder, UbloxEpochOrder) {
  const auto lines = encode(sample_fix_3d(), all_sentences(NmeaVersion::k411));
  expect_well_formed(lines);
  EXPECT_EQ(types(lines), (std::vector<std::string>{"RMC", "VTG", "GGA", "GSA", "GSV", "GLL", "GST", "ZDA"}));
  EXPECT_EQ(lines.size(), 10u);  // 3 GSV for 10 satellites
  // Default set: no GST / ZDA.
  EXPECT_EQ(types(encode(sample_fix_3d(), NmeaConfig{})),
            (std::vector<std::string>{"RMC", "VTG", "GGA", "GSA", "GSV", "GLL"}));
}

TEST(NmeaEncoder, ThreeDimensionalFixFields) {
  const auto lines = encode(sample_fix_3d(), all_sentences(NmeaVersion::k411));
  // tow 561618.25 of week 2190 = Saturday 2022-01-01 12:00:00.25 UTC (leap 18).
  EXPECT_EQ(lines[0].substr(0, lines[0].find('*')),
            "$GPRMC,120000.25,A,4717.11398,N,00833.91590,E,26.048,87.30,010122,,,A,V");
  EXPECT_EQ(lines[1].substr(0, lines[1].find('*')), "$GPVTG,87.30,T,,M,26.048,N,48.240,K,A");
  EXPECT_EQ(lines[2].substr(0, lines[2].find('*')),
            "$GPGGA,120000.25,4717.11398,N,00833.91590,E,1,09,1.18,499.6,M,48.0,M,,");
  EXPECT_EQ(lines[3].substr(0, lines[3].find('*')), "$GPGSA,A,3,03,07,08,09,18,23,26,28,29,,,,1.94,1.18,1.54,1");
  EXPECT_EQ(lines[4].substr(0, lines[4].find('*')), "$GPGSV,3,1,10,03,12,044,31,07,29,116,41,08,09,081,36,09,56,300,45,1");
  EXPECT_EQ(lines[5].substr(0, lines[5].find('*')), "$GPGSV,3,2,10,16,03,200,,18,42,010,44,23,38,230,44,26,20,170,38,1");
  EXPECT_EQ(lines[6].substr(0, lines[6].find('*')), "$GPGSV,3,3,10,28,65,100,47,29,71,156,47,1");
  EXPECT_EQ(lines[7].substr(0, lines[7].find('*')), "$GPGLL,4717.11398,N,00833.91590,E,120000.25,A,A");
  // NEO-M9N: the 95 % ellipse of the east-north covariance (north-aligned
  // here: no correlation), 2.45 sigma_n and 2.45 sigma_e.
  EXPECT_EQ(lines[8].substr(0, lines[8].find('*')), "$GPGST,120000.25,1.8,4.2,3.2,0,1.7,1.3,2.2");
  EXPECT_EQ(lines[9].substr(0, lines[9].find('*')), "$GPZDA,120000.25,01,01,2022,00,00");
}

// GST per device: the M8 and ZED-F9P leave the ellipse empty (their logs),
// the M8 prints one decimal, the M9/F9 two below 1 m and none above 10 m.
TEST(NmeaEncoder, GstFollowsTheDevice) {
  receiver::Fix f = sample_fix_3d();
  f.sigma_n_m = 0.981;
  f.sigma_e_m = 0.5;
  f.cov_en_m2 = 0.3;  // correlation 0.61: the major axis leans east of north
  f.sigma_u_m = 12.4;
  f.range_rms_m = 0.84;
  auto gst = [&](NmeaDevice d) {
    NmeaConfig c = all_sentences(NmeaVersion::k411);
    c.device = d;
    const auto lines = encode(f, c);
    return lines[8].substr(0, lines[8].find('*'));
  };
  EXPECT_EQ(gst(NmeaDevice::kM8), "$GPGST,120000.25,0.8,,,,1.0,0.5,12.4");
  EXPECT_EQ(gst(NmeaDevice::kF9), "$GPGST,120000.25,0.84,,,,0.98,0.50,12");
  // Eigen-decomposition of [[ee, en], [en, nn]] = [[0.25, 0.3], [0.3, 0.962]]:
  // lambda = 0.6062 +- 0.4657, axes 2.4477 * sqrt(lambda) = 2.53, 0.917; the
  // major axis at 0.5 atan2(0.6, 0.712) = 20.05 deg from north.
  EXPECT_EQ(gst(NmeaDevice::kM9), "$GPGST,120000.25,0.84,2.5,0.92,20,0.98,0.50,12");
  // An anticorrelated error leans west: orientation in (90, 180).
  f.cov_en_m2 = -0.3;
  EXPECT_EQ(gst(NmeaDevice::kM9), "$GPGST,120000.25,0.84,2.5,0.92,160,0.98,0.50,12");
}

TEST(NmeaEncoder, VersionFields) {
  const receiver::Fix f = sample_fix_3d();
  const auto v23 = encode(f, all_sentences(NmeaVersion::k23));
  const auto v410 = encode(f, all_sentences(NmeaVersion::k410));
  const auto v411 = encode(f, all_sentences(NmeaVersion::k411));
  expect_well_formed(v23);
  expect_well_formed(v410);
  ASSERT_EQ(v23.size(), v410.size());
  // GPS only: 4.10 and 4.11 print the same bytes.
  EXPECT_EQ(v410, v411);
  std::map<std::string, int> extra;
  for (std::size_t i = 0; i < v23.size(); ++i) {
    const Sentence a = parse_sentence(v23[i]);
    const Sentence b = parse_sentence(v410[i]);
    ASSERT_EQ(a.type, b.type);
    const int d = static_cast<int>(b.fields.size()) - static_cast<int>(a.fields.size());
    extra[a.type] = d;
    if (d == 1) {
      // The 4.10 sentence is the 2.3 one plus one trailing field.
      EXPECT_EQ(std::vector<std::string>(b.fields.begin(), b.fields.end() - 1), a.fields);
    }
  }
  EXPECT_EQ(extra["RMC"], 1);
  EXPECT_EQ(extra["GSA"], 1);
  EXPECT_EQ(extra["GSV"], 1);
  EXPECT_EQ(extra["GGA"], 0);
  EXPECT_EQ(extra["VTG"], 0);
  EXPECT_EQ(extra["GLL"], 0);
  EXPECT_EQ(extra["GST"], 0);
  EXPECT_EQ(extra["ZDA"], 0);
  EXPECT_EQ(parse_sentence(v410[0]).fields.back(), "V");  // RMC navStatus
  EXPECT_EQ(parse_sentence(v410[3]).fields.back(), "1");  // GSA systemId GPS
  EXPECT_EQ(parse_sentence(v410[4]).fields.back(), "1");  // GSV signalId L1 C/A
  EXPECT_EQ(parse_sentence(v23[0]).fields.size(), 12u);
  EXPECT_EQ(parse_sentence(v23[3]).fields.size(), 17u);
}

TEST(NmeaEncoder, NoFixBeforeTimeIsKnown) {
  receiver::Fix f;  // time_valid false, no satellites
  NmeaConfig c = all_sentences(NmeaVersion::k23);
  auto lines = encode(f, c);
  expect_well_formed(lines);
  // Forms from shared/reference/nmea0183.md §6 (checksums verified there).
  EXPECT_EQ(lines[0], "$GPRMC,,V,,,,,,,,,,N*53");
  EXPECT_EQ(lines[1], "$GPVTG,,,,,,,,,N*30");
  EXPECT_EQ(lines[2], "$GPGGA,,,,,,0,00,99.99,,,,,,*48");
  EXPECT_EQ(lines[3], "$GPGSA,A,1,,,,,,,,,,,,,99.99,99.99,99.99*30");
  EXPECT_EQ(lines[4], "$GPGSV,1,1,00*79");
  EXPECT_EQ(lines[5], "$GPGLL,,,,,,V,N*64");
  EXPECT_EQ(parse_sentence(lines[6]).fields, (std::vector<std::string>{"", "", "", "", "", "", "", ""}));
  EXPECT_EQ(parse_sentence(lines[7]).fields, (std::vector<std::string>{"", "", "", "", "00", "00"}));
  c.version = NmeaVersion::k411;
  lines = encode(f, c);
  expect_well_formed(lines);
  EXPECT_EQ(lines[0].substr(0, lines[0].find('*')), "$GPRMC,,V,,,,,,,,,,N,V");
  EXPECT_EQ(lines[3].substr(0, lines[3].find('*')), "$GPGSA,A,1,,,,,,,,,,,,,99.99,99.99,99.99,1");
  EXPECT_EQ(lines[4].substr(0, lines[4].find('*')), "$GPGSV,1,1,00,1");
}

TEST(NmeaEncoder, NoFixWithTime) {
  receiver::Fix f = sample_fix_3d();
  f.type = receiver::FixType::kNone;
  // Stale numbers in the Fix must not leak into a no-fix epoch.
  const auto lines = encode(f, all_sentences(NmeaVersion::k23));
  expect_well_formed(lines);
  EXPECT_EQ(lines[0].substr(0, lines[0].find('*')), "$GPRMC,120000.25,V,,,,,,,010122,,,N");
  EXPECT_EQ(lines[1].substr(0, lines[1].find('*')), "$GPVTG,,,,,,,,,N");
  EXPECT_EQ(lines[2].substr(0, lines[2].find('*')), "$GPGGA,120000.25,,,,,0,00,99.99,,,,,,");
  EXPECT_EQ(lines[3].substr(0, lines[3].find('*')), "$GPGSA,A,1,,,,,,,,,,,,,99.99,99.99,99.99");
  EXPECT_EQ(parse_sentence(lines[4]).fields[2], "10");  // satellites still in view
  EXPECT_EQ(lines[7].substr(0, lines[7].find('*')), "$GPGLL,,,,,120000.25,V,N");
  EXPECT_EQ(lines[8].substr(0, lines[8].find('*')), "$GPGST,120000.25,,,,,,,");
  EXPECT_EQ(lines[9].substr(0, lines[9].find('*')), "$GPZDA,120000.25,01,01,2022,00,00");
}

TEST(NmeaEncoder, TwoDimensionalFix) {
  receiver::Fix f = sample_fix_3d();
  f.type = receiver::FixType::k2D;
  const auto lines = encode(f, all_sentences(NmeaVersion::k411));
  expect_well_formed(lines);
  const Sentence gga = parse_sentence(lines[2]);
  const Sentence gsa = parse_sentence(lines[3]);
  EXPECT_EQ(gga.fields[5], "1");  // u-blox: quality 1 for 2D and 3D
  EXPECT_EQ(gsa.fields[1], "2");  // navMode 2D
  EXPECT_EQ(parse_sentence(lines[0]).fields[1], "A");
  EXPECT_EQ(parse_sentence(lines[0]).fields[11], "A");
}

// The navigation filter coasting: u-blox's dead-reckoning flags.
TEST(NmeaEncoder, DeadReckoningFix) {
  receiver::Fix f = sample_fix_3d();
  f.type = receiver::FixType::kDeadReckoning;
  const auto lines = encode(f, all_sentences(NmeaVersion::k411));
  expect_well_formed(lines);
  const Sentence rmc = parse_sentence(lines[0]);
  EXPECT_EQ(rmc.fields[1], "A");
  EXPECT_FALSE(rmc.fields[2].empty());  // the extrapolated position
  EXPECT_EQ(rmc.fields[11], "E");       // posMode estimated
  EXPECT_EQ(parse_sentence(lines[2]).fields[5], "6");  // GGA quality: estimated (dead reckoning)
  EXPECT_EQ(parse_sentence(lines[3]).fields[1], "2");  // GSA navMode
}

// 2D fix from 3 satellites: VDOP/PDOP unavailable (99.99 as u-blox), HDOP
// from the height-constrained geometry; GGA and GSA print the same HDOP.
TEST(NmeaEncoder, TwoDimensionalFixDops) {
  receiver::Fix f = sample_fix_3d();
  f.type = receiver::FixType::k2D;
  f.dop.hdop = 1.5;
  f.dop.tdop = 0.9;
  f.dop.vdop = f.dop.pdop = f.dop.gdop = receiver::Dop::kNoDop;
  const auto lines = encode(f, all_sentences(NmeaVersion::k411));
  const Sentence gga = parse_sentence(lines[2]);
  const Sentence gsa = parse_sentence(lines[3]);
  EXPECT_EQ(gga.fields[7], "1.50");
  EXPECT_EQ(gsa.fields[14], "99.99");  // PDOP
  EXPECT_EQ(gsa.fields[15], "1.50");   // HDOP
  EXPECT_EQ(gsa.fields[16], "99.99");  // VDOP
}

// Leap second 2016-12-31 23:59:60 UTC = GPS 2017-01-01 00:00:17-18 GPST,
// leap count 17 until the step: UTC prints second 60, never 00:00:00 twice.
TEST(NmeaEncoder, InsertedLeapSecondPrintsSixty) {
  receiver::Fix f = sample_fix_3d();
  f.t = time::GpsTime::from_calendar({2017, 1, 1, 0, 0, 17.5});
  f.leap_seconds = 17;
  f.in_leap_second = true;
  const auto lines = encode(f, all_sentences(NmeaVersion::k411));
  expect_well_formed(lines);
  EXPECT_EQ(parse_sentence(lines[0]).fields[0], "235960.50");  // RMC time
  EXPECT_EQ(parse_sentence(lines[0]).fields[8], "311216");     // RMC date: the day before the step
  EXPECT_EQ(parse_sentence(lines[2]).fields[0], "235960.50");  // GGA
  EXPECT_EQ(lines[9].substr(0, lines[9].find('*')), "$GPZDA,235960.50,31,12,2016,00,00");
  // The last centisecond of the inserted second rounds to the new day.
  f.t = time::GpsTime::from_calendar({2017, 1, 1, 0, 0, 17.996});
  EXPECT_EQ(encode(f, all_sentences(NmeaVersion::k411))[9].substr(0, 33), "$GPZDA,000000.00,01,01,2017,00,00");
}

TEST(NmeaEncoder, CourseEmptyBelowThreshold) {
  receiver::Fix f = sample_fix_3d();
  f.speed_m_s = 0.3;
  auto lines = encode(f, NmeaConfig{});
  // As in the real u-blox logs: $GNVTG,,T,,M,0.029,N,0.053,K,A
  EXPECT_EQ(lines[1].substr(0, lines[1].find('*')), "$GPVTG,,T,,M,0.583,N,1.080,K,A");
  EXPECT_EQ(parse_sentence(lines[0]).fields[7], "");
  NmeaConfig c;
  c.course_min_speed_m_s = 0.0;
  lines = encode(f, c);
  EXPECT_EQ(parse_sentence(lines[0]).fields[7], "87.30");
  // 359.996 deg rounds to 0.00, never 360.00.
  f.course_rad = 359.996 * kDegToRad;
  lines = encode(f, c);
  EXPECT_EQ(parse_sentence(lines[1]).fields[0], "0.00");
  c.course_min_speed_m_s = -1.0;
  EXPECT_THROW(NmeaEncoder{c}, Error);
}

TEST(NmeaEncoder, GsaAndGgaCapAtTwelveSatellites) {
  receiver::Fix f = sample_fix_3d();
  f.num_sats = 0;
  for (int prn = 1; prn <= 14; ++prn) {
    receiver::SatInfo& s = f.sats[static_cast<std::size_t>(f.num_sats++)];
    s.sat = SatId::gps(prn);
    s.el_rad = (10.0 + 5.0 * prn) * kDegToRad;
    s.az_rad = (25.0 * prn) * kDegToRad;
    s.cn0_dbhz = 40.0;
    s.healthy = s.tracked = s.used = true;
  }
  f.num_used = 14;
  const auto lines = encode(f, all_sentences(NmeaVersion::k411));
  expect_well_formed(lines);
  EXPECT_EQ(parse_sentence(lines[2]).fields[6], "12");
  EXPECT_EQ(lines[3].substr(0, lines[3].find('*')), "$GPGSA,A,3,01,02,03,04,05,06,07,08,09,10,11,12,1.94,1.18,1.54,1");
  EXPECT_EQ(parse_sentence(lines[4]).fields[0], "4");  // 14 in view -> 4 GSV
}

TEST(NmeaEncoder, GsvSelectionAndRounding) {
  receiver::Fix f = sample_fix_3d();
  f.num_sats = 0;
  auto add = [&](int prn, double el_deg, double az_deg, double cn0, bool healthy, bool tracked) {
    receiver::SatInfo& s = f.sats[static_cast<std::size_t>(f.num_sats++)];
    s.sat = SatId::gps(prn);
    s.el_rad = el_deg * kDegToRad;
    s.az_rad = az_deg * kDegToRad;
    s.cn0_dbhz = cn0;
    s.healthy = healthy;
    s.tracked = tracked;
    s.used = tracked && healthy;
  };
  add(2, -0.5, 10.0, 0.0, true, false);   // below horizon: not in view
  add(4, 0.0, 359.6, 22.4, true, true);   // az rounds to 360 -> 000
  add(5, 89.7, 0.4, 51.5, true, true);    // el 90, cno 52
  add(6, 30.0, 100.0, 40.0, false, true); // no valid ephemeris: not listed
  add(7, 45.0, 180.0, 120.0, true, true); // cno clamped to 99
  const auto lines = encode(f, NmeaConfig{});
  expect_well_formed(lines);
  EXPECT_EQ(lines[4].substr(0, lines[4].find('*')), "$GPGSV,1,1,03,04,00,000,22,05,90,000,52,07,45,180,99,1");
  // A satellite the solution uses is always listed, so used <= in view in
  // every sentence; with no position known its el/az fields stay empty.
  f.sats[3].used = true;
  f.sats[3].el_rad = std::nan("");
  const auto used = encode(f, NmeaConfig{});
  EXPECT_EQ(used[4].substr(0, used[4].find('*')), "$GPGSV,1,1,04,04,00,000,22,05,90,000,52,06,,,40,07,45,180,99,1");
  EXPECT_EQ(parse_sentence(used[3]).fields[4], "06");
}

// Parses the epoch back and checks that every sentence tells the same story.
TEST(NmeaEncoder, SentencesAgreeWithEachOther) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    receiver::Fix f = sample_fix_3d();
    f.t = f.t + u(rng) * 86400.0 * 3.0;
    f.lla.lat_rad = (u(rng) * 180.0 - 90.0) * kDegToRad;
    f.lla.lon_rad = (u(rng) * 360.0 - 180.0) * kDegToRad;
    f.lla.height_m = u(rng) * 3000.0 - 100.0;
    f.speed_m_s = u(rng) * 60.0;
    f.course_rad = u(rng) * 2.0 * kPi;
    f.sigma_e_m = 0.5 + 5.0 * u(rng);
    f.sigma_n_m = 0.5 + 5.0 * u(rng);
    f.h_acc_m = std::hypot(f.sigma_e_m, f.sigma_n_m);
    int used = 0;
    for (int i = 0; i < f.num_sats; ++i) {
      auto& s = f.sats[static_cast<std::size_t>(i)];
      s.used = s.tracked && u(rng) < 0.8;
      used += s.used ? 1 : 0;
    }
    f.num_used = used;
    f.dop.hdop = 0.5 + 3.0 * u(rng);
    const auto lines = encode(f, all_sentences(trial % 2 ? NmeaVersion::k23 : NmeaVersion::k411));
    expect_well_formed(lines);
    std::map<std::string, std::vector<Sentence>> by;
    for (const auto& l : lines) {
      Sentence s = parse_sentence(l);
      by[s.type].push_back(s);
    }
    const auto& rmc = by["RMC"][0].fields;
    const auto& vtg = by["VTG"][0].fields;
    const auto& gga = by["GGA"][0].fields;
    const auto& gsa = by["GSA"][0].fields;
    const auto& gll = by["GLL"][0].fields;
    const auto& gst = by["GST"][0].fields;
    const auto& zda = by["ZDA"][0].fields;
    // One time everywhere.
    EXPECT_EQ(rmc[0], gga[0]);
    EXPECT_EQ(rmc[0], gll[4]);
    EXPECT_EQ(rmc[0], gst[0]);
    EXPECT_EQ(rmc[0], zda[0]);
    EXPECT_EQ(rmc[8], zda[1] + zda[2] + zda[3].substr(2));
    // One position.
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(rmc[2 + k], gga[1 + k]);
      EXPECT_EQ(rmc[2 + k], gll[k]);
    }
    const double lat = (std::stod(gga[1].substr(0, 2)) + std::stod(gga[1].substr(2)) / 60.0) * (gga[2] == "S" ? -1 : 1);
    const double lon = (std::stod(gga[3].substr(0, 3)) + std::stod(gga[3].substr(3)) / 60.0) * (gga[4] == "W" ? -1 : 1);
    EXPECT_NEAR(lat, f.lla.lat_rad * kRadToDeg, 1e-7);
    double dlon = std::remainder(lon - f.lla.lon_rad * kRadToDeg, 360.0);
    EXPECT_NEAR(dlon, 0.0, 1e-7);
    EXPECT_NEAR(std::stod(gga[8]) + std::stod(gga[10]), f.lla.height_m, 0.051 + 0.051);
    // One velocity.
    EXPECT_EQ(rmc[6], vtg[4]);
    EXPECT_EQ(rmc[7], vtg[0]);
    EXPECT_NEAR(std::stod(vtg[6]) / 3.6, std::stod(vtg[4]) * 1852.0 / 3600.0, 0.001);
    if (!rmc[7].empty()) {
      EXPECT_NEAR(std::remainder(std::stod(rmc[7]) - f.course_rad * kRadToDeg, 360.0), 0.0, 0.0051);
    }
    // Satellites used: GGA numSV = GSA PRNs = num_used (capped at 12).
    int gsa_prns = 0;
    for (int k = 2; k < 14; ++k) gsa_prns += gsa[static_cast<std::size_t>(k)].empty() ? 0 : 1;
    EXPECT_EQ(std::stoi(gga[6]), gsa_prns);
    EXPECT_EQ(gsa_prns, std::min(f.num_used, 12));
    // Every used PRN is in GSV with a C/N0.
    std::map<std::string, std::string> gsv_cno;
    int gsv_total = 0;
    for (const auto& s : by["GSV"]) {
      gsv_total = std::stoi(s.fields[2]);
      for (std::size_t k = 3; k + 3 < s.fields.size(); k += 4) gsv_cno[s.fields[k]] = s.fields[k + 3];
    }
    EXPECT_EQ(static_cast<int>(gsv_cno.size()), gsv_total);
    for (int k = 2; k < 2 + gsa_prns; ++k) {
      ASSERT_TRUE(gsv_cno.count(gsa[static_cast<std::size_t>(k)]));
      EXPECT_FALSE(gsv_cno[gsa[static_cast<std::size_t>(k)]].empty());
    }
    // One HDOP.
    EXPECT_EQ(gga[7], gsa[15]);
    // GST horizontal sigmas agree with h_acc (= sqrt(sigma_n^2 + sigma_e^2)),
    // and the ellipse's axes hold the same variance 2.4477^2 times (95 %).
    EXPECT_NEAR(std::hypot(std::stod(gst[5]), std::stod(gst[6])), f.h_acc_m, 0.071);
    EXPECT_NEAR(std::hypot(std::stod(gst[2]), std::stod(gst[3])), 2.4477 * f.h_acc_m, 0.71);  // whole metres above 10 m
    EXPECT_NEAR(std::stod(gst[7]), f.sigma_u_m, f.sigma_u_m < 10.0 ? 0.051 : 0.51);
  }
}

TEST(NmeaEncoder, ExtremeAndNonFiniteInputsStayWellFormed) {
  const double nan = std::nan("");
  const double inf = HUGE_VAL;
  const double values[] = {0.0, -0.0, 1e-12, -1e-12, 1e9, -1e9, 1e300, -1e300, nan, inf, -inf};
  const auto cfg = all_sentences(NmeaVersion::k411);
  for (double v : values) {
    receiver::Fix f = sample_fix_3d();
    f.lla.height_m = v;
    f.geoid_sep_m = v;
    f.speed_m_s = v;
    f.course_rad = v;
    f.dop.hdop = f.dop.pdop = f.dop.vdop = v;
    f.range_rms_m = f.sigma_e_m = f.sigma_n_m = f.sigma_u_m = v;
    f.sats[0].cn0_dbhz = v;
    f.sats[1].el_rad = v;
    f.sats[2].az_rad = v;
    expect_well_formed(encode(f, cfg));
    f.lla.lat_rad = v;
    f.lla.lon_rad = v;
    const auto lines = encode(f, cfg);
    expect_well_formed(lines);
    if (!std::isfinite(v)) {
      EXPECT_EQ(parse_sentence(lines[2]).fields[5], "0");  // sent as no fix
    }
  }
  receiver::Fix f = sample_fix_3d();
  f.num_sats = 1000;  // out of range count is clamped
  expect_well_formed(encode(f, cfg));
  f.num_sats = -3;
  expect_well_formed(encode(f, cfg));
}

TEST(NmeaEncoder, ThirtyTwoGpsSatellitesFitTheEpochBudget) {
  receiver::Fix f = sample_fix_3d();
  f.num_sats = 0;
  for (int prn = 1; prn <= system_size(GnssSystem::kGps); ++prn) {
    receiver::SatInfo& s = f.sats[static_cast<std::size_t>(f.num_sats++)];
    s.sat = SatId::gps(prn);
    s.el_rad = 45.0 * kDegToRad;
    s.az_rad = 3.0 * kDegToRad;
    s.cn0_dbhz = 45.0;
    s.healthy = s.tracked = s.used = true;
  }
  f.lla.lat_rad = -89.9999 * kDegToRad;
  f.lla.lon_rad = -179.9999 * kDegToRad;
  f.lla.height_m = -99999.0;
  f.geoid_sep_m = -105.0;
  f.speed_m_s = 5000.0;
  std::string out;
  const std::size_t n = NmeaEncoder(all_sentences(NmeaVersion::k411)).encode_epoch(f, out);
  EXPECT_LE(n, kMaxEpochBytes);
  const auto lines = split_lines(out);
  EXPECT_EQ(lines.size(), 7u + 8u);  // RMC VTG GGA GSA GLL GST ZDA, 8 GSV
  expect_well_formed(lines);
}

}  // namespace
}  // namespace gnssemu::protocol::nmea

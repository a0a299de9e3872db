// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/common/error.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "orbit_test_data.hpp"

using namespace gnssemu;
using namespace gnssemu::orbit;
using test::kNav;

namespace {
const std::string kBad = std::string(GNSSEMU_TEST_DATA) + "/bad/";

std::size_t prn_count(const NavData& d) {
  std::set<int> s;
  for (const auto& e : d.ephemerides) s.insert(e.sat.index());
  return s.size();
}

const Ephemeris& find(const NavData& d, int prn, int toe_week, double toe_tow) {
  for (const auto& e : d.ephemerides) {
    if (e.sat == SatId::gps(prn) && e.toe == time::GpsTime(toe_week, toe_tow)) return e;
  }
  throw std::runtime_error("set not found");
}

// First 8 lines of brdc0010.22n with the record year changed by the caller.
const char* kV2Header =
    "     2.11           N: GPS NAV DATA                         RINEX VERSION / TYPE\n"
    "                                                            END OF HEADER\n";
}  // namespace

TEST(RinexNav, RecordAndPrnCounts) {
  for (auto [f, n, p, sk] : {std::tuple{"brdc0010.22n", 422, 32, 0}, {"ab422100.18n", 206, 31, 0},
                            {"NYA100NOR_S_20241240000_01D_GN.rnx", 215, 31, 0},
                            {"ELKO00USA_R_20182100000_01D_MN.rnx", 225 + 494 + 1293 + 106, 32 + 24 + 20 + 13, 0}}) {
    const NavData d = read_rinex_nav(kNav + f);
    EXPECT_EQ(d.ephemerides.size(), static_cast<std::size_t>(n)) << f;
    EXPECT_EQ(prn_count(d), static_cast<std::size_t>(p)) << f;
    EXPECT_EQ(d.skipped_records, sk) << f;
    EXPECT_EQ(d.source, kNav + f);
  }
}

TEST(RinexNav, HeaderRinex2) {
  const NavData d = read_rinex_nav(kNav + "brdc0010.22n");
  EXPECT_DOUBLE_EQ(d.rinex_version, 2.0);
  ASSERT_TRUE(d.klobuchar.valid);
  EXPECT_DOUBLE_EQ(d.klobuchar.alpha[0], 0.1211e-07);
  EXPECT_DOUBLE_EQ(d.klobuchar.alpha[1], -0.7451e-08);
  EXPECT_DOUBLE_EQ(d.klobuchar.alpha[2], -0.5960e-07);
  EXPECT_DOUBLE_EQ(d.klobuchar.alpha[3], 0.1192e-06);
  EXPECT_DOUBLE_EQ(d.klobuchar.beta[0], 0.1167e+06);
  EXPECT_DOUBLE_EQ(d.klobuchar.beta[1], -0.2458e+06);
  EXPECT_DOUBLE_EQ(d.klobuchar.beta[2], -0.6554e+05);
  EXPECT_DOUBLE_EQ(d.klobuchar.beta[3], 0.1114e+07);
  ASSERT_TRUE(d.utc.valid);
  EXPECT_DOUBLE_EQ(d.utc.a0_s, 0.279396772385e-08);
  EXPECT_DOUBLE_EQ(d.utc.a1_s_s, 0.799360577730e-14);
  EXPECT_DOUBLE_EQ(d.utc.tot_s, 147456.0);
  EXPECT_EQ(d.utc.wnt, 2191);
  ASSERT_TRUE(d.leap_seconds.has_value());
  EXPECT_EQ(*d.leap_seconds, 18);

  const NavData ab = read_rinex_nav(kNav + "ab422100.18n");
  EXPECT_DOUBLE_EQ(ab.rinex_version, 2.11);
  EXPECT_TRUE(ab.klobuchar.valid);
  EXPECT_DOUBLE_EQ(ab.klobuchar.alpha[0], 4.6566e-09);
  EXPECT_DOUBLE_EQ(ab.klobuchar.beta[3], -3.9322e+05);
  EXPECT_EQ(ab.utc.wnt, 2012);
  EXPECT_FALSE(ab.leap_seconds.has_value());  // no LEAP SECONDS line in this file
}

TEST(RinexNav, HeaderRinex3) {
  const NavData d = read_rinex_nav(kNav + "NYA100NOR_S_20241240000_01D_GN.rnx");
  EXPECT_DOUBLE_EQ(d.rinex_version, 3.05);
  ASSERT_TRUE(d.klobuchar.valid);
  EXPECT_DOUBLE_EQ(d.klobuchar.alpha[0], 1.9558e-08);
  EXPECT_DOUBLE_EQ(d.klobuchar.alpha[3], -1.1921e-07);
  EXPECT_DOUBLE_EQ(d.klobuchar.beta[0], 1.2083e+05);
  EXPECT_DOUBLE_EQ(d.klobuchar.beta[3], -6.5536e+04);
  ASSERT_TRUE(d.utc.valid);
  EXPECT_DOUBLE_EQ(d.utc.a0_s, 9.3132257462e-10);
  EXPECT_DOUBLE_EQ(d.utc.a1_s_s, 5.329070518e-15);
  EXPECT_DOUBLE_EQ(d.utc.tot_s, 61440.0);
  EXPECT_EQ(d.utc.wnt, 2313);
  EXPECT_EQ(d.leap_seconds.value_or(-1), 18);

  // Mixed file: GAL iono and GAUT/GPGA lines must not overwrite the GPS values.
  const NavData m = read_rinex_nav(kNav + "ELKO00USA_R_20182100000_01D_MN.rnx");
  EXPECT_DOUBLE_EQ(m.rinex_version, 3.03);
  EXPECT_DOUBLE_EQ(m.klobuchar.alpha[1], 1.4901e-08);
  EXPECT_DOUBLE_EQ(m.klobuchar.beta[0], 7.7824e+04);
  EXPECT_DOUBLE_EQ(m.utc.a0_s, -7.5669959188e-10);
  EXPECT_DOUBLE_EQ(m.utc.a1_s_s, 0.0);
  EXPECT_DOUBLE_EQ(m.utc.tot_s, 11696.0);
  EXPECT_EQ(m.utc.wnt, 2012);
  EXPECT_EQ(m.leap_seconds.value_or(-1), 18);
}

// brdc0010.22n lines 9-16, PRN 1, digit for digit.
TEST(RinexNav, KnownRecordRinex2) {
  const NavData d = read_rinex_nav(kNav + "brdc0010.22n");
  const Ephemeris& e = d.ephemerides.front();
  EXPECT_EQ(int(e.sat.number), 1);
  EXPECT_EQ(e.toc, time::GpsTime(2190, 518400.0));  // 2022-01-01 00:00:00 GPST (Saturday)
  EXPECT_DOUBLE_EQ(e.af0_s, 0.469126738608e-03);
  EXPECT_DOUBLE_EQ(e.af1_s_s, -0.100044417195e-10);
  EXPECT_DOUBLE_EQ(e.af2_s_s2, 0.0);
  EXPECT_EQ(e.iode, 39);
  EXPECT_DOUBLE_EQ(e.crs_m, -0.141125000000e+03);
  EXPECT_DOUBLE_EQ(e.delta_n_rad_s, 0.398838041777e-08);
  EXPECT_DOUBLE_EQ(e.m0_rad, -0.624294238235e+00);
  EXPECT_DOUBLE_EQ(e.cuc_rad, -0.736303627491e-05);
  EXPECT_DOUBLE_EQ(e.e, 0.112181392033e-01);
  EXPECT_DOUBLE_EQ(e.cus_rad, 0.469572842121e-05);
  EXPECT_DOUBLE_EQ(e.sqrt_a_sqrtm, 0.515367499542e+04);
  EXPECT_EQ(e.toe, time::GpsTime(2190, 518400.0));
  EXPECT_DOUBLE_EQ(e.cic_rad, -0.316649675369e-07);
  EXPECT_DOUBLE_EQ(e.omega0_rad, -0.103661124009e+01);
  EXPECT_DOUBLE_EQ(e.cis_rad, 0.195577740669e-06);
  EXPECT_DOUBLE_EQ(e.i0_rad, 0.986418769490e+00);
  EXPECT_DOUBLE_EQ(e.crc_m, 0.299750000000e+03);
  EXPECT_DOUBLE_EQ(e.omega_rad, 0.884087601569e+00);
  EXPECT_DOUBLE_EQ(e.omega_dot_rad_s, -0.813355308085e-08);
  EXPECT_DOUBLE_EQ(e.idot_rad_s, -0.377872882780e-09);
  EXPECT_DOUBLE_EQ(e.sv_accuracy_m, 2.0);
  EXPECT_EQ(e.health, 0);
  EXPECT_DOUBLE_EQ(e.tgd_s, 0.512227416039e-08);
  EXPECT_EQ(e.iodc, 39);
  EXPECT_TRUE(e.transmit_known);
  EXPECT_DOUBLE_EQ(e.transmit_tow_s, 511218.0);
  EXPECT_DOUBLE_EQ(e.fit_interval_h, 4.0);
}

TEST(RinexNav, KnownRecordRinex3) {
  const NavData d = read_rinex_nav(kNav + "NYA100NOR_S_20241240000_01D_GN.rnx");
  const Ephemeris& e = d.ephemerides.front();  // G27 2024 05 03 02 00 00
  EXPECT_EQ(int(e.sat.number), 27);
  EXPECT_EQ(e.toc, time::GpsTime(2312, 5 * 86400.0 + 7200.0));
  EXPECT_DOUBLE_EQ(e.af0_s, -2.202996984124e-05);
  EXPECT_DOUBLE_EQ(e.af1_s_s, -2.046363078989e-12);
  EXPECT_EQ(e.iode, 42);
  EXPECT_DOUBLE_EQ(e.sqrt_a_sqrtm, 5.153678092957e+03);
  EXPECT_EQ(e.toe, time::GpsTime(2312, 4.392e5));
  EXPECT_DOUBLE_EQ(e.omega_dot_rad_s, -8.204627469952e-09);
  EXPECT_DOUBLE_EQ(e.tgd_s, 1.862645149231e-09);
  EXPECT_DOUBLE_EQ(e.transmit_tow_s, 4.320180000000e+05);
  EXPECT_DOUBLE_EQ(e.fit_interval_h, 4.0);  // short last line: 2 of 4 fields
}

// RINEX 3.05 Table A11: GLONASS records have 5 lines (3.04: 4). A synthetic
// mixed file R01 (5 lines), G27 (NYA1 lines 8-15), R02 (5 lines, at the end).
TEST(RinexNav, Rinex305GlonassFiveLineRecords) {
  const NavData d = read_rinex_nav(kNav + "SYNT00XXX_R_20241240000_01H_MN_v305.rnx");
  EXPECT_DOUBLE_EQ(d.rinex_version, 3.05);
  EXPECT_EQ(d.skipped_records, 0);
  ASSERT_EQ(d.ephemerides.size(), 3u);
  EXPECT_EQ(d.ephemerides[0].sat, SatId(GnssSystem::kGlonass, 1));
  EXPECT_EQ(d.ephemerides[2].sat, SatId(GnssSystem::kGlonass, 2));
  EXPECT_EQ(d.ephemerides[2].glo_channel, -4);
  const Ephemeris& e = d.ephemerides[1];
  EXPECT_EQ(int(e.sat.number), 27);
  EXPECT_EQ(e.toc, time::GpsTime(2312, 5 * 86400.0 + 7200.0));
  EXPECT_DOUBLE_EQ(e.af0_s, -2.202996984124e-05);
  EXPECT_EQ(e.iode, 42);
  EXPECT_DOUBLE_EQ(e.sqrt_a_sqrtm, 5.153678092957e+03);
  EXPECT_EQ(e.toe, time::GpsTime(2312, 4.392e5));
  EXPECT_DOUBLE_EQ(e.tgd_s, 1.862645149231e-09);
  EXPECT_EQ(e.iodc, 42);
  EXPECT_DOUBLE_EQ(e.transmit_tow_s, 4.320180000000e+05);
  EXPECT_DOUBLE_EQ(e.fit_interval_h, 4.0);
}

// The same 5-line GLONASS record in a 3.04 file is a record of 4 lines plus
// a stray continuation line: rejected, not misread.
TEST(RinexNav, Rinex304GlonassIsFourLines) {
  std::ifstream f(kNav + "SYNT00XXX_R_20241240000_01H_MN_v305.rnx");
  std::stringstream ss;
  ss << f.rdbuf();
  std::string text = ss.str();
  text.replace(0, 9, "     3.04");
  std::istringstream in(text);
  try {
    (void)read_rinex_nav(in, "mem304.rnx");
    FAIL() << "5-line GLONASS record accepted in RINEX 3.04";
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), 9) << e.what();
  }
}

// ELKO G02 second record: toe 0 of week 2012, transmitted 7182 s before the
// week started (negative transmission time, RINEX 3.04 Table A6 note).
TEST(RinexNav, NegativeTransmissionTimeAcrossWeek) {
  const NavData d = read_rinex_nav(kNav + "ELKO00USA_R_20182100000_01D_MN.rnx");
  const Ephemeris& e = find(d, 2, 2012, 0.0);
  EXPECT_EQ(e.toc, time::GpsTime(2012, 0.0));
  EXPECT_EQ(e.iode, 53);
  EXPECT_TRUE(e.transmit_known);
  EXPECT_DOUBLE_EQ(e.transmit_tow_s, -7182.0);
  const Ephemeris& before = find(d, 2, 2011, 597600.0);  // previous week's last set
  EXPECT_EQ(before.iode, 52);
}

TEST(RinexNav, TwoDigitYearsAndUnknownTransmitTime) {
  // A brdc record moved to 1999 (yy = 99 -> 1999) with week 1009, and the
  // transmission time set to 0.9999e9 (unknown); the last line is short and
  // a field is blank.
  const std::string text = std::string(kV2Header) +
                           " 1 99  5 15  2  0  0.0 0.469126738608D-03-0.100044417195D-10\n"
                           "    0.390000000000D+02-0.141125000000D+03 0.398838041777D-08-0.624294238235D+00\n"
                           "   -0.736303627491D-05 0.112181392033D-01 0.469572842121D-05 0.515367499542D+04\n"
                           "    0.526080000000D+06-0.316649675369D-07-0.103661124009D+01 0.195577740669D-06\n"
                           "    0.986418769490D+00 0.299750000000D+03 0.884087601569D+00-0.813355308085D-08\n"
                           "   -0.377872882780D-09 0.100000000000D+01 0.100900000000D+04\n"
                           "    0.200000000000D+01                    0.512227416039D-08 0.390000000000D+02\n"
                           "    0.999900000000D+09\n"
                           "\n";
  std::istringstream in(text);
  const NavData d = read_rinex_nav(in, "mem.99n");
  ASSERT_EQ(d.ephemerides.size(), 1u);
  const Ephemeris& e = d.ephemerides[0];
  const time::CalendarTime c = e.toc.to_calendar();
  EXPECT_EQ(c.year, 1999);
  EXPECT_EQ(c.month, 5);
  EXPECT_EQ(c.day, 15);
  EXPECT_EQ(e.toc, time::GpsTime(1009, 6 * 86400.0 + 7200.0));
  EXPECT_EQ(e.toe, time::GpsTime(1009, 526080.0));
  EXPECT_DOUBLE_EQ(e.af2_s_s2, 0.0);  // missing field on the epoch line
  EXPECT_EQ(e.health, 0);              // blank field
  EXPECT_FALSE(e.transmit_known);
  EXPECT_DOUBLE_EQ(e.transmit_tow_s, 0.0);
  EXPECT_DOUBLE_EQ(e.fit_interval_h, 0.0);
}

TEST(RinexNav, WeekOfTransmissionIsMovedToToe) {
  // toe 518400 (Saturday) given with the next week's number: the reader keeps
  // toe within half a week of toc.
  const std::string text = std::string(kV2Header) +
                           " 1 22  1  1  0  0  0.0 0.469126738608D-03-0.100044417195D-10 0.000000000000D+00\n"
                           "    0.390000000000D+02-0.141125000000D+03 0.398838041777D-08-0.624294238235D+00\n"
                           "   -0.736303627491D-05 0.112181392033D-01 0.469572842121D-05 0.515367499542D+04\n"
                           "    0.518400000000D+06-0.316649675369D-07-0.103661124009D+01 0.195577740669D-06\n"
                           "    0.986418769490D+00 0.299750000000D+03 0.884087601569D+00-0.813355308085D-08\n"
                           "   -0.377872882780D-09 0.100000000000D+01 0.219100000000D+04 0.000000000000D+00\n"
                           "    0.200000000000D+01 0.000000000000D+00 0.512227416039D-08 0.390000000000D+02\n"
                           "    0.100000000000D+03 0.400000000000D+01\n";
  std::istringstream in(text);
  const NavData d = read_rinex_nav(in, "mem.22n");
  ASSERT_EQ(d.ephemerides.size(), 1u);
  EXPECT_EQ(d.ephemerides[0].toe, time::GpsTime(2190, 518400.0));
  // Transmission time stays tied to the file's week: 100 s into week 2191.
  EXPECT_DOUBLE_EQ(d.ephemerides[0].transmit_tow_s, 604900.0);
}

// brdc0010.22n PRN 1 (toc 2022-01-01 00:00, toe 2190/518400) with the BO-5
// week given as `week_field`.
std::string brdc_prn1_with_week(const char* week_field) {
  return std::string(kV2Header) +
         " 1 22  1  1  0  0  0.0 0.469126738608D-03-0.100044417195D-10 0.000000000000D+00\n"
         "    0.390000000000D+02-0.141125000000D+03 0.398838041777D-08-0.624294238235D+00\n"
         "   -0.736303627491D-05 0.112181392033D-01 0.469572842121D-05 0.515367499542D+04\n"
         "    0.518400000000D+06-0.316649675369D-07-0.103661124009D+01 0.195577740669D-06\n"
         "    0.986418769490D+00 0.299750000000D+03 0.884087601569D+00-0.813355308085D-08\n"
         "   -0.377872882780D-09 0.100000000000D+01 " + std::string(week_field) + " 0.000000000000D+00\n"
         "    0.200000000000D+01 0.000000000000D+00 0.512227416039D-08 0.390000000000D+02\n"
         "    0.511218000000D+06 0.400000000000D+01\n";
}

// A 10-bit week (2190 mod 1024 = 142): toc's full date decides toe's week.
TEST(RinexNav, TenBitWeekResolvedFromToc) {
  std::istringstream in(brdc_prn1_with_week("0.142000000000D+03"));
  const NavData d = read_rinex_nav(in, "mem.22n");
  ASSERT_EQ(d.ephemerides.size(), 1u);
  EXPECT_EQ(d.ephemerides[0].toe, time::GpsTime(2190, 518400.0));
  EXPECT_DOUBLE_EQ(d.ephemerides[0].transmit_tow_s, 511218.0);
  // One rollover (2190 - 1024) and transmission week + 1 mod 1024 are fine too.
  for (const char* w : {"0.116600000000D+04", "0.143000000000D+03"}) {
    std::istringstream in2(brdc_prn1_with_week(w));
    EXPECT_EQ(read_rinex_nav(in2, "mem.22n").ephemerides.at(0).toe, time::GpsTime(2190, 518400.0)) << w;
  }
}

// A week that is neither toc's (+-1) nor that mod 1024 is a corrupt record.
TEST(RinexNav, WrongWeekIsAnError) {
  std::istringstream in(brdc_prn1_with_week("0.200000000000D+04"));
  try {
    (void)read_rinex_nav(in, "mem.22n");
    FAIL() << "week 2000 with toc in week 2190 accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), 8) << e.what();  // BROADCAST ORBIT 5
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("mem.22n:8: ", 0), 0u) << msg;
    EXPECT_NE(msg.find("GPS week 2000 does not match toc"), std::string::npos) << msg;
  }
}

// Fuzz finding (tests/fuzz/regressions/rinex_nav): a Cus of 8.4e306 rad
// gave an infinite satellite velocity. Each field is held to what the
// broadcast message carries (IS-GPS-200 Table 20-III); the limits themselves
// pass.
TEST(RinexNav, ValuesTheBroadcastCannotCarryAreErrors) {
  const std::string good = brdc_prn1_with_week("0.219000000000D+04");
  struct Edit {
    const char* from;  // a field of PRN 1's record
    const char* to;
    int line;
    const char* reason;
  };
  for (const Edit& c : {Edit{" 0.469572842121D-05", " 0.84000000000D+307", 5, "Cus (rad)"},
                        Edit{" 0.469572842121D-05", "-0.610351562600D-04", 5, "Cus (rad)"},
                        Edit{" 0.000000000000D+00\n    0.390", " 0.600000000000D-01\n    0.390", 3, "af2"},
                        Edit{"-0.141125000000D+03", "-0.102500000000D+04", 4, "Crs (m)"},
                        Edit{"-0.813355308085D-08", "-0.813355308085D-04", 7, "OMEGA DOT"},
                        Edit{" 0.884087601569D+00", " 0.700000000000D+01", 7, "omega (rad)"}}) {
    std::string text = good;
    const std::size_t at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, std::string(c.from).size(), c.to);
    std::istringstream in(text);
    try {
      (void)read_rinex_nav(in, "mem.22n");
      FAIL() << c.to << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.line(), c.line) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.reason), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("IS-GPS-200 Table 20-III"), std::string::npos) << e.what();
    }
  }
  // The extremes a message can hold: Cus -2^15 * 2^-29 rad, af2 -2^7 * 2^-55 s/s^2.
  std::string edge = good;
  edge.replace(edge.find(" 0.469572842121D-05"), 19, "-0.610351562500D-04");
  edge.replace(edge.find(" 0.000000000000D+00\n    0.390"), 19, "-0.355271367880D-14");
  std::istringstream in(edge);
  EXPECT_EQ(read_rinex_nav(in, "mem.22n").ephemerides.size(), 1u);
}

struct BadCase {
  const char* file;
  int line;
  const char* reason;  // a fragment of the message
};

class RinexNavBad : public ::testing::TestWithParam<BadCase> {};

TEST_P(RinexNavBad, ErrorNamesFileAndLine) {
  const BadCase c = GetParam();
  const std::string path = kBad + c.file;
  try {
    (void)read_rinex_nav(path);
    FAIL() << "no error for " << c.file;
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), c.line) << e.what();
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ":" + std::to_string(c.line) + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(c.reason), std::string::npos) << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Files, RinexNavBad,
    ::testing::Values(BadCase{"v2_missing_end_of_header.n", 23, "END OF HEADER"},
                      BadCase{"v4_version.rnx", 1, "unsupported RINEX version 4.00"},
                      BadCase{"v3_obs_type.rnx", 1, "not a navigation file"},
                      BadCase{"v3_galileo_only.rnx", 8, "record of system 'G' in a navigation file for system 'E'"},
                      BadCase{"v3_glonass_channel.rnx", 10, "GLONASS frequency number 9 out of range -7..+6"},
                      BadCase{"v2_glonass_channel.g", 6, "GLONASS frequency number -8 out of range"},
                      BadCase{"v3_galileo_both_clock_bits.rnx", 9, "bits 8 (E5a clock) and 9 (E5b clock) exclude"},
                      BadCase{"v3_sbas_number.rnx", 8, "SBAS satellite number 99 out of range 20..58"},
                      BadCase{"v3_beidou_week.rnx", 9, "BeiDou week 2297 does not match toc"},
                      BadCase{"v2_truncated_eof.n", 17, "truncated record"},
                      BadCase{"v3_truncated_next_record.rnx", 14, "truncated record"},
                      BadCase{"v2_bad_number.n", 10, "unparsable number '-0.1411x5000000D+03'"},
                      BadCase{"v2_sqrta_negative.n", 11, "sqrt(A)"},
                      BadCase{"v3_eccentricity_one.rnx", 10, "eccentricity"},
                      BadCase{"v2_nan.n", 13, "non-finite"},
                      BadCase{"v3_unknown_system.rnx", 16, "unknown satellite system 'X'"},
                      BadCase{"v2_bad_epoch.n", 17, "invalid epoch"},
                      BadCase{"v2_bad_week.n", 22, "invalid GPS week"},
                      BadCase{"empty.n", 1, "empty file"}),
    [](const ::testing::TestParamInfo<BadCase>& p) {
      std::string n = p.param.file;
      for (char& ch : n) {
        if (ch == '.') ch = '_';
      }
      return n;
    });

TEST(RinexNav, MissingFile) {
  try {
    (void)read_rinex_nav(kBad + "does_not_exist.n");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find("does_not_exist.n: cannot open"), std::string::npos) << e.what();
  }
}

namespace {

std::string temp_gz(const std::string& name, const std::string& head, std::size_t newlines) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("gnssemu-nav-" + std::to_string(::getpid()) + "-" + name)).string();
  gzFile f = gzopen(path.c_str(), "wb9");
  gzwrite(f, head.data(), static_cast<unsigned>(head.size()));
  const std::string chunk(1u << 20, '\n');
  for (std::size_t left = newlines; left > 0;) {
    const std::size_t n = std::min(left, chunk.size());
    gzwrite(f, chunk.data(), static_cast<unsigned>(n));
    left -= n;
  }
  gzclose(f);
  return path;
}

long peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;  // Linux: kB
}

}  // namespace

// Issue 13: a ~20 kB gzip of 20 M newlines was read and split whole before
// its first line was looked at (1.3 GB RSS, then std::bad_alloc). Now the
// first line is refused at once, and blank lines are streamed, never kept.
TEST(RinexNav, GzipOfNewlinesIsRefusedAtTheFirstLine) {
  const std::string bomb = temp_gz("bomb.rnx.gz", "", 20u << 20);
  EXPECT_LT(std::filesystem::file_size(bomb), 64u << 10);
  try {
    (void)read_rinex_nav(bomb);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), bomb + ":1: first line is not 'RINEX VERSION / TYPE'");
  }
  // A valid header followed by the newlines: read through, nothing kept.
  const std::string padded = temp_gz("padded.rnx.gz", kV2Header, 20u << 20);
  const NavData d = read_rinex_nav(padded);
  EXPECT_TRUE(d.ephemerides.empty());
  EXPECT_LT(peak_rss_mb(), 200);
  std::filesystem::remove(bomb);
  std::filesystem::remove(padded);
}

TEST(RinexNav, GzipFileReadsAsThePlainOne) {
  std::ifstream in(kNav + "brdc0010.22n", std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const std::string gz = temp_gz("brdc0010.22n.gz", text.str(), 0);
  const NavData a = read_rinex_nav(kNav + "brdc0010.22n"), b = read_rinex_nav(gz);
  ASSERT_EQ(a.ephemerides.size(), b.ephemerides.size());
  for (std::size_t i = 0; i < a.ephemerides.size(); ++i) {
    EXPECT_EQ(a.ephemerides[i].toe, b.ephemerides[i].toe);
    EXPECT_EQ(a.ephemerides[i].m0_rad, b.ephemerides[i].m0_rad);
  }
  EXPECT_EQ(a.leap_seconds, b.leap_seconds);
  std::filesystem::remove(gz);
}

TEST(RinexNav, OverlongLineIsRefused) {
  std::istringstream in(std::string(kV2Header) + std::string(5000, '1') + "\n");
  try {
    (void)read_rinex_nav(in, "long.n");
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "long.n:3: line longer than 1024 bytes: not a file of this kind");
  }
}

TEST(RinexNav, FilesAreMergedAndAnEmptyOrMissingOneIsNamed) {
  const NavData one = read_rinex_nav(kNav + "brdc0010.22n");
  const NavData twice = read_rinex_nav_files({kNav + "brdc0010.22n", kNav + "brdc0010.22n"});
  EXPECT_EQ(twice.ephemerides.size(), 2 * one.ephemerides.size());  // the store keeps a repeated set once
  EXPECT_NE(twice.source.find(" + "), std::string::npos) << twice.source;
  const std::string empty =
      (std::filesystem::temp_directory_path() / ("gnssemu-nav-empty-" + std::to_string(::getpid()) + ".22n")).string();
  std::ofstream(empty) << kV2Header;
  for (const auto& [path, why] : {std::pair{empty, "no ephemerides"}, {kNav + "missing.22n", "not found"}}) {
    try {
      (void)read_rinex_nav_files({kNav + "brdc0010.22n", path});
      ADD_FAILURE() << path;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path + ": "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove(empty);
}

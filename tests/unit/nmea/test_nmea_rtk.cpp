// SPDX-License-Identifier: Apache-2.0
// GGA and RMC of differential and RTK solutions as a u-blox F9 prints them:
// quality 2/5/4 with posMode D/F/R, the correction age with one decimal and
// the reference station (the real F9K log: "...,4,12,0.76,4.2,M,-30.0,M,0.0,2000").
#include <gtest/gtest.h>

#include <string>

#include "core/protocol/nmea/nmea_encoder.hpp"
#include "nmea_test_util.hpp"

namespace gnssemu::protocol::nmea {
namespace rtk_test {

test::Sentence first(const receiver::Fix& f, const std::string& type) {
  NmeaConfig c;
  c.device = NmeaDevice::kM9;
  std::string out;
  NmeaEncoder(c).encode_epoch(f, out);
  for (const std::string& line : test::split_lines(out)) {
    test::Sentence s = test::parse_sentence(line);
    if (s.type == type) return s;
  }
  ADD_FAILURE() << "no " << type;
  return {};
}

TEST(NmeaRtk, GgaQualityAgeAndStation) {
  receiver::Fix f = test::sample_fix_3d();
  auto gga = first(f, "GGA");
  ASSERT_EQ(gga.fields.size(), 14u);
  EXPECT_EQ(gga.fields[5], "1");
  EXPECT_EQ(gga.fields[12], "");
  EXPECT_EQ(gga.fields[13], "");
  f.diff_soln = true;
  f.corr_age_s = 1.04;
  f.ref_station_id = 2000;
  gga = first(f, "GGA");
  EXPECT_EQ(gga.fields[5], "2");
  EXPECT_EQ(gga.fields[12], "1.0");
  EXPECT_EQ(gga.fields[13], "2000");
  EXPECT_EQ(first(f, "RMC").fields[11], "D");
  f.carr_soln = receiver::CarrierSolution::kFloat;
  f.ref_station_id = 17;
  gga = first(f, "GGA");
  EXPECT_EQ(gga.fields[5], "5");
  EXPECT_EQ(gga.fields[13], "0017");
  EXPECT_EQ(first(f, "RMC").fields[11], "F");
  f.carr_soln = receiver::CarrierSolution::kFixed;
  EXPECT_EQ(first(f, "GGA").fields[5], "4");
  EXPECT_EQ(first(f, "RMC").fields[11], "R");
  // No fix: no quality, no age.
  f.type = receiver::FixType::kNone;
  gga = first(f, "GGA");
  EXPECT_EQ(gga.fields[5], "0");
  EXPECT_EQ(gga.fields[12], "");
}

}  // namespace rtk_test
}  // namespace gnssemu::protocol::nmea

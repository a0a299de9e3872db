// SPDX-License-Identifier: Apache-2.0
// Truth CSV reader and linear interpolation.
#include <gtest/gtest.h>

#include <sstream>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/world/truth_track.hpp"
#include "tools/gnssemu/batch/truth_csv.hpp"

using namespace gnssemu;
using namespace gnssemu::cli;

namespace {

std::vector<world::TruthSample> read(const std::string& text) {
  std::istringstream in(text);
  return read_truth_csv(in, "t.csv");
}

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(TruthCsv, LlaColumnsInAnyOrderWithExtrasAndComments) {
  const auto s = read(
      "# recorded by a simulator\n"
      "note,height_m,tow_s,lon_deg,lat_deg,gps_week\n"
      "a, 100.5 ,1000,2.295,48.8738,2190\r\n"
      "\n"
      "b,101.5,1001.5,2.295,48.8738,2190\n");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].t.week(), 2190);
  EXPECT_DOUBLE_EQ(s[1].t.tow_s(), 1001.5);
  const Lla lla = geo::lla_from_ecef(s[0].pos_m);
  EXPECT_NEAR(lla.lat_rad * kRadToDeg, 48.8738, 1e-12);
  EXPECT_NEAR(lla.lon_rad * kRadToDeg, 2.295, 1e-12);
  EXPECT_NEAR(lla.height_m, 100.5, 1e-6);
  EXPECT_FALSE(s[0].has_vel);
}

TEST(TruthCsv, ByteOrderMarkBeforeTheHeader) {
  const auto s = read("\xEF\xBB\xBFgps_week,tow_s,lat_deg,lon_deg,height_m\n2190,1,0,0,0\n");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_NEAR(s[0].pos_m.x, kWgs84A_m, 1e-6);
}

TEST(TruthCsv, EcefAndEnuVelocity) {
  const auto s = read(
      "gps_week,tow_s,x_m,y_m,z_m,ve_m_s,vn_m_s,vu_m_s\n"
      "2190,0,6378137,0,0,1,2,3\n");
  ASSERT_EQ(s.size(), 1u);
  ASSERT_TRUE(s[0].has_vel);
  // At lat 0, lon 0: east = +y, north = +z, up = +x.
  EXPECT_NEAR(s[0].vel_m_s.x, 3.0, 1e-12);
  EXPECT_NEAR(s[0].vel_m_s.y, 1.0, 1e-12);
  EXPECT_NEAR(s[0].vel_m_s.z, 2.0, 1e-12);
}

TEST(TruthCsv, ErrorsNameFileLineAndColumn) {
  const std::string h = "gps_week,tow_s,lat_deg,lon_deg,height_m\n";
  EXPECT_EQ(error_of(""), "t.csv: empty file: no header line");
  EXPECT_EQ(error_of(h), "t.csv:1: no data rows after the header");
  EXPECT_EQ(error_of("gps_week,lat_deg,lon_deg,height_m\n"), "t.csv:1: missing column 'tow_s'");
  EXPECT_EQ(error_of("gps_week,tow_s,lat_deg,height_m\n"), "t.csv:1: missing column 'lon_deg'");
  EXPECT_EQ(error_of("gps_week,tow_s\n"),
            "t.csv:1: missing position columns: need lat_deg,lon_deg,height_m or x_m,y_m,z_m");
  EXPECT_EQ(error_of("gps_week,tow_s,lat_deg,lon_deg,height_m,x_m,y_m,z_m\n"),
            "t.csv:1: both lat_deg/lon_deg/height_m and x_m/y_m/z_m columns; give one position form");
  EXPECT_EQ(error_of("gps_week,tow_s,tow_s,lat_deg,lon_deg,height_m\n"), "t.csv:1: column 'tow_s' appears twice");
  EXPECT_EQ(error_of(h + "2190,0,1,2,3,4\n"), "t.csv:2: 6 fields, header has 5");
  EXPECT_EQ(error_of(h + "2190,0,1,2\n"), "t.csv:2: 4 fields, header has 5");
  EXPECT_EQ(error_of(h + "2190,0,1,2,3\n2190.5,1,1,2,3\n"), "t.csv:3: column 'gps_week': '2190.5' is not an integer");
  EXPECT_EQ(error_of(h + "2190,,1,2,3\n"), "t.csv:2: column 'tow_s': empty value");
  EXPECT_EQ(error_of(h + "2190,nan,1,2,3\n"), "t.csv:2: column 'tow_s': 'nan' is not finite");
  EXPECT_EQ(error_of(h + "2190,604800,1,2,3\n"), "t.csv:2: column 'tow_s': 604800 outside [0, 604800)");
  EXPECT_EQ(error_of(h + "2190,0,90.5,2,3\n"), "t.csv:2: column 'lat_deg': 90.5 outside [-90, 90]");
  EXPECT_EQ(error_of(h + "2190,0,1,2,1e7\n"), "t.csv:2: column 'height_m': 1e7 outside [-10000, 1000000]");
  EXPECT_EQ(error_of(h + "2190,5,1,2,3\n2190,5,1,2,3\n"), "t.csv:3: column 'tow_s': time is not after the previous row's");
  EXPECT_EQ(error_of("gps_week,tow_s,x_m,y_m,z_m\n2190,0,1,2,3\n"),
            "t.csv:2: column 'x_m': |(x,y,z)| = 3.741657 m is not a position near the Earth");
  EXPECT_EQ(error_of("gps_week,tow_s,x_m,y_m,z_m,ve_m_s\n"), "t.csv:1: missing column 'vn_m_s'");
}

TEST(TruthCsv, MissingFile) {
  try {
    read_truth_csv("/nonexistent/truth.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/truth.csv: truth file not found (or not a regular file)");
  }
}

TEST(TruthCsv, RowsAcrossAWeekBoundaryInterpolateInTheTrack) {
  const auto s = read(
      "gps_week,tow_s,x_m,y_m,z_m\n"
      "2190,604799,6378137,0,0\n"
      "2191,1,6378157,40,0\n");  // across the week boundary, 2 s apart
  const world::TruthTrack track(s);
  const world::Truth mid = track.at(time::GpsTime(2191, 0.5));
  ASSERT_TRUE(mid.valid);
  EXPECT_NEAR(mid.pos_m.x, 6378152.0, 1e-6);
  EXPECT_NEAR(mid.pos_m.y, 30.0, 1e-9);
  // No velocity columns: the segment's mean velocity.
  EXPECT_NEAR(mid.vel_m_s.x, 10.0, 1e-9);
  EXPECT_NEAR(mid.vel_m_s.y, 20.0, 1e-9);
  EXPECT_TRUE(track.at(time::GpsTime(2190, 604799)).valid);
  EXPECT_TRUE(track.at(time::GpsTime(2191, 1)).valid);
  EXPECT_FALSE(track.at(time::GpsTime(2191, 1.01)).valid);
  EXPECT_FALSE(track.at(time::GpsTime(2190, 604798.99)).valid);
  // Going back in time after a forward query still finds the right segment.
  EXPECT_NEAR(track.at(time::GpsTime(2190, 604799.5)).pos_m.x, 6378142.0, 1e-6);
}

TEST(TruthCsv, ValidColumnMarksRowsWithoutTruth) {
  const auto s = read(
      "gps_week,tow_s,lat_deg,lon_deg,height_m,valid\n"
      "2190,10,48,2,100,1\n"
      "2190,11,,,,0\n"
      "2190,15,48,2,100,1\n"
      "2190,16,48.0001,2,100,1\n");
  ASSERT_EQ(s.size(), 4u);
  EXPECT_TRUE(s[0].valid);
  EXPECT_FALSE(s[1].valid);
  const world::TruthTrack track(s);
  EXPECT_TRUE(track.at(time::GpsTime(2190, 10.0)).valid);   // valid end of a segment
  EXPECT_FALSE(track.at(time::GpsTime(2190, 10.5)).valid);  // towards the no-truth row
  EXPECT_FALSE(track.at(time::GpsTime(2190, 11.0)).valid);
  EXPECT_FALSE(track.at(time::GpsTime(2190, 14.9)).valid);
  const world::Truth back = track.at(time::GpsTime(2190, 15.0));
  EXPECT_TRUE(back.valid);
  EXPECT_EQ(back.pos_m.x, s[2].pos_m.x);
  EXPECT_TRUE(track.at(time::GpsTime(2190, 15.5)).valid);
}

TEST(TruthCsv, ValidColumnTakesOnlyZeroOrOne) {
  EXPECT_NE(error_of("gps_week,tow_s,lat_deg,lon_deg,height_m,valid\n2190,1,0,0,0,2\n")
                .find("t.csv:2: column 'valid': 2 is not 0 (no truth) or 1"),
            std::string::npos);
  // A valid row still needs its position.
  EXPECT_NE(error_of("gps_week,tow_s,lat_deg,lon_deg,height_m,valid\n2190,1,,0,0,1\n").find("column 'lat_deg': empty"),
            std::string::npos);
}

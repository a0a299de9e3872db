// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "daemon/truth/truth_packet.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;

namespace {

const Lla kOrigin{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};

ParseResult parse(const std::string& s) {
  static const geo::LocalFrame frame(kOrigin);
  return parse_truth_packet(s, frame);
}

std::string with(const std::string& body) {
  return R"({"version":1,"vehicle":"ego","sim_time_s":12.5,)" + body + "}";
}

void expect_drop(const std::string& packet, DropReason reason) {
  const ParseResult r = parse(packet);
  EXPECT_FALSE(r.ok) << packet;
  EXPECT_EQ(drop_reason_name(r.reason), std::string(drop_reason_name(reason))) << packet << " -> " << r.detail;
  EXPECT_FALSE(r.detail.empty());
}

}  // namespace

TEST(TruthPacket, LlaPositionConvertsToEcef) {
  const ParseResult r = parse(with(R"("lla":{"lat_deg":48.8738,"lon_deg":2.295,"height_m":100.0})"));
  ASSERT_TRUE(r.ok) << r.detail;
  EXPECT_EQ(r.sample.vehicle, "ego");
  EXPECT_DOUBLE_EQ(r.sample.sim_time_s, 12.5);
  const Ecef expect = geo::ecef_from_lla(kOrigin);
  EXPECT_NEAR((r.sample.pos_m - expect).norm(), 0.0, 1e-6);
  EXPECT_NEAR(r.sample.lla.height_m, 100.0, 1e-6);
  EXPECT_FALSE(r.sample.vel_m_s.has_value());
  EXPECT_FALSE(r.sample.gps_time.has_value());
}

TEST(TruthPacket, EnuIsRelativeToOrigin) {
  const ParseResult r = parse(with(R"("enu":{"e_m":100.0,"n_m":-50.0,"u_m":2.0})"));
  ASSERT_TRUE(r.ok) << r.detail;
  const geo::LocalFrame frame(kOrigin);
  const Enu back = frame.to_enu(r.sample.pos_m);
  EXPECT_NEAR(back.x, 100.0, 1e-6);
  EXPECT_NEAR(back.y, -50.0, 1e-6);
  EXPECT_NEAR(back.z, 2.0, 1e-6);
}

TEST(TruthPacket, EcefPositionAndVelocities) {
  const Ecef p = geo::ecef_from_lla(kOrigin);
  char buf[256];
  std::snprintf(buf, sizeof buf, R"("ecef":{"x_m":%.4f,"y_m":%.4f,"z_m":%.4f},"vel_ecef":{"x_m_s":1,"y_m_s":2,"z_m_s":3})",
                p.x, p.y, p.z);
  ParseResult r = parse(with(buf));
  ASSERT_TRUE(r.ok) << r.detail;
  EXPECT_NEAR(r.sample.lla.lat_rad, kOrigin.lat_rad, 1e-9);
  ASSERT_TRUE(r.sample.vel_m_s.has_value());
  EXPECT_DOUBLE_EQ(r.sample.vel_m_s->z, 3.0);

  // 10 m/s north at the origin: ECEF vector along local north.
  r = parse(with(R"("enu":{"e_m":0,"n_m":0,"u_m":0},"vel_enu":{"e_m_s":0,"n_m_s":10,"u_m_s":0})"));
  ASSERT_TRUE(r.ok) << r.detail;
  const Enu v = geo::ecef_to_enu_vector(*r.sample.vel_m_s, kOrigin.lat_rad, kOrigin.lon_rad);
  EXPECT_NEAR(v.x, 0.0, 1e-9);
  EXPECT_NEAR(v.y, 10.0, 1e-9);
  EXPECT_NEAR(v.z, 0.0, 1e-9);
}

TEST(TruthPacket, GpsTimeAndUnknownKeysAccepted) {
  const ParseResult r = parse(with(
      R"("lla":{"lat_deg":10,"lon_deg":350,"height_m":0},"gps_week":2190,"gps_tow_s":518400.5,"attitude":{"yaw_deg":3})"));
  ASSERT_TRUE(r.ok) << r.detail;
  ASSERT_TRUE(r.sample.gps_time.has_value());
  EXPECT_EQ(r.sample.gps_time->week(), 2190);
  EXPECT_DOUBLE_EQ(r.sample.gps_time->tow_s(), 518400.5);
  EXPECT_NEAR(r.sample.lla.lon_rad, -10.0 * kDegToRad, 1e-12);  // 350 deg == -10 deg
}

TEST(TruthPacket, MalformedAndStructural) {
  expect_drop("", DropReason::kMalformedJson);
  expect_drop("{", DropReason::kMalformedJson);
  expect_drop("hello", DropReason::kMalformedJson);
  expect_drop("\x01\x02\x03\x04", DropReason::kMalformedJson);
  expect_drop(R"({"version":1,"vehicle":"a",})", DropReason::kMalformedJson);
  expect_drop("[1,2,3]", DropReason::kNotObject);
  expect_drop("42", DropReason::kNotObject);
  expect_drop(std::string(5000, ' ') + "{}", DropReason::kTooLarge);
}

TEST(TruthPacket, VersionChecks) {
  expect_drop(R"({"vehicle":"a","sim_time_s":1,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kMissingVersion);
  expect_drop(R"({"version":2,"vehicle":"a","sim_time_s":1,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kUnknownVersion);
  expect_drop(R"({"version":"1","vehicle":"a","sim_time_s":1,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kUnknownVersion);
  expect_drop(R"({"version":0,"vehicle":"a"})", DropReason::kUnknownVersion);
}

TEST(TruthPacket, MissingAndBadFields) {
  expect_drop(R"({"version":1,"sim_time_s":1,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kMissingField);
  expect_drop(R"({"version":1,"vehicle":7,"sim_time_s":1,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kBadType);
  expect_drop(R"({"version":1,"vehicle":"","sim_time_s":1,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kBadVehicleId);
  expect_drop(R"({"version":1,"vehicle":")" + std::string(65, 'x') +
                  R"(","sim_time_s":1,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kBadVehicleId);
  expect_drop(R"({"version":1,"vehicle":"a\u0007","sim_time_s":1,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kBadVehicleId);
  expect_drop(R"({"version":1,"vehicle":"a","lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kMissingField);
  expect_drop(R"({"version":1,"vehicle":"a","sim_time_s":"now","lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kBadType);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":0})"), DropReason::kMissingField);
  expect_drop(with(R"("lla":{"lat":0,"lon":0,"h":0})"), DropReason::kMissingField);
  expect_drop(with(R"("lla":[0,0,0])"), DropReason::kBadType);
  expect_drop(with(R"("lla":{"lat_deg":"48","lon_deg":0,"height_m":0})"), DropReason::kBadType);
  expect_drop(with(R"("lla":{"lat_deg":null,"lon_deg":0,"height_m":0})"), DropReason::kBadType);
  expect_drop(with(R"("enu":{"e_m":true,"n_m":0,"u_m":0})"), DropReason::kBadType);
  expect_drop(with(R"("enu":{"e_m":0,"n_m":0,"u_m":0},"vel_enu":{"e_m_s":0,"n_m_s":0})"), DropReason::kMissingField);
  expect_drop(with(R"("enu":{"e_m":0,"n_m":0,"u_m":0},"vel_ecef":5)"), DropReason::kBadType);
}

TEST(TruthPacket, PositionCount) {
  expect_drop(with(R"("pos":{"x":1})"), DropReason::kMissingPosition);
  expect_drop(R"({"version":1,"vehicle":"a","sim_time_s":1})", DropReason::kMissingPosition);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":0,"height_m":0},"enu":{"e_m":0,"n_m":0,"u_m":0})"),
              DropReason::kDuplicatePosition);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":0,"height_m":0},"ecef":{"x_m":0,"y_m":0,"z_m":0},"enu":{})"),
              DropReason::kDuplicatePosition);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":0,"height_m":0},"lla":{"lat_deg":1,"lon_deg":0,"height_m":0})"),
              DropReason::kDuplicatePosition);
  expect_drop(with(R"("lla":{"lat_deg":0,"lat_deg":1,"lon_deg":0,"height_m":0})"), DropReason::kDuplicateKey);
  expect_drop(R"({"version":1,"version":1,"vehicle":"a","sim_time_s":1,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kDuplicateKey);
  // The same key in different objects is fine.
  EXPECT_TRUE(parse(with(R"("enu":{"e_m":0,"n_m":0,"u_m":0},"x":{"e_m":1},"y":[{"e_m":2},{"e_m":3}])")).ok);
  expect_drop(with(R"("enu":{"e_m":0,"n_m":0,"u_m":0},"vel_enu":{"e_m_s":0,"n_m_s":0,"u_m_s":0},)"
                   R"("vel_ecef":{"x_m_s":0,"y_m_s":0,"z_m_s":0})"),
              DropReason::kDuplicateVelocity);
}

TEST(TruthPacket, NonFinite) {
  // Python's json.dumps(float("nan")) writes NaN; 1e999 overflows to inf.
  expect_drop(with(R"("lla":{"lat_deg":NaN,"lon_deg":0,"height_m":0})"), DropReason::kNonFinite);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":Infinity,"height_m":0})"), DropReason::kNonFinite);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":-Infinity,"height_m":0})"), DropReason::kNonFinite);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":0,"height_m":1e999})"), DropReason::kNonFinite);
  expect_drop(R"({"version":1,"vehicle":"a","sim_time_s":1e400,"lla":{"lat_deg":0,"lon_deg":0,"height_m":0}})",
              DropReason::kNonFinite);
  expect_drop(with(R"("enu":{"e_m":0,"n_m":0,"u_m":0},"vel_enu":{"e_m_s":-1e999,"n_m_s":0,"u_m_s":0})"),
              DropReason::kNonFinite);
}

TEST(TruthPacket, ImpossibleValues) {
  expect_drop(with(R"("lla":{"lat_deg":90.0001,"lon_deg":0,"height_m":0})"), DropReason::kLatitudeRange);
  expect_drop(with(R"("lla":{"lat_deg":-91,"lon_deg":0,"height_m":0})"), DropReason::kLatitudeRange);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":-180.5,"height_m":0})"), DropReason::kLongitudeRange);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":361,"height_m":0})"), DropReason::kLongitudeRange);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":0,"height_m":-1000.5})"), DropReason::kHeightRange);
  expect_drop(with(R"("lla":{"lat_deg":0,"lon_deg":0,"height_m":100001})"), DropReason::kHeightRange);
  expect_drop(with(R"("ecef":{"x_m":0,"y_m":0,"z_m":0})"), DropReason::kHeightRange);  // Earth's centre
  expect_drop(with(R"("enu":{"e_m":0,"n_m":0,"u_m":200000})"), DropReason::kHeightRange);
  expect_drop(with(R"("enu":{"e_m":0,"n_m":0,"u_m":0},"vel_enu":{"e_m_s":800,"n_m_s":800,"u_m_s":0})"),
              DropReason::kSpeedRange);
  expect_drop(with(R"("enu":{"e_m":0,"n_m":0,"u_m":0},"vel_ecef":{"x_m_s":0,"y_m_s":0,"z_m_s":1000.1})"),
              DropReason::kSpeedRange);
  // Limits themselves are accepted.
  EXPECT_TRUE(parse(with(R"("lla":{"lat_deg":-90,"lon_deg":180,"height_m":-1000})")).ok);
  EXPECT_TRUE(parse(with(R"("lla":{"lat_deg":90,"lon_deg":-180,"height_m":100000})")).ok);
  EXPECT_TRUE(parse(with(R"("enu":{"e_m":0,"n_m":0,"u_m":0},"vel_enu":{"e_m_s":1000,"n_m_s":0,"u_m_s":0})")).ok);
}

TEST(TruthPacket, GpsTimeChecks) {
  const std::string pos = R"("lla":{"lat_deg":0,"lon_deg":0,"height_m":0},)";
  expect_drop(with(pos + R"("gps_week":2190)"), DropReason::kMissingField);
  expect_drop(with(pos + R"("gps_tow_s":5)"), DropReason::kMissingField);
  expect_drop(with(pos + R"("gps_week":2190.5,"gps_tow_s":5)"), DropReason::kBadGpsTime);
  expect_drop(with(pos + R"("gps_week":-1,"gps_tow_s":5)"), DropReason::kBadGpsTime);
  expect_drop(with(pos + R"("gps_week":2190,"gps_tow_s":604800)"), DropReason::kBadGpsTime);
  expect_drop(with(pos + R"("gps_week":2190,"gps_tow_s":-0.1)"), DropReason::kBadGpsTime);
  expect_drop(with(pos + R"("gps_week":"2190","gps_tow_s":1)"), DropReason::kBadType);
}

TEST(TruthPacket, EveryReasonHasAName) {
  for (std::size_t i = 0; i < kDropReasonCount; ++i) {
    const std::string name = drop_reason_name(static_cast<DropReason>(i));
    EXPECT_FALSE(name.empty());
    EXPECT_NE(name, "unknown");
  }
  EXPECT_STREQ(drop_reason_name(DropReason::kSimTimeBackwards), "sim_time_backwards");
}

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/geo/geodesy.hpp"
#include "daemon/truth/lever_arm.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;

namespace {

constexpr double kLeverPi = std::numbers::pi;

world::Truth lever_truth_at(const Lla& lla, const Enu& vel_enu = Enu(0, 0, 0)) {
  world::Truth t;
  t.pos_m = geo::ecef_from_lla(lla);
  t.vel_m_s = Ecef(geo::enu_to_ecef_vector(vel_enu, lla.lat_rad, lla.lon_rad));
  t.valid = true;
  return t;
}

// The antenna's offset from the vehicle in local east, north, up, m.
Enu lever_offset_enu(const world::Truth& vehicle, const world::Truth& antenna, const Lla& lla) {
  return geo::ecef_to_enu_vector(antenna.pos_m - vehicle.pos_m, lla.lat_rad, lla.lon_rad);
}

const Lla kLeverParis{48.8738 * kLeverPi / 180.0, 2.2950 * kLeverPi / 180.0, 100.0};

}  // namespace

TEST(LeverArm, BodyToNedFollowsYawPitchRoll) {
  // Heading east: forward is east, right is south.
  Vec3 n = body_to_ned(daemon::Attitude{0.0, 0.0, kLeverPi / 2}, Vec3(1, 0, 0));
  EXPECT_NEAR(n.x, 0.0, 1e-12);
  EXPECT_NEAR(n.y, 1.0, 1e-12);
  n = body_to_ned(daemon::Attitude{0.0, 0.0, kLeverPi / 2}, Vec3(0, 1, 0));
  EXPECT_NEAR(n.x, -1.0, 1e-12);
  // Nose up 90°: forward is up (down negative).
  n = body_to_ned(daemon::Attitude{0.0, kLeverPi / 2, 0.0}, Vec3(1, 0, 0));
  EXPECT_NEAR(n.z, -1.0, 1e-12);
  // Right side down 90°: right is down.
  n = body_to_ned(daemon::Attitude{kLeverPi / 2, 0.0, 0.0}, Vec3(0, 1, 0));
  EXPECT_NEAR(n.z, 1.0, 1e-12);
}

TEST(LeverArm, AppliedWithThePacketsAttitude) {
  const world::Truth v = lever_truth_at(kLeverParis);
  // 2 m forward, 1 m right, 0.5 m down, heading east.
  const world::Truth a = antenna_truth(v, Vec3(2.0, 1.0, 0.5), daemon::Attitude{0.0, 0.0, kLeverPi / 2});
  const Enu d = lever_offset_enu(v, a, kLeverParis);
  EXPECT_NEAR(d.x, 2.0, 1e-6);   // east
  EXPECT_NEAR(d.y, -1.0, 1e-6);  // north: right of an east heading is south
  EXPECT_NEAR(d.z, -0.5, 1e-6);  // up
  EXPECT_TRUE(a.valid);
  EXPECT_EQ(a.vel_m_s, v.vel_m_s);
}

TEST(LeverArm, WithoutAttitudeHeadingFollowsTheVelocity) {
  // Moving north-west at 10 m/s: forward is north-west.
  const world::Truth v = lever_truth_at(kLeverParis, Enu(-10.0 / std::sqrt(2.0), 10.0 / std::sqrt(2.0), 0.0));
  const Enu d = lever_offset_enu(v, antenna_truth(v, Vec3(1.0, 0.0, 0.0), std::nullopt), kLeverParis);
  EXPECT_NEAR(d.x, -1.0 / std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(d.y, 1.0 / std::sqrt(2.0), 1e-6);
  // Standing: heading north, right is east.
  const world::Truth s = lever_truth_at(kLeverParis);
  const Enu e = lever_offset_enu(s, antenna_truth(s, Vec3(0.0, 3.0, 0.0), std::nullopt), kLeverParis);
  EXPECT_NEAR(e.x, 3.0, 1e-6);
  EXPECT_NEAR(e.y, 0.0, 1e-6);
}

TEST(LeverArm, InvalidTruthAndZeroArmPassThrough) {
  world::Truth v = lever_truth_at(kLeverParis);
  EXPECT_EQ(antenna_truth(v, Vec3(), daemon::Attitude{1, 0.5, 2}).pos_m, v.pos_m);
  v.valid = false;
  EXPECT_EQ(antenna_truth(v, Vec3(1, 2, 3), std::nullopt).pos_m, v.pos_m);
}

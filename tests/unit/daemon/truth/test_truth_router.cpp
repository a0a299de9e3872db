// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "core/common/constants.hpp"
#include "core/geo/local_frame.hpp"
#include "daemon/truth/demo_trajectory.hpp"
#include "daemon/truth/truth_router.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;

namespace {

const time::GpsTime kT0(2190, 522000.0);
const TrackParams kParams{2.0, 0.5};

TruthSample sample(const std::string& id, double sim_s, double x_m) {
  TruthSample s;
  s.vehicle = id;
  s.sim_time_s = sim_s;
  s.pos_m = Ecef(x_m, 0.0, 0.0);
  return s;
}

}  // namespace

TEST(TruthRouter, FirstVehicleDrives) {
  TruthRouter r(kParams, config::TimeMode::kRealtime);
  EXPECT_FALSE(r.has_driver());
  EXPECT_FALSE(r.truth_at(kT0, 0.0).valid);
  TruthRouter::Ingest in = r.ingest(sample("car", 50.0, 1.0), kT0, 0.0);
  ASSERT_TRUE(in.accepted);
  EXPECT_TRUE(in.new_vehicle);
  EXPECT_TRUE(in.driving);
  EXPECT_TRUE(in.reanchored);
  EXPECT_EQ(in.stamp, kT0);
  in = r.ingest(sample("truck", 50.0, 99.0), kT0 + 0.01, 0.01);
  ASSERT_TRUE(in.accepted);
  EXPECT_FALSE(in.driving);
  EXPECT_EQ(r.driver_id(), "car");
  EXPECT_EQ(r.vehicle_count(), 2u);
  in = r.ingest(sample("car", 50.1, 2.0), kT0 + 0.12, 0.12);
  EXPECT_FALSE(in.reanchored);
  EXPECT_NEAR(in.stamp - kT0, 0.1, 1e-9);  // sim spacing, not arrival jitter
  const world::Truth t = r.truth_at(kT0 + 0.05, 0.12);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.pos_m.x, 1.5, 1e-9);
}

TEST(TruthRouter, ConfiguredVehicleDrives) {
  TruthRouter r(kParams, config::TimeMode::kRealtime, "truck");
  EXPECT_FALSE(r.ingest(sample("car", 1.0, 1.0), kT0, 0.0).driving);
  EXPECT_FALSE(r.has_driver());
  EXPECT_TRUE(r.ingest(sample("truck", 1.0, 5.0), kT0, 0.0).driving);
  EXPECT_NEAR(r.truth_at(kT0, 0.0).pos_m.x, 5.0, 1e-12);
}

TEST(TruthRouter, BackwardsDroppedRestartAfterTimeout) {
  TruthRouter r(kParams, config::TimeMode::kRealtime);
  ASSERT_TRUE(r.ingest(sample("car", 10.0, 1.0), kT0, 0.0).accepted);
  TruthRouter::Ingest in = r.ingest(sample("car", 9.0, 1.0), kT0 + 0.1, 0.1);
  EXPECT_FALSE(in.accepted);
  EXPECT_EQ(in.reason, DropReason::kSimTimeBackwards);
  // Stopped: no truth after the timeout.
  EXPECT_FALSE(r.driver_fresh(2.5));
  EXPECT_FALSE(r.truth_at(kT0 + 2.5, 2.5).valid);
  // The simulator restarts at sim time 0: accepted as a fresh start.
  in = r.ingest(sample("car", 0.0, 7.0), kT0 + 3.0, 3.0);
  ASSERT_TRUE(in.accepted);
  EXPECT_TRUE(in.reanchored);
  EXPECT_EQ(in.stamp, kT0 + 3.0);
  EXPECT_TRUE(r.driver_fresh(3.0));
  EXPECT_NEAR(r.truth_at(kT0 + 3.0, 3.0).pos_m.x, 7.0, 1e-12);
}

TEST(TruthRouter, GpsTimeInPacketWins) {
  TruthRouter r(kParams, config::TimeMode::kRealtime);
  TruthSample s = sample("car", 1.0, 1.0);
  s.gps_time = time::GpsTime(2190, 600000.0);
  const TruthRouter::Ingest in = r.ingest(s, kT0, 0.0);
  EXPECT_EQ(in.stamp, *s.gps_time);
  EXPECT_EQ(*r.driver_newest(), *s.gps_time);
}

TEST(TruthRouter, LockstepStampsFromSimTime) {
  TruthRouter r(kParams, config::TimeMode::kLockstep);
  // First packet anchors at the next epoch time passed by the daemon.
  TruthRouter::Ingest in = r.ingest(sample("car", 100.0, 0.0), kT0, 0.0);
  EXPECT_EQ(in.stamp, kT0);
  // Slow simulator: 0.5 s of sim time over 3 s of wall time, never re-anchored.
  in = r.ingest(sample("car", 100.5, 5.0), kT0 + 99.0, 1.5);
  EXPECT_FALSE(in.reanchored);
  EXPECT_NEAR(in.stamp - kT0, 0.5, 1e-9);
}

TEST(TruthRouter, ClockJumpDropsSamples) {
  TruthRouter r(kParams, config::TimeMode::kRealtime);
  r.ingest(sample("car", 1.0, 1.0), kT0, 0.0);
  r.on_clock_jump();
  EXPECT_FALSE(r.truth_at(kT0, 0.1).valid);
  EXPECT_FALSE(r.driver_newest().has_value());
  const TruthRouter::Ingest in = r.ingest(sample("car", 1.1, 2.0), kT0 - 80000.0, 0.1);
  ASSERT_TRUE(in.accepted);
  EXPECT_TRUE(in.reanchored);
  EXPECT_TRUE(r.truth_at(kT0 - 80000.0, 0.1).valid);
}

TEST(TruthRouter, VehicleLimit) {
  TruthRouter r(kParams, config::TimeMode::kRealtime);
  for (std::size_t i = 0; i < TruthRouter::kMaxVehicles; ++i) {
    std::string id = "v";
    id += std::to_string(i);  // (not "v" + ...: GCC 12 -Wrestrict false positive)
    ASSERT_TRUE(r.ingest(sample(id, 1.0, 1.0), kT0, 0.0).accepted);
  }
  const TruthRouter::Ingest in = r.ingest(sample("one-too-many", 1.0, 1.0), kT0, 0.0);
  EXPECT_FALSE(in.accepted);
  EXPECT_EQ(in.reason, DropReason::kTooManyVehicles);
}

TEST(DemoTrajectory, CircleAroundOrigin) {
  const geo::LocalFrame frame(Lla{48.8738 * kDegToRad, 2.295 * kDegToRad, 100.0});
  const DemoTrajectory demo(frame, 50.0, 5.0, 2.0);
  Enu p = demo.position_enu(0.0);
  EXPECT_NEAR(p.x, 50.0, 1e-12);
  EXPECT_NEAR(p.y, 0.0, 1e-12);
  EXPECT_NEAR(p.z, 2.0, 1e-12);
  // Quarter turn: arc 25*pi m at 5 m/s.
  const double quarter_s = 0.25 * 2.0 * kPi * 50.0 / 5.0;
  p = demo.position_enu(quarter_s);
  EXPECT_NEAR(p.x, 0.0, 1e-9);
  EXPECT_NEAR(p.y, 50.0, 1e-9);
  const Enu v = demo.velocity_enu(quarter_s);
  EXPECT_NEAR(v.x, -5.0, 1e-9);
  EXPECT_NEAR(v.y, 0.0, 1e-9);
  const world::Truth t = demo.truth(time::GpsTime(2190, 1.0), 123.0);
  ASSERT_TRUE(t.valid);
  const Enu back = frame.to_enu(t.pos_m);
  EXPECT_NEAR(std::hypot(back.x, back.y), 50.0, 1e-6);
  EXPECT_NEAR(back.z, 2.0, 1e-6);
  EXPECT_NEAR(t.vel_m_s.norm(), 5.0, 1e-9);
}

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "daemon/truth/fleet_router.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;

namespace {

const time::GpsTime kFleetT0(2190, 522000.0);
const TrackParams kFleetParams{2.0, 0.5};

TruthSample fleet_sample(const std::string& id, double sim_s, double x_m) {
  TruthSample s;
  s.vehicle = id;
  s.sim_time_s = sim_s;
  s.pos_m = Ecef(x_m, 0.0, 0.0);
  return s;
}

}  // namespace

TEST(FleetRouter, EachPacketReachesOnlyItsVehicle) {
  FleetRouter r(kFleetParams, config::TimeMode::kRealtime, {"a", "b", "c"});
  EXPECT_FALSE(r.single());
  const FleetRouter::Routed ra = r.ingest(fleet_sample("a", 1.0, 10.0), kFleetT0, 0.0);
  const FleetRouter::Routed rb = r.ingest(fleet_sample("b", 7.0, 20.0), kFleetT0, 0.0);
  ASSERT_TRUE(ra.vehicle && rb.vehicle);
  EXPECT_EQ(*ra.vehicle, 0u);
  EXPECT_EQ(*rb.vehicle, 1u);
  EXPECT_TRUE(ra.in.accepted && ra.in.driving);
  EXPECT_TRUE(rb.in.accepted && rb.in.driving);
  EXPECT_DOUBLE_EQ(r.router(0).truth_at(kFleetT0, 0.0).pos_m.x, 10.0);
  EXPECT_DOUBLE_EQ(r.router(1).truth_at(kFleetT0, 0.0).pos_m.x, 20.0);
  EXPECT_FALSE(r.router(2).has_driver());  // c never sent
  EXPECT_EQ(r.router(0).vehicle_count(), 1u);
}

TEST(FleetRouter, UnknownIdsAreRefusedAndKeepNothing) {
  FleetRouter r(kFleetParams, config::TimeMode::kRealtime, {"v0", "v1"});
  // A flood of distinct ids: every one refused, no vehicle learns of it.
  for (int i = 0; i < 10000; ++i) {
    const FleetRouter::Routed x = r.ingest(fleet_sample("x" + std::to_string(i), 1.0 + i, 0.0), kFleetT0, 0.0);
    ASSERT_FALSE(x.vehicle);
    ASSERT_FALSE(x.in.accepted);
    ASSERT_EQ(x.in.reason, DropReason::kUnknownVehicle);
  }
  EXPECT_EQ(r.size(), 2u);
  EXPECT_EQ(r.router(0).vehicle_count(), 0u);
  EXPECT_EQ(r.router(1).vehicle_count(), 0u);
  EXPECT_EQ(r.find("v1"), std::optional<std::size_t>(1));
  EXPECT_FALSE(r.find("v2"));
}

TEST(FleetRouter, SingleFormTakesAnyIdAsBefore) {
  FleetRouter r(kFleetParams, config::TimeMode::kRealtime, {std::string()}, "car");
  EXPECT_TRUE(r.single());
  const FleetRouter::Routed t = r.ingest(fleet_sample("truck", 1.0, 5.0), kFleetT0, 0.0);
  ASSERT_TRUE(t.vehicle);
  EXPECT_TRUE(t.in.accepted);
  EXPECT_FALSE(t.in.driving);  // [truth] vehicle = "car" drives
  const FleetRouter::Routed c = r.ingest(fleet_sample("car", 1.0, 6.0), kFleetT0, 0.0);
  EXPECT_TRUE(c.in.driving);
}

TEST(FleetRouter, AttitudeOfTheNewestPacketThatHadOne) {
  FleetRouter r(kFleetParams, config::TimeMode::kRealtime, {"a"});
  EXPECT_FALSE(r.attitude(0));
  TruthSample s = fleet_sample("a", 1.0, 0.0);
  s.attitude = daemon::Attitude{0.1, 0.2, 0.3};
  r.ingest(s, kFleetT0, 0.0);
  r.ingest(fleet_sample("a", 2.0, 0.0), kFleetT0 + 1.0, 1.0);
  ASSERT_TRUE(r.attitude(0));
  EXPECT_DOUBLE_EQ(r.attitude(0)->yaw_rad, 0.3);
}

TEST(FleetRouter, LockstepWaitsForEveryFreshVehicle) {
  FleetRouter r(kFleetParams, config::TimeMode::kLockstep, {"a", "b"});
  EXPECT_FALSE(r.reached(0.0));
  r.ingest(fleet_sample("a", 0.0, 0.0), kFleetT0, 0.0);
  r.ingest(fleet_sample("a", 1.0, 0.0), kFleetT0, 0.1);
  ASSERT_TRUE(r.reached(0.1));
  EXPECT_EQ(*r.reached(0.1), kFleetT0 + 1.0);  // b never sent: it does not hold a back
  r.ingest(fleet_sample("b", 0.0, 0.0), kFleetT0, 0.2);
  EXPECT_EQ(*r.reached(0.2), kFleetT0);  // b anchored at kFleetT0: the fleet is there
  r.ingest(fleet_sample("a", 2.0, 0.0), kFleetT0, 0.3);
  EXPECT_EQ(*r.reached(0.3), kFleetT0);
  r.ingest(fleet_sample("b", 2.0, 0.0), kFleetT0, 0.4);
  EXPECT_EQ(*r.reached(0.4), kFleetT0 + 2.0);
  // a stops: after its timeout b alone moves the epochs on.
  r.ingest(fleet_sample("b", 3.0, 0.0), kFleetT0, 2.25);
  EXPECT_EQ(*r.reached(2.25), kFleetT0 + 2.0);
  EXPECT_EQ(*r.reached(2.5), kFleetT0 + 3.0);
  EXPECT_TRUE(r.any_fresh(2.5));
  EXPECT_FALSE(r.any_fresh(10.0));
}

TEST(FleetRouter, ReshapeKeepsTheTracksOfTheVehiclesThatStay) {
  FleetRouter r(kFleetParams, config::TimeMode::kRealtime, {"a", "b"});
  ASSERT_TRUE(r.ingest(fleet_sample("a", 1.0, 10.0), kFleetT0, 0.0).in.accepted);
  ASSERT_TRUE(r.ingest(fleet_sample("b", 1.0, 20.0), kFleetT0, 0.0).in.accepted);
  const std::vector<std::optional<std::size_t>> moved = r.reshape({"b", "c"});
  ASSERT_EQ(moved.size(), 2u);
  EXPECT_FALSE(moved[0]);  // a removed
  ASSERT_TRUE(moved[1]);
  EXPECT_EQ(*moved[1], 0u);
  EXPECT_EQ(r.size(), 2u);
  EXPECT_EQ(r.id(1), "c");
  EXPECT_TRUE(r.router(0).has_driver());
  EXPECT_DOUBLE_EQ(r.router(0).truth_at(kFleetT0, 0.0).pos_m.x, 20.0);  // b's track went with it
  EXPECT_FALSE(r.router(1).has_driver());
  EXPECT_EQ(r.ingest(fleet_sample("a", 2.0, 10.0), kFleetT0, 0.1).in.reason, DropReason::kUnknownVehicle);
  const FleetRouter::Routed rc = r.ingest(fleet_sample("c", 2.0, 30.0), kFleetT0, 0.1);
  ASSERT_TRUE(rc.vehicle);
  EXPECT_EQ(*rc.vehicle, 1u);
  EXPECT_TRUE(rc.in.accepted && rc.in.driving);
}

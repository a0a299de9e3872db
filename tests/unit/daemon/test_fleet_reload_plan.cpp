// SPDX-License-Identifier: Apache-2.0
// daemon/fleet_reload_plan: which vehicles a reload adds, removes, keeps or
// changes, and what of a changed one applies live or at a restart.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "daemon/fleet_reload_plan.hpp"

namespace gnssemu::daemon::fleet_reload_plan_test {
namespace {

config::OutputPortConfig pty(const std::string& name, const std::string& path) {
  config::OutputPortConfig o;
  o.name = name;
  o.transport = config::PtyPortConfig{path};
  return o;
}

config::VehicleReceiverConfig receiver(const config::Config& top, const std::string& vehicle, const std::string& name) {
  return config::VehicleReceiverConfig{name, Vec3{}, config::receiver_settings(top),
                                       {pty(vehicle + "-" + name, "/tmp/gnssemu/" + vehicle + "/" + name)}};
}

// Vehicles a (gps1, gps2) and b (gps1).
config::Config fleet() {
  config::Config c = config::default_config();
  c.vehicles.push_back(config::VehicleConfig{"a", {receiver(c, "a", "gps1"), receiver(c, "a", "gps2")}, {}});
  c.vehicles.push_back(config::VehicleConfig{"b", {receiver(c, "b", "gps1")}, {}});
  return c;
}

config::VehicleConfig& vehicle(config::Config& c, const std::string& id) {
  for (config::VehicleConfig& v : c.vehicles) {
    if (v.id == id) return v;
  }
  throw std::runtime_error("no vehicle " + id);
}

}  // namespace

TEST(FleetReloadPlan, SameFleetKeepsEveryVehicle) {
  const FleetReloadPlan p = plan_fleet_reload(fleet(), fleet(), {});
  EXPECT_EQ(FleetReloadPlan::ids(p.kept), "a, b");
  EXPECT_EQ(FleetReloadPlan::ids(p.added), "none");
  EXPECT_EQ(FleetReloadPlan::ids(p.removed), "none");
  EXPECT_EQ(FleetReloadPlan::ids(p.changed), "none");
}

TEST(FleetReloadPlan, DropOneAddOneKeepsTheOther) {
  config::Config loaded = fleet();
  loaded.vehicles.erase(loaded.vehicles.begin() + 1);  // b goes
  loaded.vehicles.push_back(config::VehicleConfig{"c", {receiver(loaded, "c", "gps1")}, {}});
  loaded.vehicles.insert(loaded.vehicles.begin(), config::VehicleConfig{"d", {receiver(loaded, "d", "gps1")}, {}});
  const FleetReloadPlan p = plan_fleet_reload(fleet(), loaded, {});
  EXPECT_EQ(FleetReloadPlan::ids(p.kept), "a");
  EXPECT_EQ(FleetReloadPlan::ids(p.removed), "b");
  EXPECT_EQ(FleetReloadPlan::ids(p.added), "d, c");  // the file's order
  EXPECT_TRUE(p.changed.empty());
  ASSERT_EQ(p.removed.size(), 1u);
  EXPECT_EQ(p.removed[0].running, 1u);
  ASSERT_EQ(p.added.size(), 2u);
  EXPECT_EQ(p.added[0].loaded, 0u);
  EXPECT_EQ(p.added[1].loaded, 2u);
  EXPECT_EQ(p.kept[0].running, 0u);
  EXPECT_EQ(p.kept[0].loaded, 1u);  // a moved in the file: still kept
}

TEST(FleetReloadPlan, ReceiverModelsAndTransportApplyLive) {
  config::Config loaded = fleet();
  config::VehicleConfig& a = vehicle(loaded, "a");
  a.receivers[1].settings.world.seed += 5;                                                  // gps2's models
  a.receivers[0].outputs[0].transport = config::PtyPortConfig{"/tmp/elsewhere/a-gps1"};  // gps1's port moved
  a.receivers[0].lever_arm_m = Vec3{0.5, 0.0, 0.0};
  const FleetReloadPlan p = plan_fleet_reload(fleet(), loaded, {});
  EXPECT_EQ(FleetReloadPlan::ids(p.changed), "a");
  EXPECT_EQ(FleetReloadPlan::ids(p.kept), "b");
  ASSERT_EQ(p.changed.size(), 1u);
  const VehicleReload& v = p.changed[0];
  ASSERT_EQ(v.receivers.size(), 2u);
  EXPECT_EQ(v.receivers[0].name, "gps1");
  EXPECT_TRUE(v.receivers[0].lever_arm);
  EXPECT_FALSE(v.receivers[0].plan.receiver);
  EXPECT_EQ(v.receivers[0].plan.reopen, std::vector<std::size_t>{0});
  EXPECT_EQ(v.receivers[1].name, "gps2");
  EXPECT_TRUE(v.receivers[1].plan.receiver);
  EXPECT_FALSE(v.receivers[1].lever_arm);
  EXPECT_TRUE(v.applies());
  EXPECT_EQ(v.describe_live(), "gps1: 1 output(s) reopened, lever arm; gps2: receiver models (receiver restarted, hot)");
  EXPECT_EQ(v.describe_restart(), "nothing");
}

TEST(FleetReloadPlan, RestartPartsAreNamedPerReceiver) {
  config::Config loaded = fleet();
  config::VehicleConfig& b = vehicle(loaded, "b");
  b.receivers[0].outputs[0].baud = 115200;                           // the chip's stored port settings
  b.receivers[0].outputs.push_back(pty("b-extra", "/tmp/gnssemu/b/extra"));  // an output added
  vehicle(loaded, "a").receivers.pop_back();                         // a receiver removed
  const FleetReloadPlan p = plan_fleet_reload(fleet(), loaded, {});
  EXPECT_EQ(FleetReloadPlan::ids(p.changed), "a, b");
  ASSERT_EQ(p.changed.size(), 2u);
  EXPECT_FALSE(p.changed[0].applies());
  EXPECT_EQ(p.changed[0].describe_restart(), "receivers added or removed (gps1, gps2 -> gps1)");
  EXPECT_FALSE(p.changed[1].applies());
  EXPECT_EQ(p.changed[1].describe_restart(), "gps1: outputs added or removed (1 -> 2)");
  b.receivers[0].outputs.pop_back();
  EXPECT_EQ(plan_fleet_reload(fleet(), loaded, {}).changed[1].describe_restart(),
            "gps1: output b-gps1 protocols/messages/baud");
}

TEST(FleetReloadPlan, TopLevelRestartsAreNotRepeatedPerReceiver) {
  config::Config loaded = fleet();
  for (config::VehicleConfig& v : loaded.vehicles) {
    for (config::VehicleReceiverConfig& r : v.receivers) r.settings.rate_hz = 5.0;
  }
  // Every receiver's rate_hz changed: the top level's plan says it once.
  const FleetReloadPlan with_top = plan_fleet_reload(fleet(), loaded, {"rate_hz"});
  EXPECT_EQ(FleetReloadPlan::ids(with_top.kept), "a, b");
  const FleetReloadPlan alone = plan_fleet_reload(fleet(), loaded, {});
  EXPECT_EQ(FleetReloadPlan::ids(alone.changed), "a, b");
  EXPECT_EQ(alone.changed[0].describe_restart(), "gps1: rate_hz; gps2: rate_hz");
}

TEST(FleetReloadPlan, FleetTemplatesCompareByTheirVehicles) {
  config::Config running = config::default_config();
  running.fleet = config::FleetConfig{3, {pty("{vehicle}", "/tmp/gnssemu/{vehicle}/{receiver}")}};
  config::Config loaded = running;
  loaded.fleet->count = 2;
  FleetReloadPlan p = plan_fleet_reload(running, loaded, {});
  EXPECT_EQ(FleetReloadPlan::ids(p.kept), "v0, v1");
  EXPECT_EQ(FleetReloadPlan::ids(p.removed), "v2");
  loaded.fleet->count = 4;
  p = plan_fleet_reload(running, loaded, {});
  EXPECT_EQ(FleetReloadPlan::ids(p.added), "v3");
  EXPECT_EQ(FleetReloadPlan::ids(p.kept), "v0, v1, v2");
}

TEST(ReloadPlan, ChangingTheFormNeedsARestart) {
  const config::Config single = config::default_config();
  const std::vector<std::string> want{"top-level [[output]] replaced by [[vehicle]]/[fleet]"};
  EXPECT_EQ(plan_reload(single, fleet()).need_restart, want);
  EXPECT_EQ(plan_reload(fleet(), single).need_restart,
            std::vector<std::string>{"[[vehicle]]/[fleet] replaced by top-level [[output]]"});
}

}  // namespace gnssemu::daemon::fleet_reload_plan_test

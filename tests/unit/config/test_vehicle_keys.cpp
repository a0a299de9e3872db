// SPDX-License-Identifier: Apache-2.0
// config/vehicle_keys: [[vehicle]], [[vehicle.receiver]] with its [receiver]
// overrides, [fleet] templates, the resolved list, and the errors of the
// three forms (duplicate ids, names, paths and ports, counts, unknown keys).
#include "test_helpers.hpp"

namespace gnssemu::config::test::vehicle_keys_test {
namespace {

// kBase (6 lines) + [receiver] seed 11 on lines 7-8; vehicles start on line 9.
const std::string kTop = kBase + "[receiver]\nseed = 11\n";

const std::string kTwoVehicles = kTop +
                                 "[[vehicle]]\n"                                // 9
                                 "id = \"ego\"\n"                               // 10
                                 "[[vehicle.receiver]]\n"                       // 11
                                 "name = \"gps1\"\n"                            // 12
                                 "[[vehicle.receiver.output]]\n"                // 13
                                 "name = \"a\"\n"                               // 14
                                 "path = \"/tmp/gnssemu/ego/gps1\"\n"           // 15
                                 "[[vehicle.receiver]]\n"                       // 16
                                 "name = \"gps2\"\n"                            // 17
                                 "lever_arm_m = [1.0, 0.5, -0.2]\n"             // 18
                                 "seed = 12\n"                                  // 19
                                 "generation = \"m9\"\n"                        // 20
                                 "[[vehicle.receiver.output]]\n"                // 21
                                 "name = \"a\"\n"                               // 22
                                 "type = \"tcp\"\n"                             // 23
                                 "port = 4001\n"                                // 24
                                 "[[vehicle]]\n"                                // 25
                                 "id = \"wing\"\n"                              // 26
                                 "[[vehicle.receiver]]\n"                       // 27
                                 "name = \"gps1\"\n"                            // 28
                                 "[[vehicle.receiver.output]]\n"                // 29
                                 "name = \"a\"\n"                               // 30
                                 "path = \"/tmp/gnssemu/wing/gps1\"\n";         // 31

TEST(VehicleKeys, SingleVehicleFormIsOneVehicleWithOneReceiver) {
  const Config c = parse(kTop + "[truth]\nvehicle = \"ego\"\n[[output]]\nname = \"a\"\npath = \"/tmp/x\"\n");
  const std::vector<VehicleConfig> v = resolve_vehicles(c);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].id, "ego");
  ASSERT_EQ(v[0].receivers.size(), 1u);
  EXPECT_EQ(v[0].receivers[0].name, "gps1");
  EXPECT_EQ(v[0].receivers[0].settings.world.seed, 11u);
  ASSERT_EQ(v[0].receivers[0].outputs.size(), 1u);
  EXPECT_EQ(std::get<PtyPortConfig>(v[0].receivers[0].outputs[0].transport).path, "/tmp/x");
  EXPECT_EQ(resolve_vehicles(parse(kBase))[0].id, "");  // any vehicle
}

TEST(VehicleKeys, UnsetBaudIsTheReceiversGenerationsFactoryRate) {
  const std::vector<VehicleConfig> v = resolve_vehicles(parse(kTwoVehicles + "[[vehicle.receiver]]\n"
                                                                             "name = \"gps2\"\n"
                                                                             "generation = \"f9p\"\n"
                                                                             "[[vehicle.receiver.output]]\n"
                                                                             "name = \"a\"\n"
                                                                             "path = \"/tmp/gnssemu/wing/gps2\"\n"));
  EXPECT_EQ(v.at(0).receivers.at(0).outputs.at(0).baud, 9600u);   // m8 from the top level
  EXPECT_EQ(v.at(0).receivers.at(1).outputs.at(0).baud, 0u);      // m9 over tcp: no line
  EXPECT_EQ(v.at(1).receivers.at(1).outputs.at(0).baud, 38400u);  // f9p pty
}

TEST(VehicleKeys, ReceiversMergeTheirKeysOverTheTopLevel) {
  const Config c = parse(kTwoVehicles);
  EXPECT_TRUE(c.outputs.empty());
  const std::vector<VehicleConfig> v = resolve_vehicles(c);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].id, "ego");
  EXPECT_EQ(v[1].id, "wing");
  ASSERT_EQ(v[0].receivers.size(), 2u);
  const VehicleReceiverConfig& gps1 = v[0].receivers[0];
  const VehicleReceiverConfig& gps2 = v[0].receivers[1];
  EXPECT_EQ(gps1.settings.world.seed, 11u);
  EXPECT_EQ(gps1.settings.generation, protocol::ubx::Generation::kM8);
  EXPECT_EQ(gps2.settings.world.seed, 12u);
  // A receiver's seed is its own; the sky keeps the top level's.
  EXPECT_EQ(world::sky_seed(gps1.settings.world), 11u);
  EXPECT_EQ(world::sky_seed(gps2.settings.world), 11u);
  EXPECT_EQ(gps2.settings.generation, protocol::ubx::Generation::kM9);
  EXPECT_EQ(gps2.lever_arm_m.x, 1.0);
  EXPECT_EQ(gps2.lever_arm_m.z, -0.2);
  EXPECT_EQ(std::get<TcpPortConfig>(gps2.outputs[0].transport).port, 4001);
  // The top level is untouched by the overrides.
  EXPECT_EQ(c.world.seed, 11u);
  // Written and read back: the same vehicles, the same text.
  const std::string text = to_toml(c, kData);
  const Config back = parse_config(text, "w.toml", kData);
  ASSERT_EQ(back.vehicles.size(), 2u);
  EXPECT_EQ(back.vehicles[0].receivers[1].settings.world.seed, 12u);
  EXPECT_EQ(to_toml(back, kData), text);
}

TEST(VehicleKeys, FleetExpandsTemplates) {
  const Config c = parse(kTop +
                         "[fleet]\ncount = 3\n"
                         "[[fleet.output]]\nname = \"gps-{vehicle}\"\npath = \"/tmp/gnssemu/{vehicle}/{receiver}\"\n"
                         "[[fleet.output]]\nname = \"net\"\ntype = \"tcp\"\nport_base = 5000\n"
                         "[[fleet.output]]\nname = \"u\"\ntype = \"udp\"\naddress = \"127.0.0.1\"\nport_base = 6000\n");
  const std::vector<VehicleConfig> v = resolve_vehicles(c);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[2].id, "v2");
  const VehicleReceiverConfig& r = v[2].receivers[0];
  EXPECT_EQ(r.name, "gps1");
  // One sky (the top level's seed); each vehicle's own noise and clock.
  EXPECT_EQ(r.settings.world.seed, 13u);
  EXPECT_EQ(world::sky_seed(r.settings.world), 11u);
  EXPECT_EQ(v[0].receivers[0].settings.world.seed, 11u);
  EXPECT_EQ(r.outputs[0].name, "gps-v2");
  EXPECT_EQ(std::get<PtyPortConfig>(r.outputs[0].transport).path, "/tmp/gnssemu/v2/gps1");
  EXPECT_EQ(std::get<TcpPortConfig>(r.outputs[1].transport).port, 5002);
  EXPECT_EQ(std::get<UdpPortConfig>(r.outputs[2].transport).port, 6002);
  EXPECT_EQ(to_toml(parse_config(to_toml(c, kData), "w.toml", kData), kData), to_toml(c, kData));
}

TEST(VehicleKeys, DuplicatesAreErrorsAtTheirLine) {
  std::string dup_id = kTwoVehicles;
  dup_id.replace(dup_id.find("\"wing\""), 6, "\"ego\"");
  EXPECT_EQ(error_of(dup_id), "t.toml:26: vehicle[1].id: 'ego' is used twice");
  std::string dup_name = kTwoVehicles;
  dup_name.replace(dup_name.find("\"gps2\""), 6, "\"gps1\"");
  EXPECT_EQ(error_of(dup_name), "t.toml:17: vehicle[0].receiver[1].name: 'gps1' is used twice on vehicle 'ego'");
  std::string dup_path = kTwoVehicles;
  dup_path.replace(dup_path.find("/wing/"), 6, "/ego/");
  EXPECT_EQ(error_of(dup_path), "t.toml:31: vehicle 'wing' receiver 'gps1' output 'a': path: '/tmp/gnssemu/ego/gps1' "
                                "is already used by vehicle 'ego' receiver 'gps1' output 'a'");
  EXPECT_EQ(error_of(kTwoVehicles + "[status]\nport = 4001\n"),
            "t.toml:24: vehicle 'ego' receiver 'gps2' output 'a': port: tcp port 4001 is already used by the status "
            "page");
}

TEST(VehicleKeys, TemplateCollisions) {
  const std::string fleet = kTop + "[fleet]\ncount = 2\n[[fleet.output]]\nname = \"a\"\n";  // name on line 12
  EXPECT_EQ(error_of(fleet + "path = \"/tmp/gnssemu/gps\"\n"),
            "t.toml:13: vehicle 'v1' receiver 'gps1' output 'a': path: '/tmp/gnssemu/gps' is already used by vehicle "
            "'v0' receiver 'gps1' output 'a'");
  EXPECT_EQ(error_of(fleet + "type = \"tcp\"\nport_base = 5000\n[[fleet.output]]\nname = \"b\"\ntype = \"tcp\"\n"
                             "port_base = 5001\n"),
            "t.toml:14: vehicle 'v1' receiver 'gps1' output 'a': port_base: tcp port 5001 is already used by vehicle "
            "'v0' receiver 'gps1' output 'b'");
  EXPECT_EQ(error_of(fleet + "path = \"/tmp/{vehicle}/{antenna}\"\n"),
            "t.toml:13: fleet.output[0].path: unknown placeholder '{antenna}' (known: {vehicle}, {receiver}, {index})");
  EXPECT_EQ(error_of(fleet + "type = \"udp\"\naddress = \"127.0.0.1\"\nport_base = 65535\n"),
            "t.toml:15: fleet.output[0].port_base: 65535 + 1 (the last vehicle's index) is above 65535");
  EXPECT_EQ(error_of(fleet + "type = \"udp\"\naddress = \"127.0.0.1\"\nport = 6000\n"),
            "t.toml:15: fleet.output[0].port: a template has port_base (vehicle index gets port_base + index)");
}

TEST(VehicleKeys, BadCountsKeysAndForms) {
  EXPECT_EQ(error_of(kTop + "[fleet]\ncount = 0\n"), "t.toml:10: fleet.count: 0 is out of range [1, 1000]");
  EXPECT_EQ(error_of(kTop + "[fleet]\ncount = 1001\n"), "t.toml:10: fleet.count: 1001 is out of range [1, 1000]");
  EXPECT_EQ(error_of(kTop + "[fleet]\n"), "t.toml:9: missing required key 'fleet.count' in [fleet]");
  EXPECT_EQ(error_of(kTop + "[[vehicle]]\nid = \"v1\"\n[[vehicle.receiver]]\nname = \"g\"\n[fleet]\ncount = 2\n"),
            "t.toml:14: fleet.count: the fleet's vehicle 'v1' is also a [[vehicle]] id");
  EXPECT_EQ(error_of(kTop + "[[vehicle]]\nid = \"ego\"\n[[vehicle.receiver]]\nname = \"g\"\nsede = 3\n"),
            "t.toml:13: unknown key 'vehicle[0].receiver[0].sede' (did you mean 'seed'?); a [[vehicle.receiver]] "
            "takes name, lever_arm_m, [[vehicle.receiver.output]] and the keys of [receiver]");
  EXPECT_EQ(error_of(kTop + "[[vehicle]]\nid = \"ego\"\n[[vehicle.receiver]]\nname = \"g\"\ntruth_port = 1\n"),
            "t.toml:13: unknown key 'vehicle[0].receiver[0].truth_port'; a [[vehicle.receiver]] takes name, lever_arm_m, "
            "[[vehicle.receiver.output]] and the keys of [receiver]");
  EXPECT_EQ(error_of(kTop + "[[vehicle]]\nid = \"ego\"\n"),
            "t.toml:9: missing required table 'vehicle[0].receiver' in [vehicle[0]]");
  EXPECT_EQ(error_of(kTop + "[[vehicle]]\nid = \"e/1\"\n[[vehicle.receiver]]\nname = \"g\"\n"),
            "t.toml:10: vehicle[0].id: 'e/1' may hold only letters, digits, '_', '-' and '.'");
  EXPECT_EQ(error_of(kTop + "[[vehicle]]\nid = \"e\"\n[[vehicle.receiver]]\nname = \"g\"\nlever_arm_m = [0, 0, 101]\n"),
            "t.toml:13: vehicle[0].receiver[0].lever_arm_m: components must be numbers within ±100 m");
  EXPECT_EQ(error_of(kTop + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\n[[vehicle]]\nid = \"e\"\n"
                            "[[vehicle.receiver]]\nname = \"g\"\n"),
            "t.toml:9: output: a top-level [[output]] is the single-vehicle form; with [[vehicle]] or [fleet] give the "
            "ports in [[vehicle.receiver.output]] or [[fleet.output]]");
  EXPECT_EQ(error_of(kTop + "[truth]\nvehicle = \"ego\"\n[fleet]\ncount = 2\n"),
            "t.toml:10: truth.vehicle: picks the vehicle of the single-vehicle form; [[vehicle]] and [fleet] name their "
            "own");
  const std::string bad_allow = error_of(kTop + "[[vehicle]]\nid = \"e\"\nallow = [\"10.0.0.1\", \"10.0.0.300\"]\n"
                                                "[[vehicle.receiver]]\nname = \"g\"\n");
  EXPECT_EQ(bad_allow.rfind("t.toml:11: vehicle[0].allow: ", 0), 0u) << bad_allow;
}

TEST(VehicleKeys, AllowIsPerVehicle) {
  const Config c = parse(kTop + "[[vehicle]]\nid = \"a\"\nallow = [\"127.0.0.1\", \"10.0.0.0/8\"]\n"
                                "[[vehicle.receiver]]\nname = \"g\"\n[[vehicle]]\nid = \"b\"\n"
                                "[[vehicle.receiver]]\nname = \"g\"\n");
  ASSERT_EQ(c.vehicles.size(), 2u);
  ASSERT_EQ(c.vehicles[0].allow.size(), 2u);
  EXPECT_EQ(c.vehicles[0].allow[1].text(), "10.0.0.0/8");
  EXPECT_TRUE(c.vehicles[1].allow.empty());
}

}  // namespace
}  // namespace gnssemu::config::test::vehicle_keys_test

// SPDX-License-Identifier: Apache-2.0
// StatusProducer: what /api/status and the control socket's status carry.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "daemon/status/status_producer.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::daemon {
namespace {

const Lla kSite{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};

receiver::Fix fix_at(double tow_s, const Enu& offset_m) {
  receiver::Fix f;
  f.t = time::GpsTime(2190, tow_s);
  f.time_valid = true;
  f.type = receiver::FixType::k3D;
  const Ecef truth = geo::ecef_from_lla(kSite);
  f.pos_m = Ecef(truth + geo::enu_to_ecef_vector(offset_m, kSite.lat_rad, kSite.lon_rad));
  f.lla = geo::lla_from_ecef(f.pos_m);
  f.h_acc_m = 1.5;
  f.v_acc_m = 2.5;
  f.dop.pdop = 1.4;
  f.num_used = 2;
  f.num_tracked = 3;
  f.num_visible = 4;
  f.num_sats = 5;
  auto sat = [](int prn, double az, double el) {
    receiver::SatInfo s;
    s.sat = SatId::gps(prn);
    s.az_rad = az * kDegToRad;
    s.el_rad = el * kDegToRad;
    s.healthy = true;
    s.above_mask = el >= 5.0;
    return s;
  };
  f.sats[0] = sat(1, 10, 60);
  f.sats[0].tracked = f.sats[0].used = true;
  f.sats[0].cn0_dbhz = 45.0;
  f.sats[1] = sat(2, 100, 30);
  f.sats[1].tracked = f.sats[1].used = f.sats[1].nlos = true;
  f.sats[1].cn0_dbhz = 33.0;
  f.sats[2] = sat(3, 200, 20);
  f.sats[2].tracked = f.sats[2].excluded = true;
  f.sats[2].cn0_dbhz = 40.0;
  f.sats[3] = sat(4, 300, 40);
  f.sats[3].blocked = true;
  f.sats[4] = sat(5, 50, 2);
  return f;
}

world::Truth truth_at(double tow_s) {
  world::Truth t;
  t.t = time::GpsTime(2190, tow_s);
  t.pos_m = geo::ecef_from_lla(kSite);
  t.valid = true;
  return t;
}

TEST(StatusProducer, JsonCarriesFixSatellitesErrorAndStates) {
  StatusProducer p(StatusSettings{10.0, 32.0, 26.0, 2.0, "lockstep"});
  p.set_ports({PortInfo{"gps0", "pty", "/tmp/gps0"}});
  const receiver::Fix f = fix_at(1000.0, Enu(3.0, 4.0, -2.0));
  const world::Truth t = truth_at(1000.0);
  p.on_epoch(EpochStatus{&f, &t, 0.0, 5.0, 1.25});
  std::string out;
  p.write_json(out);
  const nlohmann::json j = nlohmann::json::parse(out);
  EXPECT_EQ(j["fix"]["type"], 3);
  EXPECT_EQ(j["fix"]["type_name"], "3D");
  EXPECT_EQ(j["fix"]["num_used"], 2);
  EXPECT_NEAR(j["fix"]["ttff_s"].get<double>(), 1.25, 1e-9);
  EXPECT_NEAR(j["error"]["e_m"].get<double>(), 3.0, 1e-3);
  EXPECT_NEAR(j["error"]["n_m"].get<double>(), 4.0, 1e-3);
  EXPECT_NEAR(j["error"]["u_m"].get<double>(), -2.0, 1e-3);
  EXPECT_NEAR(j["error"]["h_m"].get<double>(), 5.0, 1e-3);
  EXPECT_EQ(j["settings"]["elevation_mask_deg"], 10.0);
  EXPECT_EQ(j["epoch"]["time_mode"], "lockstep");
  ASSERT_EQ(j["satellites"].size(), 5u);
  const char* states[] = {"used", "nlos", "excluded", "blocked", "below_mask"};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(j["satellites"][i]["state"], states[i]) << i;
  EXPECT_EQ(j["satellites"][0]["az_deg"], 10.0);
  EXPECT_EQ(j["satellites"][3]["cn0_dbhz"], 0.0);  // not tracked
  EXPECT_EQ(j["ports"][0]["name"], "gps0");
  EXPECT_TRUE(j["faults"].empty());
  EXPECT_EQ(j["history"]["t_s"].size(), 1u);
}

TEST(StatusProducer, NoFixOrNoTruthGivesNullErrorNotZero) {
  StatusProducer p(StatusSettings{});
  receiver::Fix f = fix_at(1000.0, Enu(1, 1, 1));
  world::Truth t = truth_at(1000.0);
  t.valid = false;
  p.on_epoch(EpochStatus{&f, &t, 0.0, 1.0, 0.0});
  f.type = receiver::FixType::kNone;
  t.valid = true;
  p.on_epoch(EpochStatus{&f, &t, 1.0, 2.0, 0.0});
  std::string out;
  p.write_json(out);
  const nlohmann::json j = nlohmann::json::parse(out);
  EXPECT_FALSE(j["error"]["valid"].get<bool>());
  EXPECT_TRUE(j["error"]["e_m"].is_null());
  EXPECT_TRUE(j["fix"]["lat_deg"].is_null());
  EXPECT_TRUE(j["fix"]["ttff_s"].is_null());
  EXPECT_TRUE(j["history"]["e_m"][0].is_null());
  EXPECT_TRUE(j["history"]["h_acc_m"][1].is_null());
  EXPECT_EQ(j["error"]["samples"], 0);
}

TEST(StatusProducer, CepFromTheHistoryAndHistoryBoundedNewestLast) {
  StatusProducer p(StatusSettings{});
  // Horizontal errors 1..100 m: CEP50 = 50 m, CEP95 = 95 m (nearest rank).
  for (int k = 1; k <= 100; ++k) {
    const receiver::Fix f = fix_at(1000.0 + k, Enu(k, 0.0, 0.0));
    const world::Truth t = truth_at(1000.0 + k);
    p.on_epoch(EpochStatus{&f, &t, static_cast<double>(k), 0.0, 0.0});
  }
  std::string out;
  p.write_json(out, 10);
  nlohmann::json j = nlohmann::json::parse(out);
  EXPECT_NEAR(j["error"]["cep50_m"].get<double>(), 50.0, 1e-3);
  EXPECT_NEAR(j["error"]["cep95_m"].get<double>(), 95.0, 1e-3);
  ASSERT_EQ(j["history"]["t_s"].size(), 10u);
  EXPECT_EQ(j["history"]["t_s"][9], 100.0);
  for (int k = 101; k <= 1000; ++k) {
    const receiver::Fix f = fix_at(1000.0 + k, Enu(1.0, 0.0, 0.0));
    const world::Truth t = truth_at(1000.0 + k);
    p.on_epoch(EpochStatus{&f, &t, static_cast<double>(k), 0.0, 0.0});
  }
  out.clear();
  p.write_json(out);
  j = nlohmann::json::parse(out);
  EXPECT_EQ(j["history"]["t_s"].size(), StatusProducer::kHistory);
  EXPECT_EQ(j["history"]["t_s"][0], 1000.0 - StatusProducer::kHistory + 1);
  EXPECT_NEAR(j["error"]["cep95_m"].get<double>(), 1.0, 1e-3);  // the old errors left the window
}

TEST(StatusProducer, DeadReckoningIsPlottedButNotInTheCep) {
  StatusProducer p(StatusSettings{});
  for (int k = 1; k <= 10; ++k) {
    receiver::Fix f = fix_at(1000.0 + k, Enu(k <= 5 ? 1.0 : 500.0, 0.0, 0.0));
    if (k > 5) f.type = receiver::FixType::kDeadReckoning;  // drifting on the filter alone
    const world::Truth t = truth_at(1000.0 + k);
    p.on_epoch(EpochStatus{&f, &t, static_cast<double>(k), 0.0, 0.0});
  }
  std::string out;
  p.write_json(out, 10);
  const nlohmann::json j = nlohmann::json::parse(out);
  EXPECT_EQ(j["error"]["samples"], 5);
  EXPECT_NEAR(j["error"]["cep95_m"].get<double>(), 1.0, 1e-3);
  EXPECT_NEAR(j["history"]["e_m"][9].get<double>(), 500.0, 1e-3);  // still drawn
}

TEST(StatusProducer, TruthAndPortRatesFromCounters) {
  StatusProducer p(StatusSettings{});
  p.set_ports({PortInfo{"ser", "serial", "/dev/ttyUSB0"}});
  for (int k = 0; k <= 4; ++k) {
    const receiver::Fix f = fix_at(1000.0 + k, Enu());
    const world::Truth t = truth_at(1000.0 + k);
    p.on_epoch(EpochStatus{&f, &t, static_cast<double>(k), 0.0, 0.0});
    TruthCounters tc;
    tc.packets_accepted = static_cast<uint64_t>(50 * k);
    tc.dropped[static_cast<std::size_t>(DropReason::kMalformedJson)] = 3;
    tc.simulator = tc.fresh = true;
    p.set_truth(tc);
    PortCounters pc;
    pc.protocols = "NMEA+UBX";
    pc.baud_bps = 9600;
    pc.bytes_offered = static_cast<uint64_t>(1200 * k);
    pc.tx_level_bytes = 1024;
    pc.tx_capacity_bytes = 4096;
    p.set_port_counters(0, pc);
  }
  std::string out;
  p.write_json(out);
  const nlohmann::json j = nlohmann::json::parse(out);
  EXPECT_NEAR(j["truth"]["rate_hz"].get<double>(), 50.0, 1e-6);
  EXPECT_EQ(j["truth"]["dropped"], 3);
  EXPECT_EQ(j["truth"]["source"], "simulator");
  EXPECT_EQ(j["truth"]["drops"].size(), 1u);
  EXPECT_NEAR(j["ports"][0]["bytes_per_s"].get<double>(), 1200.0, 1e-6);
  EXPECT_NEAR(j["ports"][0]["line_use"].get<double>(), 1.25, 1e-4);  // 1200 B/s on a 960 B/s line
  EXPECT_NEAR(j["ports"][0]["tx_fill"].get<double>(), 0.25, 1e-4);
  EXPECT_EQ(j["ports"][0]["protocols"], "NMEA+UBX");
  EXPECT_EQ(j["ports"][0]["link_bytes_lost"], 0);
}

TEST(StatusProducer, PortsCarryTheirLinkFaultCounters) {
  StatusProducer p(StatusSettings{});
  p.set_ports({PortInfo{"gps0", "pty", "/tmp/gps0"}, PortInfo{"net", "tcp", "127.0.0.1:2000"}});
  PortCounters pc;
  pc.bytes_written = 9500;
  pc.link_faults = LinkFaultStats{500, 1, 2, 3, 4, 5, 6, 7, 8};
  p.set_port_counters(1, pc);
  std::string out;
  p.write_json(out, 0);
  const nlohmann::json j = nlohmann::json::parse(out);
  const nlohmann::json& net = j["ports"][1];
  EXPECT_EQ(net["link_bytes_lost"], 500);
  EXPECT_EQ(net["link_messages_corrupted"], 1);
  EXPECT_EQ(net["link_messages_dropped"], 2);
  EXPECT_EQ(net["link_epochs_delayed"], 3);
  EXPECT_EQ(net["link_epochs_frozen"], 4);
  EXPECT_EQ(net["link_epochs_stopped"], 5);
  EXPECT_EQ(net["link_replies_stopped"], 6);
  EXPECT_EQ(net["link_epochs_skipped"], 7);
  EXPECT_EQ(net["link_epochs_wrong_fix"], 8);
  EXPECT_EQ(net["bytes_written"], 9500);  // the keys before them are unchanged
  EXPECT_EQ(j["ports"][0]["link_epochs_wrong_fix"], 0);
}

TEST(StatusProducer, FaultsAreCarriedAsAList) {
  StatusProducer p(StatusSettings{});
  FaultStatus a{"1", "jammer", "J/S 20 dB", 10.0, 70.0, true};
  FaultStatus b{"2", "outage", "antenna disconnected", 100.0, std::nan(""), false};
  const FaultStatus list[] = {a, b};
  p.set_faults(list);
  std::string out;
  p.write_json(out, 0);
  const nlohmann::json j = nlohmann::json::parse(out);
  ASSERT_EQ(j["faults"].size(), 2u);
  EXPECT_EQ(j["faults"][0]["type"], "jammer");
  EXPECT_TRUE(j["faults"][0]["active"].get<bool>());
  EXPECT_TRUE(j["faults"][1]["end_s"].is_null());
  EXPECT_TRUE(j["history"]["t_s"].empty());
}

TEST(StatusProducer, EpochAndSerialisationAllocateNothingAfterWarmUp) {
  StatusProducer p(StatusSettings{});
  p.set_ports({PortInfo{"gps0", "pty", "/tmp/gps0"}, PortInfo{"net", "tcp", "127.0.0.1:2000"}});
  std::string out;
  out.reserve(256 * 1024);
  auto epoch = [&](int k) {
    const receiver::Fix f = fix_at(1000.0 + k, Enu(0.1 * k, 0.0, 0.0));
    const world::Truth t = truth_at(1000.0 + k);
    p.on_epoch(EpochStatus{&f, &t, static_cast<double>(k), 0.0, 0.0});
    p.set_truth(TruthCounters{});
    p.set_port_counters(0, PortCounters{});
    p.set_port_counters(1, PortCounters{});
    out.clear();
    p.write_json(out);
  };
  for (int k = 0; k < 5; ++k) epoch(k);
  const long before = support::allocation_count();
  for (int k = 5; k < 700; ++k) epoch(k);
  EXPECT_EQ(support::allocation_count() - before, 0);
}

}  // namespace
}  // namespace gnssemu::daemon

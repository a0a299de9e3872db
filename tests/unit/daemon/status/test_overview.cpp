// SPDX-License-Identifier: Apache-2.0
// The fleet overview: each producer's row, the envelope, limit/offset, the
// whole fleet sorted before paging, the query's refusals, and no allocation
// once the string has capacity.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "daemon/status/overview.hpp"
#include "daemon/status/status_producer.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::daemon {
namespace {

const Lla kOverviewSite{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};

/// A 3D fix off_enu_m from a valid truth (default 3 m east and 4 m north:
/// h error 5 m), hAcc 1.5 m and 7 satellites used unless given.
void feed_fix(StatusProducer& p, receiver::CarrierSolution carrier, const Enu& off_enu_m = Enu(3.0, 4.0, 0.0),
              double h_acc_m = 1.5, int num_used = 7) {
  receiver::Fix f;
  f.t = time::GpsTime(2190, 1000.0);
  f.time_valid = true;
  f.type = receiver::FixType::k3D;
  f.carr_soln = carrier;
  f.diff_soln = carrier != receiver::CarrierSolution::kNone;
  const Ecef truth_pos = geo::ecef_from_lla(kOverviewSite);
  f.pos_m = Ecef(truth_pos + geo::enu_to_ecef_vector(off_enu_m, kOverviewSite.lat_rad, kOverviewSite.lon_rad));
  f.lla = geo::lla_from_ecef(f.pos_m);
  f.h_acc_m = h_acc_m;
  f.num_used = num_used;
  f.num_tracked = 9;
  f.num_visible = 11;
  world::Truth t;
  t.t = f.t;
  t.pos_m = truth_pos;
  t.valid = true;
  p.on_epoch(EpochStatus{&f, &t, 1.0, 1.0, 1.0});
}

/// No fix (antenna outage) and no truth.
void feed_nothing(StatusProducer& p) {
  receiver::Fix f;
  f.t = time::GpsTime(2190, 1000.0);
  f.num_visible = 10;
  world::Truth t;
  p.on_epoch(EpochStatus{&f, &t, 1.0, 1.0, 0.0});
}

nlohmann::json overview_json(const std::vector<OverviewEntry>& e, OverviewQuery q = {}) {
  std::string out;
  write_overview(out, e, q);
  return nlohmann::json::parse(out);
}

TEST(Overview, RowsCarryFixSatellitesErrorTruthFaultsAndPorts) {
  StatusProducer a(StatusSettings{});
  a.set_ports({PortInfo{"p0", "pty", "/tmp/p0"}, PortInfo{"p1", "udp", "127.0.0.1:9"}});
  feed_fix(a, receiver::CarrierSolution::kFixed);
  PortCounters c0, c1;
  c0.bytes_written = 1000;
  c0.epochs_dropped = 2;
  c1.bytes_written = 234;
  c1.messages_dropped = 5;
  a.set_port_counters(0, c0);
  a.set_port_counters(1, c1);
  TruthCounters tc;
  tc.simulator = tc.fresh = true;
  tc.age_s = 0.125;
  a.set_truth(tc);
  const FaultStatus faults[] = {{"1", "outage", "antenna", 0.0, 5.0, true},
                                {"2", "jammer", "J/S 20 dB", 50.0, std::nan(""), false}};
  a.set_faults(faults);

  StatusProducer b(StatusSettings{});
  feed_nothing(b);

  const nlohmann::json j = overview_json({{"v0", "gps1", &a}, {"v1", "gps2", &b}});
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["total"], 2);
  ASSERT_EQ(j["rows"].size(), 2u);
  const nlohmann::json& r = j["rows"][0];
  EXPECT_EQ(r["vehicle"], "v0");
  EXPECT_EQ(r["receiver"], "gps1");
  EXPECT_EQ(r["epochs"], 1);
  EXPECT_EQ(r["fix_type"], 3);
  EXPECT_EQ(r["fix_name"], "3D");
  EXPECT_EQ(r["carrier"], "fixed");
  EXPECT_EQ(r["diff"], true);
  EXPECT_EQ(r["num_used"], 7);
  EXPECT_EQ(r["num_tracked"], 9);
  EXPECT_EQ(r["num_visible"], 11);
  EXPECT_NEAR(r["h_err_m"].get<double>(), 5.0, 1e-3);
  EXPECT_NEAR(r["h_acc_m"].get<double>(), 1.5, 1e-9);
  EXPECT_NEAR(r["cep95_m"].get<double>(), 5.0, 1e-3);
  EXPECT_EQ(r["truth_source"], "simulator");
  EXPECT_EQ(r["truth_fresh"], true);
  EXPECT_NEAR(r["truth_age_s"].get<double>(), 0.125, 1e-9);
  EXPECT_EQ(r["faults_active"], 1);
  EXPECT_EQ(r["faults_scheduled"], 2);
  ASSERT_EQ(r["active_faults"].size(), 1u);
  EXPECT_EQ(r["active_faults"][0]["id"], "1");
  EXPECT_EQ(r["active_faults"][0]["type"], "outage");
  EXPECT_EQ(r["ports"], 2);
  EXPECT_EQ(r["bytes_written"], 1234);
  EXPECT_EQ(r["epochs_dropped"], 2);
  EXPECT_EQ(r["messages_dropped"], 5);

  // What does not exist is null, never 0.
  const nlohmann::json& n = j["rows"][1];
  EXPECT_EQ(n["fix_type"], 0);
  EXPECT_EQ(n["fix_name"], "none");
  EXPECT_EQ(n["carrier"], "none");
  EXPECT_EQ(n["num_visible"], 10);
  EXPECT_TRUE(n["h_err_m"].is_null());
  EXPECT_TRUE(n["h_acc_m"].is_null());
  EXPECT_TRUE(n["cep95_m"].is_null());
  EXPECT_EQ(n["truth_valid"], false);
  EXPECT_EQ(n["truth_source"], "none");
  EXPECT_TRUE(n["truth_age_s"].is_null());
  EXPECT_EQ(n["faults_active"], 0);
  EXPECT_TRUE(n["active_faults"].empty());
  EXPECT_EQ(n["ports"], 0);
}

TEST(Overview, LimitAndOffsetPickTheRowsTotalCountsAll) {
  std::vector<StatusProducer> producers(5, StatusProducer(StatusSettings{}));
  const std::vector<std::string> names = {"v0", "v1", "v2", "v3", "v4"};
  std::vector<OverviewEntry> e;
  for (std::size_t i = 0; i < producers.size(); ++i) e.push_back({names[i], "gps1", &producers[i]});
  const nlohmann::json j = overview_json(e, OverviewQuery{1, 2});
  EXPECT_EQ(j["total"], 5);
  EXPECT_EQ(j["offset"], 1);
  EXPECT_EQ(j["limit"], 2);
  ASSERT_EQ(j["rows"].size(), 2u);
  EXPECT_EQ(j["rows"][0]["vehicle"], "v1");
  EXPECT_EQ(j["rows"][1]["vehicle"], "v2");
  EXPECT_EQ(overview_json(e, OverviewQuery{4, 10})["rows"].size(), 1u);
  EXPECT_TRUE(overview_json(e, OverviewQuery{9, 10})["rows"].empty());
  EXPECT_TRUE(overview_json({})["rows"].empty());
}

TEST(Overview, ActiveFaultIdsAreBoundedTheCountIsNot) {
  StatusProducer p(StatusSettings{});
  std::vector<FaultStatus> faults;
  for (int i = 0; i < 20; ++i) faults.push_back({std::to_string(i + 1), "satellite", "", 0.0, 9.0, true});
  p.set_faults(faults);
  const nlohmann::json r = overview_json({{"v", "r", &p}})["rows"][0];
  EXPECT_EQ(r["faults_active"], 20);
  EXPECT_EQ(r["active_faults"].size(), kOverviewMaxFaultIds);
}

TEST(Overview, QueryParsesLimitAndOffset) {
  OverviewQuery q;
  EXPECT_EQ(parse_overview_query("", q), "");
  EXPECT_EQ(q.limit, kOverviewMaxRows);
  EXPECT_EQ(q.offset, 0u);
  EXPECT_EQ(parse_overview_query("limit=25&offset=100", q), "");
  EXPECT_EQ(q.limit, 25u);
  EXPECT_EQ(q.offset, 100u);
}

TEST(Overview, QueryRefusesUnknownKeysAndBadNumbers) {
  OverviewQuery q{7, 8};
  for (const char* bad : {"limit=0", "limit=1001", "limit=-1", "limit=abc", "limit=", "limit", "limit=5x",
                          "offset=-3", "offset=1.5", "limit=2&limit=3", "vehicle=a", "histroy=3"}) {
    const std::string why = parse_overview_query(bad, q);
    EXPECT_FALSE(why.empty()) << bad;
    EXPECT_EQ(q.offset, 7u) << bad << ": q changed on a refusal";
  }
  EXPECT_NE(parse_overview_query("vehicle=a", q).find("unknown query parameter 'vehicle'"), std::string::npos);
  EXPECT_NE(parse_overview_query("limit=0", q).find("[1, 1000]"), std::string::npos);
}

TEST(Overview, QueryParsesSortAndOrder) {
  OverviewQuery q;
  EXPECT_EQ(parse_overview_query("sort=herr&order=desc&limit=5", q), "");
  EXPECT_EQ(q.sort, OverviewSort::kHErr);
  EXPECT_TRUE(q.descending);
  EXPECT_EQ(q.limit, 5u);
  EXPECT_EQ(parse_overview_query("sort=name", q), "");
  EXPECT_EQ(q.sort, OverviewSort::kName);
  EXPECT_FALSE(q.descending);
  for (const char* bad : {"sort=speed", "sort=", "sort=herr&sort=name", "order=up", "order=asc&order=desc"}) {
    EXPECT_FALSE(parse_overview_query(bad, q).empty()) << bad;
  }
  EXPECT_NE(parse_overview_query("sort=speed", q).find("sort must be one of name, fix, sats, herr"), std::string::npos);
  EXPECT_NE(parse_overview_query("order=up", q).find("order must be asc or desc, not 'up'"), std::string::npos);
}

// The whole fleet is ordered before paging; no-fix rows (no error) go last
// in either order; names in natural order; ties keep the configuration's.
TEST(Overview, SortOrdersTheWholeFleetBeforePaging) {
  StatusProducer fixed(StatusSettings{}), lost(StatusSettings{}), far(StatusSettings{});
  feed_fix(fixed, receiver::CarrierSolution::kNone);  // 5 m
  feed_nothing(lost);                                 // no error
  feed_fix(far, receiver::CarrierSolution::kNone, Enu(30.0, 0.0, 0.0), 9.0, 4);  // 30 m
  const auto ids = [](const std::vector<OverviewEntry>& e) {
    std::string s;
    for (const OverviewEntry& x : e) s += std::string(x.vehicle) + "/" + std::string(x.receiver) + " ";
    return s;
  };
  std::vector<OverviewEntry> e{{"v10", "a", &lost}, {"v9", "a", &far}, {"v2", "b", &fixed}, {"v2", "a", &fixed}};
  OverviewQuery q;
  ASSERT_EQ(parse_overview_query("sort=herr", q), "");
  sort_overview(e, q);
  EXPECT_EQ(ids(e), "v2/b v2/a v9/a v10/a ");  // 5, 5 (configuration order), 30 m, none
  ASSERT_EQ(parse_overview_query("sort=herr&order=desc", q), "");
  sort_overview(e, q);
  EXPECT_EQ(ids(e), "v9/a v2/b v2/a v10/a ");  // no error still last
  ASSERT_EQ(parse_overview_query("sort=name", q), "");
  sort_overview(e, q);
  EXPECT_EQ(ids(e), "v2/a v2/b v9/a v10/a ");  // natural: v9 before v10
  ASSERT_EQ(parse_overview_query("sort=sats&order=desc&limit=2&offset=1", q), "");
  sort_overview(e, q);
  const nlohmann::json j = overview_json(e, q);  // 7, 7, 4, 0 used: rows 2-3 of the sorted fleet
  ASSERT_EQ(j["rows"].size(), 2u);
  EXPECT_EQ(j["rows"][0]["vehicle"], "v2");
  EXPECT_EQ(j["rows"][0]["receiver"], "b");
  EXPECT_EQ(j["rows"][1]["vehicle"], "v9");
  OverviewQuery config;
  std::vector<OverviewEntry> before = e;
  sort_overview(e, config);  // no sort: as given
  EXPECT_EQ(ids(e), ids(before));
}

TEST(Overview, SerialisingAllocatesNothingOnceTheStringHasCapacity) {
  StatusProducer p(StatusSettings{});
  p.set_ports({PortInfo{"p0", "pty", "/tmp/p0"}});
  feed_fix(p, receiver::CarrierSolution::kNone);
  const FaultStatus faults[] = {{"1", "outage", "antenna", 0.0, 5.0, true}};
  p.set_faults(faults);
  const std::vector<OverviewEntry> e(100, OverviewEntry{"v", "gps1", &p});
  std::string out;
  write_overview(out, e, {});
  out.reserve(out.size() * 2);
  out.clear();
  const long before = support::allocation_count();
  write_overview(out, e, {});
  EXPECT_EQ(support::allocation_count() - before, 0);
  EXPECT_EQ(nlohmann::json::parse(out)["rows"].size(), 100u);
}

}  // namespace
}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
// Scenario files (config/scenario_file): [[event]] tables into fault events;
// every error names file:line and the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "config/scenario_file.hpp"
#include "core/common/error.hpp"
#include "test_helpers.hpp"

namespace gnssemu::config::scenario_file_test {
namespace {

using faults::FaultType;
using faults::Param;

using test::expect_error;

std::vector<faults::FaultEvent> parse(const std::string& text) { return parse_scenario(text, "s.toml"); }

TEST(ScenarioFile, ReadsTheIssueExamples) {
  const auto ev = parse(R"(
[[event]]
type = "jammer"
start_s = 10
duration_s = 60
js_db = [0, 60]

[[event]]
type = "spoofer"
mode = "drag"
start_s = 100
drag_speed_m_s = 2.0
drag_heading_deg = 90
power_advantage_db = 6

[[event]]
type = "satellite"
start_s = 5
prn = 12
bias_m = 50

[[event]]
type = "outage"
start_s = 200
)");
  ASSERT_EQ(ev.size(), 4u);
  EXPECT_EQ(ev[0].type, FaultType::kJammer);
  EXPECT_EQ(ev[0].param(Param::kJsDb).to, 60.0);
  EXPECT_EQ(ev[0].duration_s, 60.0);
  EXPECT_EQ(ev[0].line, 2);
  EXPECT_EQ(ev[1].mode, static_cast<int>(faults::SpoofMode::kDrag));
  EXPECT_EQ(ev[1].value(Param::kDragSpeedMS, 0.0), 2.0);
  EXPECT_FALSE(std::isfinite(ev[1].duration_s));  // to the end
  EXPECT_EQ(ev[2].param(Param::kPrn).from, 12.0);
  EXPECT_EQ(ev[3].type, FaultType::kOutage);
  EXPECT_EQ(ev[3].mode, static_cast<int>(faults::OutageKind::kBlockage));
}

TEST(ScenarioFile, ErrorsNameTheLineAndTheReason) {
  expect_error([] { parse("[[event]]\nstart_s = 0\ntype = \"laser\"\n"); },
               {"s.toml:3", "unknown type 'laser'", "jammer, spoofer, outage, sky_block, satellite, port"});
  expect_error([] { parse("[[event]]\ntype = \"jammer\"\nstart_s = 0\njs_db = 10\nfoo = 1\n"); },
               {"s.toml:5", "unknown key 'foo' for type jammer", "js_db"});
  expect_error([] { parse("[[event]]\ntype = \"satellite\"\nstart_s = 0\nprn = 40\n"); },
               {"s.toml:4", "prn: 40 is out of range: not a satellite"});
  expect_error([] { parse("[[event]]\ntype = \"satellite\"\nstart_s = 0\nprn = \"I05\"\n"); },
               {"s.toml:4", "prn: unknown satellite 'I05'"});
  expect_error([] { parse("[[event]]\ntype = \"satellite\"\nstart_s = 0\nprn = \"R40\"\n"); },
               {"s.toml:4", "prn: unknown satellite 'R40'"});
  expect_error([] { parse("[[event]]\ntype = \"jammer\"\nstart_s = 0\njs_db = [0, 60]\n"); },
               {"s.toml:4", "js_db: a [from, to] ramp needs a finite duration_s"});
  expect_error([] { parse("[[event]]\ntype = \"spoofer\"\nstart_s = 0\nmode = \"warp\"\n"); },
               {"s.toml:4", "unknown value 'warp'", "drag, time_push, meacon, takeover"});
  expect_error([] { parse("[[event]]\ntype = \"satellite\"\nstart_s = 3\nbias_m = 5\n"); },
               {"s.toml:1", "prn is required"});
  expect_error([] { parse("[[event]]\ntype = \"outage\"\nstart_s = -1\n"); }, {"s.toml:3", "start_s: must be >= 0"});
  expect_error([] { parse("[[event]]\ntype = \"outage\"\nstart_s = 0\nduration_s = 0\n"); },
               {"s.toml:4", "duration_s: must be > 0"});
  expect_error([] { parse("[[event]]\nstart_s = 0\n"); }, {"s.toml:1", "type is required"});
  expect_error([] { parse("[[event]]\ntype = \"outage\"\n"); }, {"s.toml:1", "start_s is required"});
  expect_error([] { parse("[[event]]\ntype = \"satellite\"\nstart_s = 0\nprn = [3, 4]\nduration_s = 9\n"); },
               {"s.toml:4", "prn: cannot be ramped"});
  expect_error([] { parse("[[event]]\ntype = \"jammer\"\nstart_s = 0\njs_db = \"loud\"\n"); },
               {"s.toml:4", "expected a number"});
  expect_error([] { parse("[events]\n"); }, {"s.toml:1", "a scenario is a list of [[event]] tables"});
  expect_error([] { parse("[[event]\n"); }, {"s.toml:1", "TOML syntax error"});
}

TEST(ScenarioFile, SatellitesByNumberOrRinexName) {
  const auto ev = parse(R"([[event]]
type = "satellite"
start_s = 0
prn = "E11"

[[event]]
type = "satellite"
start_s = 0
prn = "G05"

[[event]]
type = "satellite"
start_s = 0
prn = 5
)");
  ASSERT_EQ(ev.size(), 3u);
  EXPECT_EQ(faults::sat_from_param(ev[0].param(Param::kPrn).from), SatId(GnssSystem::kGalileo, 11));
  EXPECT_EQ(faults::describe(ev[0], 0.0), "prn=E11");
  // A plain number is a GPS PRN, the same satellite as its RINEX name.
  EXPECT_EQ(ev[1].param(Param::kPrn).from, 5.0);
  EXPECT_EQ(ev[2].param(Param::kPrn).from, 5.0);
  EXPECT_EQ(faults::describe(ev[2], 0.0), "prn=5");
}

TEST(ScenarioFile, SpooferSystemsAndJammerBands) {
  const auto ev = parse(R"([[event]]
type = "spoofer"
start_s = 0
systems = "G,E"

[[event]]
type = "jammer"
start_s = 0
kind = "narrowband"
js_db = 30
freq_mhz = 1602.0
bandwidth_mhz = 1.0
)");
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].param(Param::kSystems).from,
            static_cast<double>(SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGalileo).bits()));
  EXPECT_EQ(faults::describe(ev[0], 0.0), "mode=drag systems=G,E");
  EXPECT_EQ(faults::describe(ev[1], 0.0), "kind=narrowband js_db=30 freq_mhz=1602 bandwidth_mhz=1");
  expect_error([] { parse("[[event]]\ntype = \"spoofer\"\nstart_s = 0\nsystems = \"G,X\"\n"); },
               {"s.toml:4", "systems: expected systems as RINEX letters"});
  expect_error([] { parse("[[event]]\ntype = \"spoofer\"\nstart_s = 0\nsystems = [\"G\", \"R\"]\n"); },
               {"s.toml:4", "systems: expected systems as RINEX letters"});
  expect_error([] { parse("[[event]]\ntype = \"jammer\"\nstart_s = 0\njs_db = 3\nfreq_mhz = 900\n"); },
               {"s.toml:5", "freq_mhz: 900 is out of range"});
}

// A rule across keys waits for the whole table: eirp_dbw comes before
// lat_deg in the table's order, and the pair is complete only after it.
TEST(ScenarioFile, PositionedJammerByLatLon) {
  const auto ev = parse(R"([[event]]
type = "jammer"
start_s = 0
eirp_dbw = -20
lat_deg = 48.87
lon_deg = 2.29
height_m = 100
gain_dbi = 0
)");
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].param(Param::kEirpDbw).from, -20.0);
  EXPECT_EQ(ev[0].param(Param::kLatDeg).from, 48.87);
  EXPECT_EQ(ev[0].param(Param::kLonDeg).from, 2.29);
  expect_error([] { parse("[[event]]\ntype = \"jammer\"\nstart_s = 0\neirp_dbw = -20\n"); },
               {"s.toml:4", "eirp_dbw: needs distance_m or lat_deg and lon_deg"});
  expect_error([] { parse("[[event]]\ntype = \"jammer\"\nstart_s = 0\neirp_dbw = -20\nlat_deg = 48\n"); },
               {"s.toml:5", "lat_deg: lat_deg and lon_deg go together"});
}

TEST(ScenarioFile, ShippedExamplesAreValid) {
  const std::filesystem::path dir = std::filesystem::path(GNSSEMU_SOURCE_DIR) / "config/examples/scenarios";
  int n = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().extension() != ".toml") continue;
    EXPECT_NO_THROW(read_scenario(f.path().string())) << f.path();
    ++n;
  }
  EXPECT_GE(n, 5);
  const auto every = read_scenario((dir / "every_type.toml").string());
  EXPECT_EQ(every.size(), 6u);
  EXPECT_EQ(every.back().type, FaultType::kPort);
}

TEST(ScenarioFile, MissingFileIsAnError) {
  expect_error([] { read_scenario("/nonexistent/s.toml"); }, {"/nonexistent/s.toml"});
}

}  // namespace
}  // namespace gnssemu::config::scenario_file_test

TEST(ScenarioFile, TargetsNameAVehicleOrOneReceiver) {
  const auto events = parse_targeted_scenario(
      "[[event]]\ntype = \"outage\"\nstart_s = 0\ntarget = \"v3\"\n"
      "[[event]]\ntype = \"outage\"\nstart_s = 1\ntarget = \"v3/gps2\"\n"
      "[[event]]\ntype = \"outage\"\nstart_s = 2\n",
      "s.toml");
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].target, "v3");
  EXPECT_EQ(events[1].target, "v3/gps2");
  EXPECT_EQ(events[2].target, "");
  EXPECT_TRUE(target_matches("v3", "v3", "gps1"));
  EXPECT_TRUE(target_matches("v3/gps2", "v3", "gps2"));
  EXPECT_FALSE(target_matches("v3/gps2", "v3", "gps1"));
  EXPECT_FALSE(target_matches("v3", "v30", "gps1"));
  expect_error([] { parse_targeted_scenario("[[event]]\ntype = \"outage\"\nstart_s = 0\ntarget = \"a/b/c\"\n", "s.toml"); },
               {"s.toml:4", "target"});
  expect_error([] { parse_targeted_scenario("[[event]]\ntype = \"outage\"\nstart_s = 0\ntarget = 3\n", "s.toml"); },
               {"s.toml:4"});
  // One receiver (gnssemu batch): a target picks nothing and is refused.
  expect_error([] { parse_scenario("[[event]]\ntype = \"outage\"\nstart_s = 0\ntarget = \"v3\"\n", "s.toml"); },
               {"s.toml:1", "target 'v3'"});
}

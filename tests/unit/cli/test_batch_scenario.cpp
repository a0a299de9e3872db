// SPDX-License-Identifier: Apache-2.0
// gnssemu batch --scenario: faults between world and receiver in the
// daemon's code path; byte-identical output for the same scenario, seed and
// truth; the receiver's own hAcc/vAcc beside the true error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "cli_test_util.hpp"

using namespace gnssemu;
using namespace gnssemu::cli::test;

namespace {

double col(const Csv& csv, std::size_t row, const std::string& name) {
  const std::string& v = csv.rows.at(row).at(static_cast<std::size_t>(csv.col(name)));
  return v.empty() ? NAN : std::stod(v);
}

TEST(BatchScenario, SameScenarioSeedAndTruthGiveTheSameBytes) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("truth.csv", static_truth(130.0));
  const std::string scen =
      std::string(GNSSEMU_SOURCE_DIR) + "/config/examples/scenarios/every_type.toml";
  std::string outs[2][3];
  for (auto& o : outs) {
    const std::string n = dir.file("o.nmea"), u = dir.file("o.ubx"), e = dir.file("o.csv");
    const CliResult r =
        run({"batch", "--config", cfg, "--truth", truth, "--scenario", scen, "--nmea", n, "--ubx", u, "--errors", e});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("port event not applied in batch"), std::string::npos) << r.err;
    o[0] = read_file(n);
    o[1] = read_file(u);
    o[2] = read_file(e);
  }
  for (int k = 0; k < 3; ++k) EXPECT_EQ(outs[0][k], outs[1][k]) << k;
  const CliResult plain = run({"batch", "--config", cfg, "--truth", truth, "--errors", "-"});
  EXPECT_NE(plain.out, outs[0][2]);  // the scenario did something
}

TEST(BatchScenario, DragOffIsFarOffWhileReportingMetres) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("truth.csv", static_truth(310.0));
  const std::string scen = dir.write("s.toml",
                                     "[[event]]\ntype = \"spoofer\"\nmode = \"drag\"\nstart_s = 10\n"
                                     "drag_speed_m_s = 2.0\ndrag_heading_deg = 90\npower_advantage_db = 6\n");
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth, "--scenario", scen, "--errors", "-"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv csv = parse_csv(r.out);
  ASSERT_EQ(csv.rows.size(), 311u);
  const std::size_t last = csv.rows.size() - 1;
  EXPECT_NEAR(col(csv, last, "e_m"), 600.0, 15.0);  // 2 m/s x 300 s
  EXPECT_LT(col(csv, last, "hacc_m"), 5.0);          // what it says about itself
  EXPECT_LT(col(csv, last, "vacc_m"), 8.0);
  EXPECT_EQ(col(csv, last, "fix_type"), 3.0);
}

TEST(BatchScenario, BadScenarioIsAnErrorWithItsLine) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("truth.csv", static_truth(10.0));
  const std::string scen = dir.write("s.toml", "[[event]]\ntype = \"jammer\"\nstart_s = 0\njs_db = 500\n");
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth, "--scenario", scen});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("s.toml:4"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("js_db: 500 is out of range"), std::string::npos) << r.err;
}

}  // namespace

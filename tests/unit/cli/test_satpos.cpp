// SPDX-License-Identifier: Apache-2.0
// gnssemu satpos against the independent reference (tests/data/reference,
// tools/reference/satpos_reference.py) and physical consistency checks.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <map>
#include <sstream>

#include "cli_test_util.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "tools/gnssemu/satpos.hpp"

using namespace gnssemu;
using namespace gnssemu::cli::test;

namespace {

struct RefCompare {
  int compared = 0;
  double max_pos_m = 0.0, max_vel_m_s = 0.0, max_clk_s = 0.0;
};

RefCompare compare_with_reference(const std::string& nav_name) {
  const std::string ref_path = std::string(GNSSEMU_TEST_DATA) + "/reference/satpos_" + nav_name + ".csv";
  const Csv ref = parse_csv(read_file(ref_path));
  EXPECT_GT(ref.rows.size(), 100u) << ref_path;
  const orbit::NavData nav = orbit::read_rinex_nav(nav_path(nav_name));
  const orbit::EphemerisStore store(nav.ephemerides);

  // Reference rows grouped by epoch, one satpos run per epoch.
  std::map<std::pair<int, std::string>, std::vector<std::size_t>> by_epoch;
  for (std::size_t i = 0; i < ref.rows.size(); ++i) {
    by_epoch[{std::stoi(ref.cell(i, "week")), ref.cell(i, "tow_s")}].push_back(i);
  }
  RefCompare rc;
  for (const auto& [epoch, rows] : by_epoch) {
    const time::GpsTime t(epoch.first, std::stod(epoch.second));
    std::ostringstream out;
    cli::write_satpos(store, t, out);
    const Csv ours = parse_csv(out.str());
    std::map<int, std::size_t> row_of_prn;
    for (std::size_t j = 0; j < ours.rows.size(); ++j) {
      if (ours.cell(j, "sat").front() == 'G') row_of_prn[std::stoi(ours.cell(j, "prn"))] = j;  // the reference is GPS
    }
    for (std::size_t i : rows) {
      const int prn = std::stoi(ref.cell(i, "prn"));
      const auto it = row_of_prn.find(prn);
      if (it == row_of_prn.end()) {
        ADD_FAILURE() << nav_name << " week " << epoch.first << " tow " << epoch.second << ": no row for G" << prn;
        continue;
      }
      const std::size_t j = it->second;
      const std::string where = nav_name + " G" + std::to_string(prn) + " tow " + epoch.second;
      EXPECT_EQ(ours.num(j, "toe_tow_s"), ref.num(i, "toe_tow_s")) << where;
      EXPECT_EQ(ours.cell(j, "iode"), ref.cell(i, "iode")) << where;
      double dp = 0.0, dv = 0.0;
      for (const char* c : {"x_m", "y_m", "z_m"}) dp = std::max(dp, std::fabs(ours.num(j, c) - ref.num(i, c)));
      for (const char* c : {"vx_m_s", "vy_m_s", "vz_m_s"}) dv = std::max(dv, std::fabs(ours.num(j, c) - ref.num(i, c)));
      const double dc = std::fabs(ours.num(j, "clk_bias_s") - ref.num(i, "clk_bias_s"));
      rc.max_pos_m = std::max(rc.max_pos_m, dp);
      rc.max_vel_m_s = std::max(rc.max_vel_m_s, dv);
      rc.max_clk_s = std::max(rc.max_clk_s, dc);
      ++rc.compared;
    }
  }
  return rc;
}

}  // namespace

class SatposReference : public ::testing::TestWithParam<const char*> {};

// Positions 0.1 mm (printed to 0.1 mm: rounding gives 5e-5), velocity 5e-6 m/s
// (analytic vs the reference's finite difference; 7e-7 seen), clock 1e-15 s
// (printed to 1e-15: rounding gives 5e-16).
TEST_P(SatposReference, MatchesIndependentImplementation) {
  const RefCompare rc = compare_with_reference(GetParam());
  EXPECT_GT(rc.compared, 300);
  EXPECT_LT(rc.max_pos_m, 1e-4);
  EXPECT_LT(rc.max_vel_m_s, 5e-6);
  EXPECT_LT(rc.max_clk_s, 1e-15);
  std::printf("%s: %d rows, max |dpos| %.2e m, |dvel| %.2e m/s, |dclk| %.2e s\n", GetParam(), rc.compared,
              rc.max_pos_m, rc.max_vel_m_s, rc.max_clk_s);
}

INSTANTIATE_TEST_SUITE_P(AllNavFiles, SatposReference,
                         ::testing::Values("brdc0010.22n", "ab422100.18n", "NYA100NOR_S_20241240000_01D_GN.rnx",
                                           "ELKO00USA_R_20182100000_01D_MN.rnx"),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                           std::string name = param_info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(Satpos, CommandLineEndToEnd) {
  const CliResult r = run({"satpos", "--nav", nav_path("brdc0010.22n"), "--week", "2190", "--tow", "521233.25"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "sat,prn,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,clk_bias_s,toe_tow_s,iode");
  const Csv csv = parse_csv(r.out);
  // 32 PRNs in the file, G11, G22 and G28 unhealthy (health 63) all day.
  ASSERT_EQ(csv.rows.size(), 29u);
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const int prn = std::stoi(csv.cell(i, "prn"));
    EXPECT_TRUE(prn != 11 && prn != 22 && prn != 28) << prn;
    const double r_m = std::sqrt(std::pow(csv.num(i, "x_m"), 2) + std::pow(csv.num(i, "y_m"), 2) +
                                 std::pow(csv.num(i, "z_m"), 2));
    EXPECT_NEAR(r_m, 26.56e6, 0.9e6) << prn;  // GPS orbit radius: a ~ 26 560 km, e < 0.03
    EXPECT_LT(std::fabs(csv.num(i, "clk_bias_s")), 1e-3) << prn;
  }
  // Spot value from the reference CSV (G01, first row).
  EXPECT_EQ(csv.cell(0, "prn"), "1");
  EXPECT_EQ(csv.cell(0, "sat"), "G01");
  EXPECT_NEAR(csv.num(0, "x_m"), 13341779.092132412, 1e-4);
  EXPECT_NEAR(csv.num(0, "clk_bias_s"), 0.00046910383386010831, 1e-15);
  EXPECT_EQ(csv.cell(0, "iode"), "39");
}

// Away from the switch between ephemerides (toe 446400 / 453600 switch at 450000).
TEST(Satpos, VelocityIsTheDerivativeOfPosition) {
  const std::string nav = nav_path("NYA100NOR_S_20241240000_01D_GN.rnx");
  const Csv a = parse_csv(run({"satpos", "--nav", nav, "--week", "2312", "--tow", "450999.5"}).out);
  const Csv b = parse_csv(run({"satpos", "--nav", nav, "--week", "2312", "--tow", "451000.5"}).out);
  const Csv m = parse_csv(run({"satpos", "--nav", nav, "--week", "2312", "--tow", "451000"}).out);
  ASSERT_EQ(a.rows.size(), m.rows.size());
  ASSERT_EQ(b.rows.size(), m.rows.size());
  ASSERT_GE(m.rows.size(), 20u);
  for (std::size_t i = 0; i < m.rows.size(); ++i) {
    for (const auto& [p, v] : {std::pair{"x_m", "vx_m_s"}, {"y_m", "vy_m_s"}, {"z_m", "vz_m_s"}}) {
      // Central difference over 1 s: truncation ~ |jerk|/24 ~ 1e-4 m/s.
      EXPECT_NEAR(b.num(i, p) - a.num(i, p), m.num(i, v), 1e-3) << m.cell(i, "prn") << " " << p;
    }
  }
}

// SPDX-License-Identifier: Apache-2.0
// gnssemu spp --preset rtklib: RTKLIB rnx2rtkp's single-point weights,
// models and residual test on the real NYA1 hour (the comparison with
// rnx2rtkp itself: integration.spp_vs_rtklib_preset).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cli_test_util.hpp"

using namespace gnssemu::cli::test;

namespace spp_preset_test {

namespace {

const std::string kObs = std::string(GNSSEMU_TEST_DATA) + "/obs/NYA100NOR_S_20241240000_90M_30S_MO.rnx";
const std::string kNav = nav_path("NYA100NOR_S_20241240000_01D_GN.rnx");
const std::string kStation = "1202434.1303,252632.2212,6237772.4351";

double mean_of(const Csv& c, const char* col) {
  double s = 0.0;
  for (std::size_t i = 0; i < c.rows.size(); ++i) s += c.num(i, col);
  return s / static_cast<double>(c.rows.size());
}

}  // namespace

TEST(SppPreset, RtklibPresetReproducesRnx2rtkpMeans) {
  const CliResult r = run({"spp", "--obs", kObs, "--nav", kNav, "--mask", "10", "--station", kStation, "--preset", "rtklib"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv c = parse_csv(r.out);
  ASSERT_EQ(c.rows.size(), 180u);
  // rnx2rtkp 2.4.3 b34 -p 0 (brdc iono, saas tropo, 10 deg) on the same
  // file: mean E -0.063, N -0.019, U -0.681 m against the header position
  // (docs/validation.md). The default weights give U -0.418 m.
  EXPECT_NEAR(mean_of(c, "e_m"), -0.063, 0.005);
  EXPECT_NEAR(mean_of(c, "n_m"), -0.019, 0.005);
  EXPECT_NEAR(mean_of(c, "u_m"), -0.681, 0.005);
}

TEST(SppPreset, OnlyTheSolverSettingsChange) {
  const CliResult own = run({"spp", "--obs", kObs, "--nav", kNav, "--mask", "10"});
  const CliResult rtk = run({"spp", "--obs", kObs, "--nav", kNav, "--mask", "10", "--preset", "rtklib"});
  ASSERT_EQ(own.status, 0) << own.err;
  ASSERT_EQ(rtk.status, 0) << rtk.err;
  const Csv a = parse_csv(own.out), b = parse_csv(rtk.out);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  std::vector<double> d;
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_EQ(a.cell(i, "tow_s"), b.cell(i, "tow_s"));
    EXPECT_EQ(a.cell(i, "nsat"), b.cell(i, "nsat"));  // same satellites, other weights
    d.push_back(std::hypot(std::hypot(a.num(i, "x_m") - b.num(i, "x_m"), a.num(i, "y_m") - b.num(i, "y_m")),
                           a.num(i, "z_m") - b.num(i, "z_m")));
  }
  std::sort(d.begin(), d.end());
  EXPECT_GT(d[d.size() / 2], 0.05);  // the weights matter ...
  EXPECT_LT(d.back(), 2.0);          // ... by decimetres
}

TEST(SppPreset, UnknownPresetIsAnError) {
  const CliResult r = run({"spp", "--obs", kObs, "--nav", kNav, "--preset", "rtk"});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("--preset"), std::string::npos) << r.err;
}

}  // namespace spp_preset_test

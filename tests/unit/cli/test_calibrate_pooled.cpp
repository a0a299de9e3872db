// SPDX-License-Identifier: Apache-2.0
// gnssemu calibrate on several station-days at once: --obs/--nav/--station
// once per day, one pooled fit, per-day SPP rows, a day column in the
// residuals; mismatched counts are an error.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "cli_test_util.hpp"

using namespace gnssemu::cli::test;

namespace {

const std::string kDay = std::string(GNSSEMU_TEST_DATA) + "/obs/NYA100NOR_S_20241240000_01D_30S_GO_L1.rnx.gz";
const std::string kHour = std::string(GNSSEMU_TEST_DATA) + "/obs/NYA100NOR_S_20241240000_90M_30S_MO.rnx";
const std::string kNav = nav_path("NYA100NOR_S_20241240000_01D_GN.rnx");
const std::string kStation = "1202434.1303,252632.2212,6237772.4351";

std::map<std::string, double> report(const CliResult& r) {
  const Csv csv = parse_csv(r.out);
  std::map<std::string, double> v;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) v[csv.cell(i, "parameter")] = csv.num(i, "value");
  return v;
}

}  // namespace

TEST(CalibratePooled, TwoStretchesGiveOneFitAndTwoSppRows) {
  TempDir dir;
  const CliResult r = run({"calibrate", "--obs", kDay, "--nav", kNav, "--station", kStation, "--obs", kHour, "--nav",
                           kNav, "--station", kStation, "--mask", "10", "--out", dir.file("pooled.toml"),
                           "--residuals", dir.file("res.csv")});
  ASSERT_EQ(r.status, 0) << r.err;
  std::map<std::string, double> v = report(r);
  EXPECT_EQ(v["epochs"], 2880 + 180);
  EXPECT_EQ(v["spp1_fixes"], 2880);
  EXPECT_EQ(v["spp2_fixes"], 180);
  EXPECT_EQ(v.count("spp_fixes"), 0u);
  // The hour is part of the day: its own SPP statistics are the hour's.
  EXPECT_LT(v["spp2_sigma_e"], v["spp1_sigma_e"]);
  const Csv res = parse_csv(read_file(dir.file("res.csv")));
  ASSERT_FALSE(res.rows.empty());
  EXPECT_EQ(res.cell(0, "day"), "1");
  EXPECT_EQ(res.cell(res.rows.size() - 1, "day"), "2");
  // A one-day fit has no day column and spp_ rows.
  const CliResult one = run({"calibrate", "--obs", kHour, "--nav", kNav, "--station", kStation, "--mask", "10",
                             "--out", dir.file("one.toml"), "--residuals", dir.file("one.csv")});
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_EQ(report(one)["spp_fixes"], 180);
  EXPECT_EQ(parse_csv(read_file(dir.file("one.csv"))).header.size(), 9u);  // tow_s,sat,prn,...,nmf_wet
}

TEST(CalibratePooled, EveryDayNeedsItsNavAndStation) {
  TempDir dir;
  const CliResult r = run({"calibrate", "--obs", kDay, "--obs", kHour, "--nav", kNav, "--station", kStation, "--out",
                           dir.file("x.toml")});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("2 --obs, 1 --nav and 1 --station"), std::string::npos) << r.err;
}

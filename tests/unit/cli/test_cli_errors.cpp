// SPDX-License-Identifier: Apache-2.0
// Every bad input: a clear message on stderr naming the culprit, nothing on
// stdout beyond what was already valid, and a non-zero exit status.
#include <gtest/gtest.h>

#include "cli_test_util.hpp"
#include "config/setup/nav_setup.hpp"
#include "core/common/error.hpp"

using namespace gnssemu;
using namespace gnssemu::cli;
using namespace gnssemu::cli::test;

namespace {

const std::vector<std::string> kGoodTime = {"--week", "2190", "--tow", "521233.25"};
const std::vector<std::string> kGoodSite = {"--lat", "48.8738", "--lon", "2.2950", "--height", "100"};

std::vector<std::string> cmd(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

void expect_fails(const CliResult& r, int status, const std::string& needle) {
  EXPECT_EQ(r.status, status) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
}

}  // namespace

TEST(CliErrors, NoSubcommandOrUnknownOne) {
  expect_fails(run({}), kExitUsage, "subcommand");
  expect_fails(run({"frobnicate"}), kExitUsage, "frobnicate");
}

TEST(CliErrors, HelpIsNotAnError) {
  const CliResult r = run({"--help"});
  EXPECT_EQ(r.status, kExitOk);
  EXPECT_NE(r.out.find("satpos"), std::string::npos);
  EXPECT_NE(r.out.find("batch"), std::string::npos);
}

TEST(CliErrors, MissingRequiredOption) {
  expect_fails(run({"satpos", "--nav", nav_path("brdc0010.22n"), "--week", "2190"}), kExitUsage, "--tow");
  expect_fails(run(cmd({"sky", "--nav", nav_path("brdc0010.22n")}, kGoodTime)), kExitUsage, "--lat");
  expect_fails(run({"batch", "--truth", "x.csv"}), kExitUsage, "--config");
}

TEST(CliErrors, MissingNavFile) {
  const CliResult r = run(cmd({"satpos", "--nav", "/nonexistent/brdc.22n"}, kGoodTime));
  expect_fails(r, kExitBadInput, "/nonexistent/brdc.22n");
  EXPECT_NE(r.err.find("not found"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(CliErrors, MalformedNavFileNamesFileAndLine) {
  TempDir dir;
  // A RINEX 2 header, then a record whose first line has a broken number.
  const std::string text =
      "     2.11           N: GPS NAV DATA                         RINEX VERSION / TYPE\n"
      "                                                            END OF HEADER\n"
      " 1 22  1  1  0  0  0.0 4.691039398313D-04-1.000444171950D-11 0.000000000000D+00\n"
      "    3.900000000000D+01-1.411250000000D+02 3.9xx787136096D-09 2.235409431520D+00\n";
  const std::string path = dir.write("bad.22n", text);
  const CliResult r = run(cmd({"satpos", "--nav", path}, kGoodTime));
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_NE(r.err.find(path + ":"), std::string::npos) << r.err;  // file:line from the orbit reader
  EXPECT_EQ(r.out, "");
}

TEST(CliErrors, BadNumbers) {
  const std::string nav = nav_path("brdc0010.22n");
  expect_fails(run({"satpos", "--nav", nav, "--week", "abc", "--tow", "0"}), kExitUsage, "--week");
  expect_fails(run({"satpos", "--nav", nav, "--week", "2190", "--tow", "12x"}), kExitUsage, "--tow");
  expect_fails(run({"satpos", "--nav", nav, "--week", "2190", "--tow", "604800"}), kExitBadInput, "--tow");
  expect_fails(run({"satpos", "--nav", nav, "--week", "2190", "--tow", "-1"}), kExitBadInput, "--tow");
  expect_fails(run({"satpos", "--nav", nav, "--week", "2190", "--tow", "nan"}), kExitBadInput, "--tow");
  expect_fails(run({"satpos", "--nav", nav, "--week", "-3", "--tow", "0"}), kExitBadInput, "--week");
  expect_fails(run(cmd({"sky", "--nav", nav, "--lat", "91", "--lon", "0", "--height", "0"}, kGoodTime)),
               kExitBadInput, "--lat");
  expect_fails(run(cmd({"sky", "--nav", nav, "--lat", "0", "--lon", "inf", "--height", "0"}, kGoodTime)),
               kExitBadInput, "--lon");
  expect_fails(run(cmd(cmd({"dop", "--nav", nav, "--mask", "90"}, kGoodTime), kGoodSite)), kExitBadInput, "--mask");
  expect_fails(run(cmd(cmd({"dop", "--nav", nav, "--mask", "-5"}, kGoodTime), kGoodSite)), kExitBadInput, "--mask");
}

TEST(CliErrors, TimeOutsideTheNavFile) {
  const CliResult r = run({"satpos", "--nav", nav_path("brdc0010.22n"), "--week", "2200", "--tow", "0"});
  expect_fails(r, kExitBadInput, "no healthy ephemeris valid at week 2200");
  EXPECT_NE(r.err.find("brdc0010.22n"), std::string::npos);
  EXPECT_EQ(r.out, "");
}

TEST(CliErrors, BatchMissingFiles) {
  TempDir dir;
  const std::string truth = dir.write("t.csv", "gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,520000,48,2,100\n");
  expect_fails(run({"batch", "--config", "/nonexistent/c.toml", "--truth", truth}), kExitBadInput,
               "/nonexistent/c.toml");
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  expect_fails(run({"batch", "--config", cfg, "--truth", dir.file("missing.csv")}), kExitBadInput, "missing.csv");
}

TEST(CliErrors, BatchBadConfigNamesFileAndLine) {
  TempDir dir;
  const std::string truth = dir.write("t.csv", "gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,520000,48,2,100\n");
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n"), "[receiver]\nrate_hz = -4.0\n"));
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth});
  expect_fails(r, kExitBadInput, cfg + ":10");
  EXPECT_NE(r.err.find("rate_hz"), std::string::npos) << r.err;
}

TEST(CliErrors, BatchMalformedTruthNamesFileLineAndColumn) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("t.csv",
                                      "gps_week,tow_s,lat_deg,lon_deg,height_m\n"
                                      "2190,520000,48.1,2.2,100\n"
                                      "2190,520001,48.1,two,100\n");
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth});
  expect_fails(r, kExitBadInput, truth + ":3: column 'lon_deg': 'two' is not a number");
}

// [nav] mode auto: truth outside the nav data runs on the data moved to its
// date, and says so; as_is refuses it, naming the data's coverage.
TEST(CliErrors, BatchTruthOutsideNavCoverage) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("t.csv", "gps_week,tow_s,x_m,y_m,z_m\n2100,0,4194423,162183,4780188\n");
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth});
  EXPECT_EQ(r.status, kExitOk) << r.err;
  EXPECT_NE(r.err.find("nav data moved -636 days"), std::string::npos) << r.err;
  config::Config c = config::load_config(cfg);
  c.nav.mode = orbit::NavMode::kAsIs;
  try {
    config::make_constellation(c, config::load_nav(c), time::GpsTime(2100, 0.0));
    ADD_FAILURE() << "as_is served a time outside its data";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("brdc0010.22n: start 2020-04-05 00:00:00 GPST lies outside the nav data "
                        "(2021-12-31 22:00:00 GPST to 2022-01-02 01:59:44 GPST)"),
              std::string::npos)
        << what;
  }
}

TEST(CliErrors, BatchUnwritableOutput) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("t.csv", "gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,520000,48,2,100\n");
  expect_fails(run({"batch", "--config", cfg, "--truth", truth, "--errors", "/nonexistent/dir/e.csv"}),
               kExitBadInput, "/nonexistent/dir/e.csv");
}

TEST(CliErrors, BatchBothOutputsOnStdout) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("t.csv", "gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,520000,48,2,100\n");
  expect_fails(run({"batch", "--config", cfg, "--truth", truth, "--nmea", "-", "--errors", "-"}), kExitBadInput,
               "cannot both be '-'");
}

TEST(CliErrors, NegativeNumbersAreValuesNotOptions) {
  const CliResult r = run({"sky", "--nav", nav_path("brdc0010.22n"), "--week", "2190", "--tow", "521233.25", "--lat",
                           "-33.9", "--lon", "-70.5", "--height", "-20.5"});
  EXPECT_EQ(r.status, kExitOk) << r.err;
  EXPECT_GT(parse_csv(r.out).rows.size(), 4u);
}

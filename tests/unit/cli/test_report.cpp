// SPDX-License-Identifier: Apache-2.0
// batch --sats and --report, and gnssemu plot: the columns others script
// against, the self-contained HTML, and file:line errors for bad input.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_test_util.hpp"
#include "tools/gnssemu/report/plot.hpp"

using namespace gnssemu;
using namespace gnssemu::cli::test;

namespace {

/// The JSON a report carries (the #report-data element).
nlohmann::json report_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"report-data\">";
  const std::size_t a = html.find(open);
  EXPECT_NE(a, std::string::npos);
  const std::size_t b = html.find("</script>", a);
  return nlohmann::json::parse(html.substr(a + open.size(), b - a - open.size()));
}

std::string excerpt() { return std::string(GNSSEMU_TEST_DATA) + "/receiver-logs/ublox-8-excerpt.log"; }

TEST(BatchSats, ExactColumnsOneRowPerEpochAndSatelliteAgreeingWithErrors) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("t.csv", static_truth(60.0));
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth, "--sats", dir.file("s.csv"), "--errors",
                           dir.file("e.csv")});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text = read_file(dir.file("s.csv"));
  EXPECT_EQ(text.substr(0, text.find('\n')), "gps_week,tow_s,sat,prn,az_deg,el_deg,cn0_dbhz,tracked,used");
  const Csv sats = parse_csv(text);
  const Csv errors = parse_csv(read_file(dir.file("e.csv")));
  ASSERT_EQ(errors.rows.size(), 61u);
  std::map<std::string, int> used_per_epoch;
  std::set<std::string> epochs;
  for (std::size_t i = 0; i < sats.rows.size(); ++i) {
    const std::string tow = sats.cell(i, "tow_s");
    epochs.insert(tow);
    const double el = sats.num(i, "el_deg"), az = sats.num(i, "az_deg"), cn0 = sats.num(i, "cn0_dbhz");
    EXPECT_GE(el, 0.0);
    EXPECT_LE(el, 90.0);
    EXPECT_GE(az, 0.0);
    EXPECT_LT(az, 360.0);
    const int tracked = std::stoi(sats.cell(i, "tracked")), used = std::stoi(sats.cell(i, "used"));
    EXPECT_TRUE(tracked == 0 || tracked == 1);
    EXPECT_LE(used, tracked);
    EXPECT_EQ(cn0 > 0.0, tracked == 1) << "C/N0 only for tracked satellites";
    used_per_epoch[tow] += used;
  }
  EXPECT_EQ(epochs.size(), 61u);
  for (std::size_t i = 0; i < errors.rows.size(); ++i) {
    EXPECT_EQ(used_per_epoch[errors.cell(i, "tow_s")], std::stoi(errors.cell(i, "nsat"))) << errors.cell(i, "tow_s");
  }
}

TEST(BatchReport, SelfContainedHtmlWithTheRunsStatisticsAndAReference) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("t.csv", static_truth(120.0));
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth, "--report", dir.file("rep"), "--cn0-reference",
                           excerpt()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("mean |diff|"), std::string::npos) << r.err;
  const std::string html = read_file(dir.file("rep/report.html"));
  EXPECT_NE(html.find("Chart.js v3"), std::string::npos);       // the library is inlined
  EXPECT_NE(html.find("const GnssCharts"), std::string::npos);  // and the chart code
  EXPECT_EQ(html.find("<script src="), std::string::npos);      // nothing loaded from elsewhere
  const nlohmann::json d = report_data(html);
  EXPECT_EQ(d["summary"]["epochs"], 121);
  EXPECT_EQ(d["summary"]["fixes"], 120);  // a hot start: the first epoch acquires (1 s TTFF)
  EXPECT_GT(d["summary"]["cep95_m"].get<double>(), d["summary"]["cep50_m"].get<double>());
  EXPECT_EQ(d["epochs"]["t_s"].size(), 121u);
  EXPECT_EQ(d["epochs"]["t_s"][120], 120.0);
  EXPECT_FALSE(d["sky"]["prn"].empty());
  ASSERT_EQ(d["sky"]["sat"].size(), d["sky"]["prn"].size());
  EXPECT_EQ(d["sky"]["sat"][0].get<std::string>().substr(0, 1), "G");
  EXPECT_EQ(d["reference"]["source"], "ublox-8-excerpt.log");
  EXPECT_GT(d["reference"]["samples"].get<int>(), 100);
  EXPECT_EQ(d["elevation_mask_deg"], 5.0);
  const auto& cdf = d["cdf"]["p"];
  ASSERT_FALSE(cdf.empty());
  EXPECT_DOUBLE_EQ(cdf.back().get<double>(), 1.0);
}

TEST(Plot, ReportFromTheCsvsOfARunMatchesTheBatchReport) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("t.csv", static_truth(30.0));
  ASSERT_EQ(run({"batch", "--config", cfg, "--truth", truth, "--sats", dir.file("s.csv"), "--errors", dir.file("e.csv"),
                 "--report", dir.file("a")})
                .status,
            0);
  const CliResult r = run({"plot", "--errors", dir.file("e.csv"), "--sats", dir.file("s.csv"), "--mask", "5", "--out",
                           dir.file("b")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("report.html"), std::string::npos);
  const nlohmann::json a = report_data(read_file(dir.file("a/report.html")));
  const nlohmann::json b = report_data(read_file(dir.file("b/report.html")));
  // The errors CSV keeps 0.1 mm, the report 1 mm: equal to within rounding.
  auto near = [](const nlohmann::json& x, const nlohmann::json& y) {
    ASSERT_EQ(x.size(), y.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      ASSERT_EQ(x[i].is_null(), y[i].is_null()) << i;  // null: no fix at that epoch
      if (!x[i].is_null()) {
        EXPECT_NEAR(x[i].get<double>(), y[i].get<double>(), 1.5e-3) << i;
      }
    }
  };
  for (const char* k : {"epochs", "fixes", "fixes_3d", "error_samples"}) EXPECT_EQ(a["summary"][k], b["summary"][k]);
  for (const char* k : {"cep50_m", "cep95_m", "h_rms_m", "v95_m"}) {
    EXPECT_NEAR(a["summary"][k].get<double>(), b["summary"][k].get<double>(), 1.5e-3) << k;
  }
  near(a["epochs"]["e_m"], b["epochs"]["e_m"]);
  near(a["epochs"]["u_m"], b["epochs"]["u_m"]);
  EXPECT_EQ(a["sky"]["prn"], b["sky"]["prn"]);
  EXPECT_EQ(a["sky"]["state"], b["sky"]["state"]);
  EXPECT_EQ(a["epochs"]["tracked"], b["epochs"]["tracked"]);
}

TEST(Plot, DeadReckoningIsNotCountedAsAFix) {
  TempDir dir;
  const std::string e = dir.write("e.csv",
                                  "gps_week,tow_s,fix_type,nsat,e_m,n_m,u_m,hdop,vdop,pdop,hacc_m,vacc_m\n"
                                  "2190,1,3,8,1.0,0.0,1.0,1,1,1,2,3\n"
                                  "2190,2,3,8,2.0,0.0,1.0,1,1,1,2,3\n"
                                  "2190,3,1,0,400.0,0.0,9.0,,,,20,30\n"
                                  // batch's row for a fix while the truth is missing: no error columns
                                  "2190,4,3,8,,,,1,1,1,2,3\n");
  const CliResult r = run({"plot", "--errors", e, "--out", dir.file("p")});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json d = report_data(read_file(dir.file("p/report.html")));
  EXPECT_EQ(d["summary"]["fixes"], 3);
  EXPECT_EQ(d["summary"]["error_samples"], 2);
  EXPECT_NEAR(d["summary"]["h_max_m"].get<double>(), 2.0, 1e-9);
}

TEST(Plot, BenchMultipathCsvGivesTimeAgainstError) {
  TempDir dir;
  const std::string mp = dir.write(
      "mp.csv",
      "azimuth_rays,rays,max_bounces,reuse_m,reuse_deg,us_per_epoch_mean,us_per_epoch_p95,us_per_epoch_max,"
      "rays_per_epoch,misclassified,misclassified_pct,nlos_delay_err_rms_m,nlos_delay_err_max_m,pos_err_rms_m,"
      "pos_err_max_m\n"
      "0,256,16,0,0,106,193,264,352,178,2.10,5.88,111.6,12.48,81.2\n"
      "128,0,16,1,1,808,1059,1173,3057,80,1.00,18.84,403.1,19.44,212.3\n");
  const CliResult r = run({"plot", "--multipath", mp, "--out", dir.file("m")});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json d = report_data(read_file(dir.file("m/report.html")));
  ASSERT_EQ(d["multipath"].size(), 2u);
  EXPECT_EQ(d["multipath"][0]["label"], "hemisphere 256, 16 bounces");
  EXPECT_EQ(d["multipath"][1]["label"], "cone 128, 16 bounces, reuse 1 m / 1°");
  EXPECT_EQ(d["multipath"][1]["us_mean"], 808.0);
  EXPECT_EQ(d["multipath"][1]["pos_err_rms_m"], 19.44);
}

TEST(Plot, ReferenceFromARealReceiversGsvSkipsUntrackedAndSbas) {
  const cli::Cn0Reference ref = cli::read_cn0_reference(excerpt());
  // 10 epochs of a MAX-M8Q: per epoch up to 12 GPS satellites with C/N0 (PRN 2 has none; 46, 48, 51 are SBAS).
  EXPECT_GE(ref.el_deg.size(), 100u);
  EXPECT_LE(ref.el_deg.size(), 130u);
  EXPECT_EQ(ref.el_deg[0], 21.0);  // PRN 3 of the first GSV
  EXPECT_EQ(ref.cn0_dbhz[0], 29.0);
  TempDir dir;
  const cli::Cn0Reference csv = cli::read_cn0_reference(dir.write("r.csv", "el_deg,cn0_dbhz\n10,35\n80,48.5\n"));
  ASSERT_EQ(csv.el_deg.size(), 2u);
  EXPECT_EQ(csv.cn0_dbhz[1], 48.5);
}

TEST(Plot, BadInputIsAnErrorNamingFileAndLine) {
  TempDir dir;
  const std::string sats = dir.write("s.csv", "gps_week,tow_s,prn,az_deg,el_deg,cn0_dbhz,tracked,used\n"
                                              "2190,1.0,5,10,20,40,1,1\n2190,1.0,40,10,20,40,1,1\n");
  CliResult r = run({"plot", "--sats", sats, "--out", dir.file("o")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("s.csv:3: column 'prn'"), std::string::npos) << r.err;
  const std::string bad_sat = dir.write("b.csv", "gps_week,tow_s,sat,prn,az_deg,el_deg,cn0_dbhz,tracked,used\n"
                                                 "2190,1.0,E11,11,10,20,40,1,1\n2190,1.0,X05,5,10,20,40,1,1\n");
  r = run({"plot", "--sats", bad_sat, "--out", dir.file("o")});
  EXPECT_NE(r.err.find("b.csv:3: column 'sat': 'X05' is not a satellite"), std::string::npos) << r.err;
  const std::string short_row = dir.write("e.csv", "gps_week,tow_s,fix_type,nsat,e_m,n_m,u_m,hdop,vdop,pdop\n2190,1,3\n");
  r = run({"plot", "--errors", short_row, "--out", dir.file("o")});
  EXPECT_NE(r.err.find("e.csv:2: 3 fields, the header has 10"), std::string::npos) << r.err;
  const std::string half = dir.write("h.csv", "gps_week,tow_s,fix_type,nsat,e_m,n_m,u_m,hdop,vdop,pdop\n"
                                              "2190,1,3,8,1.0,,2.0,1,1,1\n");
  r = run({"plot", "--errors", half, "--out", dir.file("o")});
  EXPECT_NE(r.err.find("h.csv:2: e_m, n_m, u_m must be all given or all empty"), std::string::npos) << r.err;
  const std::string no_col = dir.write("n.csv", "gps_week,tow_s\n2190,1\n");
  r = run({"plot", "--errors", no_col, "--out", dir.file("o")});
  EXPECT_NE(r.err.find("n.csv:1: no column 'fix_type'"), std::string::npos) << r.err;
  const std::string used_untracked = dir.write("u.csv", "gps_week,tow_s,prn,az_deg,el_deg,cn0_dbhz,tracked,used\n"
                                                        "2190,1.0,5,10,20,0,0,1\n");
  r = run({"plot", "--sats", used_untracked, "--out", dir.file("o")});
  EXPECT_NE(r.err.find("u.csv:2: used but not tracked"), std::string::npos) << r.err;
  const std::string nothing = dir.write("x.log", "# a comment\nhello\n");
  r = run({"plot", "--sats", sats, "--cn0-reference", nothing, "--out", dir.file("o")});
  EXPECT_NE(r.status, 0);
  r = run({"plot", "--out", dir.file("o")});
  EXPECT_NE(r.err.find("give --errors, --sats and/or --multipath"), std::string::npos) << r.err;
  r = run({"batch", "--config", "c", "--truth", "t", "--cn0-reference", nothing});
  EXPECT_NE(r.err.find("--cn0-reference needs --report DIR"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("o/report.html")));
}

}  // namespace

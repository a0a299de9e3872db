// SPDX-License-Identifier: Apache-2.0
// tools/gnssemu/bench_multipath: the multipath benchmark's sweep and its figures.
#include <gtest/gtest.h>

#include "cli_test_util.hpp"
#include "tools/gnssemu/bench_multipath.hpp"

namespace gnssemu::cli {
namespace {

using test::Csv;
using test::nav_path;
using test::parse_csv;
using test::run;
using test::TempDir;

const std::string kScenes = std::string(GNSSEMU_TEST_DATA) + "/scenes/";

TEST(BenchMultipath, MeanP95AndMaxComeFromTheSameMedianRepeat) {
  EXPECT_EQ(median_repeat({5.0, 1.0, 3.0}), 2u);
  EXPECT_EQ(median_repeat({4.0, 2.0}), 1u);  // lower median
  EXPECT_EQ(median_repeat({7.0}), 0u);
  const test::CliResult r =
      run({"bench", "multipath", "--scene", kScenes + "street_canyon.toml", "--origin", "48.8738,2.2950,100",
           "--nav", nav_path("brdc0010.22n"), "--week", "2190", "--tow", "561600", "--path=3,-100,3,100", "--speed",
           "20", "--repeats", "3", "--reference-rays", "8192", "--settings", "128,0,16,0,0,0,256,4,2,1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("of 3 repeat(s) per setting the median one by mean gives mean, p95 and max"),
            std::string::npos)
      << r.err;
  const Csv c = parse_csv(r.out);
  ASSERT_EQ(c.rows.size(), 2u);
  EXPECT_EQ(c.num(0, "azimuth_rays"), 128.0);
  EXPECT_EQ(c.num(1, "rays"), 256.0);
  EXPECT_EQ(c.num(1, "max_bounces"), 4.0);
  EXPECT_EQ(c.num(1, "reuse_m"), 2.0);
  for (std::size_t i = 0; i < 2; ++i) {
    // One repeat's figures: its mean cannot exceed its own max.
    EXPECT_LE(c.num(i, "us_per_epoch_mean"), c.num(i, "us_per_epoch_max") + 0.05);
    EXPECT_LE(c.num(i, "us_per_epoch_p95"), c.num(i, "us_per_epoch_max"));
  }
  const test::CliResult bad = run({"bench", "multipath", "--scene", kScenes + "street_canyon.toml", "--origin",
                                   "48.8738,2.2950,100", "--nav", nav_path("brdc0010.22n"), "--path=3,-100,3,100",
                                   "--settings", "128,0,16"});
  EXPECT_EQ(bad.status, kExitBadInput);
  EXPECT_NE(bad.err.find("groups of 5"), std::string::npos) << bad.err;
}

TEST(BenchMultipath, PrintsTheSweep) {
  TempDir dir;
  const test::CliResult r =
      run({"bench", "multipath", "--scene", kScenes + "street_canyon.toml", "--origin", "48.8738,2.2950,100",
           "--nav", nav_path("brdc0010.22n"), "--week", "2190", "--tow", "561600", "--path=3,-100,3,100", "--speed",
           "20", "--repeats", "1", "--reference-rays", "8192"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("reference (4096 per satellite"), std::string::npos) << r.err;
  const Csv c = parse_csv(r.out);
  ASSERT_EQ(c.rows.size(), 20u);
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    EXPECT_GE(c.num(i, "misclassified_pct"), 0.0);
    EXPECT_GT(c.num(i, "rays_per_epoch"), 0.0);
    // A straight two-wall canyon: at full depth every setting with >= 128
    // cone rays or >= 256 hemisphere rays finds the reference paths, with
    // exact delays; shallower searches miss the deep ones.
    if ((c.num(i, "azimuth_rays") >= 128 || c.num(i, "rays") >= 256) && c.num(i, "max_bounces") == 16) {
      EXPECT_EQ(c.num(i, "misclassified"), 0.0) << i;
      EXPECT_LT(c.num(i, "nlos_delay_err_max_m"), 1e-3) << i;
      EXPECT_LT(c.num(i, "pos_err_max_m"), 1e-3) << i;
    }
    if (c.num(i, "max_bounces") == 2) {
      EXPECT_GT(c.num(i, "misclassified"), 0.0) << i;
    }
  }
  const test::CliResult bad = run({"bench", "multipath", "--origin", "48.8,2.3,100", "--nav",
                                   nav_path("brdc0010.22n"), "--path=0,0,1,1"});
  EXPECT_EQ(bad.status, kExitBadInput);
  EXPECT_NE(bad.err.find("--scene or --city"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace gnssemu::cli

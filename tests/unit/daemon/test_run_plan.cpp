// SPDX-License-Identifier: Apache-2.0
// What gnssemud runs on: the epoch clock's start and the satellites for it,
// decided (and refused) before any port opens (--check-config does the same).
#include <gtest/gtest.h>

#include <algorithm>

#include "config/config.hpp"
#include "config/setup/nav_setup.hpp"
#include "core/common/error.hpp"
#include "daemon/run_plan.hpp"

using namespace gnssemu;

namespace run_plan_test {

namespace {

const std::string kNav = std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n";
const time::GpsTime kToday(2446, 210807.4);  // 2026-11-24 10:33:27.4 GPST

config::Config base() {
  return config::parse_config("[origin]\nlat_deg = 48.8738\nlon_deg = 2.295\nheight_m = 100\n[nav]\nfile = \"" + kNav +
                                  "\"\n",
                              "t.toml", "/");
}

}  // namespace

TEST(RunPlan, DefaultIsTodayWithTheDataMovedToIt) {
  const config::Config c = base();
  EXPECT_TRUE(c.time.use_wall_clock_date);  // no [time] at all: today
  const daemon::RunPlan p = daemon::plan_run(c, config::load_nav(c), kToday);
  EXPECT_EQ(p.start, time::GpsTime(2446, 210808.0));  // next whole GPS second
  EXPECT_EQ(p.constellation.mode, orbit::NavMode::kRelabel);
  EXPECT_EQ(p.constellation.shift_s, 1788.0 * 86400.0);
}

TEST(RunPlan, ConfiguredStartInsideTheDataUsesThemAsTheyAre) {
  const config::Config c = config::parse_config("[origin]\nlat_deg = 48.8738\nlon_deg = 2.295\nheight_m = 100\n[nav]\n"
                                                "file = \"" + kNav + "\"\n[time]\nstart = \"2022-01-01T10:00:00\"\n",
                                                "t.toml", "/");
  EXPECT_FALSE(c.time.use_wall_clock_date);  // a start without the key: the start's date
  const daemon::RunPlan p = daemon::plan_run(c, config::load_nav(c), kToday);
  EXPECT_EQ(p.start, time::GpsTime::from_calendar({2022, 1, 1, 10, 0, 0.0}));
  EXPECT_EQ(p.constellation.mode, orbit::NavMode::kAsIs);
  EXPECT_EQ(p.constellation.nav.leap_seconds, 18);
}

// Issue 12: use_wall_clock_date with a 2022 nav file gave "configuration OK"
// and then no fix forever. Now: as_is says why, naming the coverage; the
// default (auto) moves the data to today.
TEST(RunPlan, AsIsStartOutsideTheDataIsRefused) {
  config::Config c = base();
  c.nav.mode = orbit::NavMode::kAsIs;
  try {
    (void)daemon::plan_run(c, config::load_nav(c), kToday);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("start 2026-11-24 10:33:28 GPST lies outside the nav data "
                                         "(2021-12-31 22:00:00 GPST to 2022-01-02 01:59:44 GPST)"),
              std::string::npos)
        << e.what();
  }
  c.nav.mode = orbit::NavMode::kAlmanac;  // no almanac file given
  EXPECT_THROW((void)daemon::plan_run(c, config::load_nav(c), kToday), Error);
  c.nav.almanac_file = std::string(GNSSEMU_TEST_DATA) + "/almanac/sem_week862_toa319488.al3";
  EXPECT_EQ(daemon::plan_run(c, config::load_nav(c), kToday).constellation.mode, orbit::NavMode::kAlmanac);
}

TEST(RunPlan, NavFolderAndFiles) {
  config::Config c = base();
  c.nav_file.clear();
  c.nav.folder = std::string(GNSSEMU_TEST_DATA) + "/nav";
  const std::vector<std::string> paths = config::nav_paths(c);
  // brdc0010.22n, ab422100.18n, NYA1 x2, ELKO: nav file names only (not SYNT..._MN_v305.rnx).
  EXPECT_EQ(paths.size(), 5u);
  EXPECT_TRUE(std::is_sorted(paths.begin(), paths.end()));
  EXPECT_TRUE(config::is_nav_file_name("brdc0010.22n.gz"));
  EXPECT_TRUE(config::is_nav_file_name("ESBC00DNK_R_20201770000_01D_MN.rnx.gz"));
  EXPECT_FALSE(config::is_nav_file_name("NYA100NOR_S_20241240000_90M_30S_MO.rnx"));
  EXPECT_FALSE(config::is_nav_file_name("LARM0010.22O"));
  c.nav.folder = std::string(GNSSEMU_TEST_DATA) + "/obs";
  EXPECT_THROW((void)config::nav_paths(c), Error);
}

}  // namespace run_plan_test

// SPDX-License-Identifier: Apache-2.0
// --nav repeated (one ephemeris store) and --nav-mode on satpos, sky and dop.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "cli_test_util.hpp"
#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/constellation.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/world/sky/sky.hpp"
#include "tools/gnssemu/sky.hpp"

using namespace gnssemu;
using namespace gnssemu::cli;
using namespace gnssemu::cli::test;

namespace {

const std::string kNya3 = nav_path("NYA100NOR_S_20241240000_01D_GN.rnx");  // 2024-05-03
const std::string kNya6 = nav_path("NYA100NOR_S_20241270000_01D_GN.rnx");  // 2024-05-06
const std::vector<std::string> kNyaSite = {"--lat", "78.93", "--lon", "11.87", "--height", "80"};

std::string fmt_tow(double tow_s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", tow_s);
  return buf;
}

std::vector<std::string> at(std::vector<std::string> head, const time::GpsTime& t,
                            const std::vector<std::string>& site) {
  head.insert(head.end(), {"--week", std::to_string(t.week()), "--tow", fmt_tow(t.tow_s())});
  head.insert(head.end(), site.begin(), site.end());
  return head;
}

}  // namespace

// Two daily files, as a run across midnight reads them: wherever one file
// alone covers the time, the pair gives that file's own answer, and where
// neither does (the days between), the pair fails as each does.
TEST(NavFiles, DopWithTwoFilesEqualsEachFilesOwnAnswer) {
  const time::GpsTime first = time::GpsTime::from_calendar({2024, 5, 3, 0, 0, 0.0});
  int only_a = 0, only_b = 0, none = 0;
  for (double h = 0.0; h <= 4.0 * 24.0 + 2.0; h += 0.5) {
    const time::GpsTime t = first + h * 3600.0;
    const CliResult a = run(at({"dop", "--nav", kNya3}, t, kNyaSite));
    const CliResult b = run(at({"dop", "--nav", kNya6}, t, kNyaSite));
    const CliResult ab = run(at({"dop", "--nav", kNya3, "--nav", kNya6}, t, kNyaSite));
    const CliResult ba = run(at({"dop", "--nav", kNya6, "--nav", kNya3}, t, kNyaSite));
    EXPECT_EQ(ab.out, ba.out) << h;  // the order of the files does not matter
    if (a.status == kExitOk && b.status != kExitOk) {
      ++only_a;
      EXPECT_EQ(ab.out, a.out) << h;
    } else if (b.status == kExitOk && a.status != kExitOk) {
      ++only_b;
      EXPECT_EQ(ab.out, b.out) << h;
    } else {
      ASSERT_NE(a.status, kExitOk) << "the files overlap at " << h << " h";
      ++none;
      EXPECT_NE(ab.status, kExitOk) << h;
      EXPECT_NE(ab.err.find("no healthy ephemeris valid"), std::string::npos) << ab.err;
    }
  }
  EXPECT_EQ(only_a, 53);  // 05-03 00:00 to 05-04 02:00 (the midnight sets), half-hourly
  EXPECT_EQ(only_b, 53);  // 05-06 00:00 to 05-07 02:00
  EXPECT_GT(none, 0);     // 05-04 02:30 to 05-05 23:30
}

// One real daily file cut at noon into two RINEX files: the pair answers
// as the whole file at every time, through the hours both cover.
TEST(NavFiles, DayCutInTwoAnswersAsTheWholeFile) {
  TempDir dir;
  std::ifstream in(nav_path("brdc0010.22n"));
  std::string line, header, am, pm;
  bool in_header = true;
  std::vector<std::string> record;
  while (std::getline(in, line)) {
    if (in_header) {
      header += line + "\n";
      in_header = line.find("END OF HEADER") == std::string::npos;
      continue;
    }
    record.push_back(line);
    if (record.size() == 8) {
      const int hour = std::stoi(record[0].substr(12, 2));
      std::string& dst = hour < 12 ? am : pm;
      for (const std::string& r : record) dst += r + "\n";
      record.clear();
    }
  }
  const std::string a = dir.write("am.22n", header + am), b = dir.write("pm.22n", header + pm);
  const std::vector<std::string> site = {"--lat", "48.8738", "--lon", "2.295", "--height", "100"};
  for (double tow = 518400.0 - 3600.0; tow <= 518400.0 + 86400.0; tow += 1800.0) {
    const time::GpsTime t(2190, tow);
    const CliResult whole = run(at({"dop", "--nav", nav_path("brdc0010.22n")}, t, site));
    const CliResult pair = run(at({"dop", "--nav", a, "--nav", b}, t, site));
    ASSERT_EQ(whole.status, kExitOk) << whole.err;
    EXPECT_EQ(pair.out, whole.out) << tow;
    const CliResult sky_whole = run(at({"sky", "--nav", nav_path("brdc0010.22n")}, t, site));
    const CliResult sky_pair = run(at({"sky", "--nav", b, "--nav", a}, t, site));
    EXPECT_EQ(sky_pair.out, sky_whole.out) << tow;
  }
}

// Issue 12: the sky of a relabelled date is the original sky at the
// relabelled offset: the same satellites at the same azimuth, elevation and
// range (<= 1 mm), the same DOP (<= 1e-9), through the CLI and the library.
TEST(NavFiles, RelabelledDateHasTheOriginalGeometry) {
  const std::vector<std::string> site = {"--lat", "48.8738", "--lon", "2.295", "--height", "100"};
  const double shift = 1788.0 * kSecondsPerDay;  // 2022-01-01 -> 2026-11-24
  for (const double tow : {518400.0 + 600.0, 518400.0 + 43200.0 + 17.5, 518400.0 + 86000.0}) {
    const time::GpsTime t(2190, tow), moved = t + shift;
    const CliResult sky0 = run(at({"sky", "--nav", nav_path("brdc0010.22n")}, t, site));
    const CliResult sky1 = run(at({"sky", "--nav", nav_path("brdc0010.22n"), "--nav-mode", "relabel"}, moved, site));
    ASSERT_EQ(sky1.status, kExitOk) << sky1.err;
    const Csv c0 = parse_csv(sky0.out), c1 = parse_csv(sky1.out);
    ASSERT_EQ(c0.rows.size(), c1.rows.size());
    for (std::size_t i = 0; i < c0.rows.size(); ++i) {
      for (const char* col : {"prn", "az_deg", "el_deg", "range_m", "iono_klobuchar_m", "atten_db", "cn0_dbhz"}) {
        EXPECT_EQ(c1.cell(i, col), c0.cell(i, col)) << col << " row " << i;
      }
    }
    const CliResult dop0 = run(at({"dop", "--nav", nav_path("brdc0010.22n")}, t, site));
    const CliResult dop1 = run(at({"dop", "--nav", nav_path("brdc0010.22n"), "--nav-mode", "auto"}, moved, site));
    EXPECT_EQ(dop1.out, dop0.out);
  }
  // The numbers themselves, unrounded.
  const orbit::NavData nav = orbit::read_rinex_nav(nav_path("brdc0010.22n"));
  orbit::ConstellationRequest req;
  req.start = time::GpsTime(2190, 518400.0 + 43200.0) + shift;
  const orbit::Constellation c = orbit::build_constellation(nav, req);
  ASSERT_EQ(c.shift_s, shift);
  const orbit::EphemerisStore original(nav.ephemerides), relabelled(c.nav.ephemerides, c.store_options());
  const Lla rx_lla{48.8738 * kDegToRad, 2.295 * kDegToRad, 100.0};
  const Ecef rx = geo::ecef_from_lla(rx_lla);
  for (double dt = 0.0; dt < 86400.0; dt += 3.0 * 3600.0 + 7.0) {
    const time::GpsTime t = time::GpsTime(2190, 518400.0 + 300.0) + dt;
    int n = 0;
    for (int prn = 1; prn <= system_size(GnssSystem::kGps); ++prn) {
      const orbit::Ephemeris* e0 = original.select(SatId::gps(prn), t);
      const orbit::Ephemeris* e1 = relabelled.select(SatId::gps(prn), t + shift);
      ASSERT_EQ(e0 == nullptr, e1 == nullptr) << prn;
      if (e0 == nullptr) continue;
      const world::SkySat s0 = world::sky_sat(*e0, t, rx, rx_lla, Ecef());
      const world::SkySat s1 = world::sky_sat(*e1, t + shift, rx, rx_lla, Ecef());
      EXPECT_LT(std::fabs(s1.range_m - s0.range_m), 1e-3) << prn;
      EXPECT_LT((s1.pos_m - s0.pos_m).norm(), 1e-3) << prn;
      EXPECT_LT(std::fabs(s1.el_rad - s0.el_rad) * 26e6, 1e-3) << prn;
      EXPECT_LT(std::fabs(s1.az_rad - s0.az_rad) * 26e6, 1e-3) << prn;
      ++n;
    }
    EXPECT_GT(n, 25);
    pipeline::Pipeline p0(original, geometry_config(5.0 * kDegToRad)), p1(relabelled, geometry_config(5.0 * kDegToRad));
    world::Truth truth;
    truth.pos_m = rx;
    truth.valid = true;
    truth.t = t;
    const receiver::Dop d0 = p0.step(t, truth).dop;
    truth.t = t + shift;
    const receiver::Dop d1 = p1.step(t + shift, truth).dop;
    // DOP is taken at the fix, and the sky's error draws follow GPS time: the
    // relabelled date's fix lies metres from the original's (~1e-8 in DOP).
    EXPECT_NEAR(d1.gdop, d0.gdop, 1e-6);
    EXPECT_NEAR(d1.pdop, d0.pdop, 1e-6);
    EXPECT_NEAR(d1.hdop, d0.hdop, 1e-6);
    EXPECT_NEAR(d1.vdop, d0.vdop, 1e-6);
    EXPECT_NEAR(d1.tdop, d0.tdop, 1e-6);
  }
}

TEST(NavFiles, ModesAndAlmanacOnTheCommandLine) {
  const std::string yuma = std::string(GNSSEMU_TEST_DATA) + "/almanac/yuma_week862_toa319488.alm";
  const std::vector<std::string> today = {"--week", "2446", "--tow", "210808"};
  CliResult r = run({"satpos", "--nav-mode", "almanac", "--almanac", yuma, "--week", "2446", "--tow", "210808"});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  EXPECT_GE(parse_csv(r.out).rows.size(), 29u);
  r = run({"satpos", "--nav", nav_path("brdc0010.22n"), "--nav-mode", "relabel", "--week", "2446", "--tow", "210808"});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  EXPECT_GE(parse_csv(r.out).rows.size(), 29u);
  // Days after the data's end the orbits go on in relabel mode, not as_is.
  r = run({"satpos", "--nav", nav_path("brdc0010.22n"), "--nav-mode", "relabel", "--week", "2446", "--tow", "500000"});
  EXPECT_EQ(r.status, kExitOk) << r.err;
  r = run({"satpos", "--nav", nav_path("brdc0010.22n"), "--week", "2446", "--tow", "210808"});
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_NE(r.err.find("--nav-mode relabel moves them to that date"), std::string::npos) << r.err;
  r = run({"satpos", "--nav", nav_path("brdc0010.22n"), "--almanac", yuma, "--week", "2446", "--tow", "0"});
  EXPECT_NE(r.err.find("--almanac needs --nav-mode almanac"), std::string::npos) << r.err;
  r = run({"satpos", "--nav-mode", "almanac", "--week", "2446", "--tow", "0"});
  EXPECT_NE(r.err.find("--nav-mode almanac needs --almanac FILE"), std::string::npos) << r.err;
  r = run({"satpos", "--week", "2446", "--tow", "0"});
  EXPECT_NE(r.err.find("--nav FILE is required"), std::string::npos) << r.err;
  r = run({"satpos", "--nav", nav_path("brdc0010.22n"), "--nav-mode", "today", "--week", "2446", "--tow", "0"});
  EXPECT_EQ(r.status, kExitUsage);
}

// SPDX-License-Identifier: Apache-2.0
// --systems on satpos, sky, dop, batch and calibrate: RINEX letters, the
// default set of each, and the satellites of a multi-GNSS file (satpos
// against RTKLIB's states of the same file).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "cli_test_util.hpp"
#include "core/common/sat_id.hpp"

using namespace gnssemu;
using namespace gnssemu::cli::test;

namespace {

const std::string kMixedNav = "BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz";
// A reference epoch of tests/data/reference/rtklib_BRDC00IGS_R_20240100000_01D_MN.csv.
const std::vector<std::string> kMixedEpoch = {"--week", "2296", "--tow", "263399.925"};
const std::vector<std::string> kParisSite = {"--lat", "48.8738", "--lon", "2.295", "--height", "100"};

std::vector<std::string> joined(std::vector<std::string> a, const std::vector<std::string>& b,
                             const std::vector<std::string>& c = {}) {
  a.insert(a.end(), b.begin(), b.end());
  a.insert(a.end(), c.begin(), c.end());
  return a;
}

/// The system letters of the `sat` column.
std::set<char> systems_in(const Csv& csv) {
  std::set<char> s;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) s.insert(csv.cell(i, "sat").front());
  return s;
}

}  // namespace

TEST(SystemsOption, SatposDefaultIsEverySystemOfTheFiles) {
  const CliResult r = run(joined({"satpos", "--nav", nav_path(kMixedNav)}, kMixedEpoch));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(systems_in(parse_csv(r.out)), (std::set<char>{'G', 'R', 'E', 'C', 'J', 'S'}));
  const CliResult gps = run(joined({"satpos", "--nav", nav_path("brdc0010.22n"), "--week", "2190", "--tow", "540000"}, {}));
  ASSERT_EQ(gps.status, 0) << gps.err;
  EXPECT_EQ(systems_in(parse_csv(gps.out)), std::set<char>{'G'});
}

TEST(SystemsOption, SatposPrintsEverySatelliteOfTheChosenSystems) {
  const CliResult r = run(joined({"satpos", "--nav", nav_path(kMixedNav), "--systems", "R,E,C,J"}, kMixedEpoch));
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv csv = parse_csv(r.out);
  EXPECT_EQ(systems_in(csv), (std::set<char>{'R', 'E', 'C', 'J'}));
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const auto sat = parse_sat(csv.cell(i, "sat"));
    ASSERT_TRUE(sat.has_value()) << csv.cell(i, "sat");
    EXPECT_EQ(sat->prn(), std::stoi(csv.cell(i, "prn"))) << csv.cell(i, "sat");  // J02 is PRN 194
  }
  // The same rows as without --systems, G and S left out.
  const Csv all = parse_csv(run(joined({"satpos", "--nav", nav_path(kMixedNav)}, kMixedEpoch)).out);
  std::size_t others = 0;
  for (std::size_t i = 0; i < all.rows.size(); ++i) others += std::string("RECJ").find(all.cell(i, "sat").front()) != std::string::npos;
  EXPECT_EQ(csv.rows.size(), others);
}

// Each satellite of the chosen systems where RTKLIB 2.4.3 computed it from
// the same file: the CLI prints the state of the same set (1 mm; GLONASS 1 cm).
TEST(SystemsOption, SatposAgreesWithRtklibPerSystem) {
  const Csv ref = parse_csv(read_file(std::string(GNSSEMU_TEST_DATA) + "/reference/rtklib_BRDC00IGS_R_20240100000_01D_MN.csv"));
  std::map<std::string, std::vector<std::size_t>> by_tow;
  for (std::size_t i = 0; i < ref.rows.size(); ++i) by_tow[ref.cell(i, "tow_s")].push_back(i);
  std::map<char, int> compared;
  for (const auto& [tow, rows] : by_tow) {
    const CliResult r = run({"satpos", "--nav", nav_path(kMixedNav), "--systems", "R,E,C,J", "--week", "2296", "--tow", tow});
    ASSERT_EQ(r.status, 0) << r.err;
    const Csv ours = parse_csv(r.out);
    std::map<std::string, std::size_t> row_of;
    for (std::size_t j = 0; j < ours.rows.size(); ++j) row_of[ours.cell(j, "sat")] = j;
    for (const std::size_t i : rows) {
      const std::string sat = ref.cell(i, "sat");
      const auto it = row_of.find(sat);
      if (sat[0] == 'G' || sat[0] == 'S') {
        EXPECT_EQ(it, row_of.end()) << sat << " printed though not asked for";
        continue;
      }
      // Unhealthy sets are not printed; a set RTKLIB chose at the receive time may differ at its edge.
      if (it == row_of.end() || ours.num(it->second, "toe_tow_s") != ref.num(i, "toe_tow_s")) continue;
      const std::size_t j = it->second;
      const double d = std::hypot(ours.num(j, "x_m") - ref.num(i, "x_m"), ours.num(j, "y_m") - ref.num(i, "y_m"),
                                  ours.num(j, "z_m") - ref.num(i, "z_m"));
      EXPECT_LE(d, sat[0] == 'R' ? 1e-2 : 2e-3) << sat << " tow " << tow;  // RTKLIB's CSV: mm
      ++compared[sat[0]];
    }
  }
  for (const char s : {'R', 'E', 'C', 'J'}) EXPECT_GE(compared[s], 10) << s;
}

TEST(SystemsOption, SkyAndDopCountTheChosenSystems) {
  const CliResult gps = run(joined({"sky", "--nav", nav_path(kMixedNav), "--systems", "G"}, kMixedEpoch, kParisSite));
  const CliResult four = run(joined({"sky", "--nav", nav_path(kMixedNav), "--systems", "G,R,E,C"}, kMixedEpoch, kParisSite));
  ASSERT_EQ(gps.status, 0) << gps.err;
  ASSERT_EQ(four.status, 0) << four.err;
  const Csv g = parse_csv(gps.out), f = parse_csv(four.out);
  EXPECT_EQ(systems_in(g), std::set<char>{'G'});
  EXPECT_EQ(systems_in(f), (std::set<char>{'G', 'R', 'E', 'C'}));
  EXPECT_GT(f.rows.size(), 2 * g.rows.size());

  const CliResult dg = run(joined({"dop", "--nav", nav_path(kMixedNav), "--systems", "G"}, kMixedEpoch, kParisSite));
  const CliResult df = run(joined({"dop", "--nav", nav_path(kMixedNav), "--systems", "G,R,E,C"}, kMixedEpoch, kParisSite));
  ASSERT_EQ(dg.status, 0) << dg.err;
  ASSERT_EQ(df.status, 0) << df.err;
  const Csv a = parse_csv(dg.out), b = parse_csv(df.out);
  EXPECT_EQ(a.num(0, "nsat"), static_cast<double>(g.rows.size()));
  EXPECT_EQ(b.num(0, "nsat"), static_cast<double>(f.rows.size()));
  EXPECT_LT(b.num(0, "pdop"), a.num(0, "pdop"));
}

TEST(SystemsOption, BadListsAreRejected) {
  for (const std::string bad : {"X", "G,G", "G,", "", "GR", "g"}) {
    const CliResult r = run(joined({"satpos", "--nav", nav_path(kMixedNav), "--systems", bad}, kMixedEpoch));
    EXPECT_EQ(r.status, kExitBadInput) << bad;
    EXPECT_NE(r.err.find("--systems"), std::string::npos) << bad << ": " << r.err;
  }
  // A system the files lack is named; the others are printed.
  const CliResult r = run({"satpos", "--nav", nav_path("brdc0010.22n"), "--systems", "G,E", "--week", "2190", "--tow", "540000"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("no Galileo (E) ephemerides"), std::string::npos) << r.err;
  const CliResult none = run({"satpos", "--nav", nav_path("brdc0010.22n"), "--systems", "R", "--week", "2190", "--tow", "540000"});
  EXPECT_EQ(none.status, kExitBadInput);
  EXPECT_NE(none.err.find("no healthy ephemeris valid at week 2190 tow 540000.000 for --systems R"), std::string::npos) << none.err;
}

TEST(SystemsOption, CalibrateAcceptsGpsAndNamesWhatItSupports) {
  const std::vector<std::string> base = {"calibrate", "--obs", "/nonexistent.obs", "--nav", nav_path(kMixedNav),
                                         "--station", "4027893.6,307045.6,4919475.0", "--out", "/nonexistent/x.toml"};
  CliResult r = run(joined(base, {"--systems", "G,R"}));
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_NE(r.err.find("--systems G,R: calibrate fits GPS alone so far (supported: G)"), std::string::npos) << r.err;
  r = run(joined(base, {"--systems", "Q"}));
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_NE(r.err.find("--systems: 'Q'"), std::string::npos) << r.err;
  r = run(joined(base, {"--systems", "G"}));  // accepted: fails later, at the missing file
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_NE(r.err.find("/nonexistent.obs"), std::string::npos) << r.err;
}

// batch: the config's [receiver] constellations unless --systems; the shipped
// nav data serve every system asked for.
TEST(SystemsOption, BatchTracksTheConfiguredOrChosenSystems) {
  TempDir dir;
  const std::string nav = std::string(GNSSEMU_SOURCE_DIR) + "/config/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz";
  const std::string cfg = dir.write("gnssemu.toml", config_text(nav));
  const std::string m9 = dir.write("m9.toml", config_text(nav, "[receiver]\ngeneration = \"m9\"\n"));
  std::string truth = "gps_week,tow_s,lat_deg,lon_deg,height_m\n";
  for (int k = 0; k <= 20; ++k) truth += "2296," + std::to_string(302400 + k) + ",48.8738,2.295,100\n";  // 2024-01-10 12:00
  const std::string truth_path = dir.write("truth.csv", truth);
  // No constellations: every system in the sky, the M8 tracking its factory set (GPS, GLONASS, QZSS, SBAS;
  // QZSS is not above Paris).
  const CliResult m8 = run({"batch", "--config", cfg, "--truth", truth_path, "--sats", "-"});
  ASSERT_EQ(m8.status, 0) << m8.err;
  EXPECT_EQ(systems_in(parse_csv(m8.out)), (std::set<char>{'G', 'R', 'S'}));
  EXPECT_NE(m8.err.find("systems G,R,E,C,J,S in the sky, the chip tracks G,R,J,S"), std::string::npos) << m8.err;
  const CliResult gps = run({"batch", "--config", cfg, "--truth", truth_path, "--sats", "-", "--systems", "G"});
  ASSERT_EQ(gps.status, 0) << gps.err;
  EXPECT_EQ(systems_in(parse_csv(gps.out)), std::set<char>{'G'});
  // Four major systems: a NEO-M9N tracks them all at once.
  const CliResult all = run({"batch", "--config", m9, "--truth", truth_path, "--sats", "-", "--systems", "G,R,E,C,J"});
  ASSERT_EQ(all.status, 0) << all.err;
  const std::set<char> seen = systems_in(parse_csv(all.out));  // QZSS: not above Paris
  for (const char s : {'G', 'R', 'E', 'C'}) EXPECT_EQ(seen.count(s), 1u) << s;
  EXPECT_EQ(seen.count('S'), 0u);
  EXPECT_NE(all.err.find("systems G,R,E,C,J"), std::string::npos) << all.err;
  const CliResult bad = run({"batch", "--config", cfg, "--truth", truth_path, "--systems", "G,I"});
  EXPECT_EQ(bad.status, kExitBadInput);
  EXPECT_NE(bad.err.find("--systems: 'G,I'"), std::string::npos) << bad.err;
}

// SPDX-License-Identifier: Apache-2.0
// gnssemu sky --scene and batch with [scene].
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include <fmt/format.h>

#include "cli_test_util.hpp"
#include "core/common/constants.hpp"
#include "core/geo/local_frame.hpp"

namespace gnssemu::cli::scene_cli_test {
namespace {

using test::Csv;
using test::nav_path;
using test::parse_csv;
using test::read_file;
using test::run;
using test::TempDir;

const std::string kScenes = std::string(GNSSEMU_TEST_DATA) + "/scenes/";
const Lla kOrigin{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};

std::vector<std::string> sky_args(const Enu& at, const std::string& scene) {
  const Lla p = geo::LocalFrame(kOrigin).to_lla(at);
  std::vector<std::string> a = {"sky", "--nav", nav_path("brdc0010.22n"), "--week", "2190", "--tow", "561600",
                                "--lat", fmt::format("{:.10f}", p.lat_rad * kRadToDeg), "--lon",
                                fmt::format("{:.10f}", p.lon_rad * kRadToDeg), "--height",
                                fmt::format("{:.4f}", p.height_m)};
  if (!scene.empty()) {
    a.insert(a.end(), {"--scene", scene, "--scene-origin", "48.8738,2.2950,100.0"});
  }
  return a;
}

TEST(SkyScene, ColumnsAndCanyonPaths) {
  const Enu at(3.0, 0.0, 1.5);
  const test::CliResult plain = run(sky_args(at, ""));
  const test::CliResult r = run(sky_args(at, kScenes + "street_canyon.toml"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string header = r.out.substr(0, r.out.find('\n'));
  EXPECT_EQ(header.substr(header.size() - 38), ",los,bounces,nlos_delay_m,path_loss_db") << header;
  EXPECT_EQ(header.substr(0, header.size() - 38), plain.out.substr(0, plain.out.find('\n')));
  const Csv sky = parse_csv(r.out), ref = parse_csv(plain.out);
  ASSERT_EQ(sky.rows.size(), ref.rows.size());
  int los = 0, nlos = 0, none = 0;
  for (std::size_t i = 0; i < sky.rows.size(); ++i) {
    EXPECT_EQ(sky.cell(i, "prn"), ref.cell(i, "prn"));
    EXPECT_EQ(sky.cell(i, "el_deg"), ref.cell(i, "el_deg"));
    const double az = sky.num(i, "az_deg"), el = sky.num(i, "el_deg");
    // The canyon runs north-south between 30 m walls 10 m away on each side
    // (7 m east, 13 m west of the antenna): the open sky is a strip.
    const double across = std::fabs(std::sin(az * kDegToRad)) * std::cos(el * kDegToRad);
    const double wall_m = std::sin(az * kDegToRad) > 0.0 ? 7.0 : 13.0;
    const double t = across > 0.0 ? wall_m / across : 1e9;  // distance to the wall plane along the ray
    const bool open = 1.5 + t * std::sin(el * kDegToRad) > 30.0 ||
                      std::fabs(t * std::cos(az * kDegToRad) * std::cos(el * kDegToRad)) > 150.0;
    if (sky.cell(i, "los") == "1") {
      ++los;
      EXPECT_EQ(sky.num(i, "nlos_delay_m"), 0.0);
      EXPECT_TRUE(open) << "prn " << sky.cell(i, "prn");
    } else if (!sky.cell(i, "nlos_delay_m").empty()) {
      ++nlos;
      EXPECT_GT(sky.num(i, "nlos_delay_m"), 0.0);
      EXPECT_NEAR(sky.num(i, "path_loss_db"), 3.0 * sky.num(i, "bounces"), 1e-9);
      EXPECT_FALSE(open);
    } else {
      ++none;
      EXPECT_EQ(sky.cell(i, "bounces"), "0");
      EXPECT_EQ(sky.cell(i, "path_loss_db"), "");
    }
  }
  EXPECT_GT(los, 0);
  EXPECT_GT(nlos + none, 0);
}

TEST(SkyScene, EmptySceneAllDirectInsideABoxNothing) {
  // A box 5 km away hides nothing (an empty mesh file is an error).
  std::vector<std::string> far = sky_args(Enu(0.0, 0.0, 1.5), kScenes + "closed_box.obj");
  far.insert(far.end(), {"--offset-m", "5000,0,0"});
  const test::CliResult e = run(far);
  ASSERT_EQ(e.status, 0) << e.err;
  const Csv es = parse_csv(e.out);
  ASSERT_GT(es.rows.size(), 4u);
  for (std::size_t i = 0; i < es.rows.size(); ++i) {
    EXPECT_EQ(es.cell(i, "los"), "1");
    EXPECT_EQ(es.num(i, "nlos_delay_m"), 0.0);
  }
  const test::CliResult b = run(sky_args(Enu(1.0, 2.0, 1.5), kScenes + "closed_box.obj"));
  ASSERT_EQ(b.status, 0) << b.err;
  const Csv bs = parse_csv(b.out);
  for (std::size_t i = 0; i < bs.rows.size(); ++i) {
    EXPECT_EQ(bs.cell(i, "los"), "0");
    EXPECT_EQ(bs.cell(i, "nlos_delay_m"), "");
  }
  const test::CliResult bad = run(sky_args(Enu(), kScenes + "missing.obj"));
  EXPECT_EQ(bad.status, kExitBadInput);
  EXPECT_NE(bad.err.find("missing.obj"), std::string::npos) << bad.err;
  const test::CliResult empty = run(sky_args(Enu(), kScenes + "empty.obj"));
  EXPECT_EQ(empty.status, kExitBadInput);
  EXPECT_NE(empty.err.find("empty.obj: no triangles"), std::string::npos) << empty.err;
}

std::string canyon_truth(int n);

// The scene options take the ranges of the config keys they mirror (core's).
TEST(SceneCli, OptionRangesAreTheConfigRanges) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--scale", "0"}, "--scale: 0 is out of range (0, 1000000]"},
      {{"--max-loss-db", "0"}, "--max-loss-db: 0 is out of range (0, 1000] dB"},
      {{"--yaw-deg", "400"}, "--yaw-deg: 400 is out of range [-360, 360] deg"},
      {{"--reflection-loss-db", "101"}, "--reflection-loss-db: 101 is out of range [0, 100] dB"},
      {{"--min-arrival-elevation-deg", "90"}, "--min-arrival-elevation-deg: 90 is out of range [-89, 89] deg"},
  };
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> a = sky_args(Enu(1.0, 2.0, 1.5), kScenes + "closed_box.obj");
    a.insert(a.end(), extra.begin(), extra.end());
    const test::CliResult r = run(a);
    EXPECT_EQ(r.status, kExitBadInput) << extra[0];
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
}

TEST(SceneCli, SkippedMeshElementsAreReportedWithTheFirstProblem) {
  // Two good triangles of a wall far east, one face with a missing vertex.
  TempDir dir;
  const std::string mesh = dir.write("w.obj", "v 500 -10 0\nv 500 10 0\nv 500 10 30\nv 500 -10 30\n"
                                              "f 1 2 3\nf 1 3 4\nf 1 2 9\n");
  const std::string expect = "mesh: 1 bad elements skipped (1 bad index, 0 NaN/inf, 0 degenerate); first: " + mesh +
                             ":7: face refers to a vertex that does not exist";
  const test::CliResult s = run(sky_args(Enu(0.0, 0.0, 1.5), mesh));
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_NE(s.err.find(expect), std::string::npos) << s.err;
  const std::string cfg =
      dir.write("c.toml", test::config_text(nav_path("brdc0010.22n"), "[scene]\nmesh = \"" + mesh + "\"\n"));
  const std::string truth = dir.write("t.csv", canyon_truth(2));
  const test::CliResult b = run({"batch", "--config", cfg, "--truth", truth});
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_NE(b.err.find(expect), std::string::npos) << b.err;
  const test::CliResult m =
      run({"bench", "multipath", "--scene", mesh, "--origin", "48.8738,2.2950,100", "--nav", nav_path("brdc0010.22n"),
           "--week", "2190", "--tow", "561600", "--path=0,0,0,20", "--speed", "20", "--repeats", "1",
           "--reference-rays", "1024", "--settings", "0,256,2,0,0"});
  ASSERT_EQ(m.status, 0) << m.err;
  EXPECT_NE(m.err.find(expect), std::string::npos) << m.err;
}

std::string canyon_truth(int n) {
  std::string s = "gps_week,tow_s,x_m,y_m,z_m\n";
  const geo::LocalFrame f(kOrigin);
  for (int k = 0; k < n; ++k) {
    const Ecef p = f.to_ecef(Enu(3.0, -100.0 + 2.0 * k, 1.5));
    s += fmt::format("2190,{:.1f},{:.4f},{:.4f},{:.4f}\n", 561600.0 + k, p.x, p.y, p.z);
  }
  return s;
}

TEST(BatchScene, ConfigSceneAddsColumnsAndChangesTheFix) {
  TempDir dir;
  const std::string extra = "[scene]\nmesh = \"" + kScenes + "street_canyon.toml\"\n";
  const std::string cfg = dir.write("c.toml", test::config_text(nav_path("brdc0010.22n"), extra));
  const std::string truth = dir.write("t.csv", canyon_truth(100));
  const test::CliResult r = run({"batch", "--config", cfg, "--truth", truth, "--errors", dir.file("e.csv")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("scene: per epoch"), std::string::npos) << r.err;
  const Csv e = parse_csv(read_file(dir.file("e.csv")));
  ASSERT_EQ(e.rows.size(), 100u);
  int nlos = 0, blocked = 0;
  for (std::size_t i = 0; i < e.rows.size(); ++i) {
    // Not tracked: blocked, or a reflection too weak for the tracking loops.
    EXPECT_GE(e.num(i, "nvisible"), e.num(i, "ntracked") + e.num(i, "nblocked"));
    nlos += static_cast<int>(e.num(i, "nlos"));
    blocked += static_cast<int>(e.num(i, "nblocked"));
    if (e.num(i, "nlos") > 0) {
      EXPECT_GT(e.num(i, "nlos_delay_mean_m"), 0.0);
    }
  }
  EXPECT_GT(nlos, 0);
  EXPECT_GT(blocked, 0);
  // Inside a closed building: no fix at all.
  const std::string box = dir.write(
      "b.toml", test::config_text(nav_path("brdc0010.22n"), "[scene]\nmesh = \"" + kScenes + "closed_box.obj\"\n"));
  const std::string still = dir.write("s.csv", "gps_week,tow_s,x_m,y_m,z_m\n" + [] {
    const Ecef p = geo::LocalFrame(kOrigin).to_ecef(Enu(0.0, 0.0, 1.5));
    return fmt::format("2190,561600.0,{:.4f},{:.4f},{:.4f}\n2190,561610.0,{:.4f},{:.4f},{:.4f}\n", p.x, p.y, p.z,
                       p.x, p.y, p.z);
  }());
  const test::CliResult rb = run({"batch", "--config", box, "--truth", still});
  ASSERT_EQ(rb.status, 0) << rb.err;
  EXPECT_NE(rb.err.find("fixes 0 (0.0%)"), std::string::npos) << rb.err;
}

// What sky says of each satellite at the antenna position `at`, one letter
// per row: L direct, R reflections only, X not received.
std::string sky_classes(const Enu& at, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> a = sky_args(at, kScenes + "street_canyon.toml");
  a.insert(a.end(), extra.begin(), extra.end());
  const test::CliResult r = run(a);
  EXPECT_EQ(r.status, 0) << r.err;
  const Csv c = parse_csv(r.out);
  std::string k;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    k += c.cell(i, "los") == "1" ? 'L' : c.cell(i, "nlos_delay_m").empty() ? 'X' : 'R';
  }
  return k;
}

int sky_not_received(const Enu& at, const std::vector<std::string>& extra = {}) {
  const std::string k = sky_classes(at, extra);
  return static_cast<int>(std::count(k.begin(), k.end(), 'X'));
}

/// Satellites batch reports as not received (nblocked) for one epoch at
/// `at` (scene ENU) with config file cfg; -1 when batch fails.
int batch_not_received(TempDir& dir, const std::string& cfg, const Enu& at) {
  const Ecef p = geo::LocalFrame(kOrigin).to_ecef(at);
  const std::string truth = dir.write(
      "t.csv", fmt::format("gps_week,tow_s,x_m,y_m,z_m\n2190,561600.0,{:.4f},{:.4f},{:.4f}\n", p.x, p.y, p.z));
  const test::CliResult b = run({"batch", "--config", cfg, "--truth", truth, "--errors", dir.file("e.csv")});
  EXPECT_EQ(b.status, 0) << b.err;
  if (b.status != 0) return -1;
  const Csv e = parse_csv(read_file(dir.file("e.csv")));
  EXPECT_EQ(e.rows.size(), 1u);
  return e.rows.size() == 1 ? static_cast<int>(e.num(0, "nblocked")) : -1;
}

TEST(SkyScene, ClassifiesLikeBatchWithTheConfigDefaults) {
  // One default loss cap (21 dB) in every entry point: sky and a receiver
  // configured only with [scene] mesh agree on what is not received.
  TempDir dir;
  const std::string cfg = dir.write(
      "c.toml", test::config_text(nav_path("brdc0010.22n"), "[scene]\nmesh = \"" + kScenes + "street_canyon.toml\"\n"));
  bool capped_somewhere = false;
  for (const Enu& at : {Enu(3.0, 0.0, 1.5), Enu(-8.0, 60.0, 1.5), Enu(8.0, -120.0, 1.5), Enu(0.0, 140.0, 1.5)}) {
    const int none = sky_not_received(at);
    EXPECT_EQ(none, batch_not_received(dir, cfg, at)) << at.x << "," << at.y;
    // The same options as the config keys: no cap receives deeper paths.
    capped_somewhere = capped_somewhere || sky_not_received(at, {"--max-loss-db", "1000"}) < none;
  }
  EXPECT_TRUE(capped_somewhere) << "the test positions never need more than 7 reflections";
}

TEST(SkyScene, PlacementAndSearchOptionsMirrorTheConfig) {
  // The canyon moved 100 m east and turned by 90 deg (now east-west,
  // y in [-10, 10]): the config placement in batch and the same options
  // in sky give the same not-received count.
  TempDir dir;
  const std::string extra = "[scene]\nmesh = \"" + kScenes +
                            "street_canyon.toml\"\noffset_m = [100, 0, 0]\nyaw_deg = 90\nmax_loss_db = 9\n"
                            "azimuth_rays = 64\nmin_arrival_elevation_deg = -10\n";
  const std::string cfg = dir.write("c.toml", test::config_text(nav_path("brdc0010.22n"), extra));
  const Enu at(100.0, -3.0, 1.5);
  const std::vector<std::string> opts = {"--offset-m", "100,0,0", "--yaw-deg", "90", "--max-loss-db", "9",
                                         "--azimuth-rays", "64", "--min-arrival-elevation-deg", "-10"};
  const int none = sky_not_received(at, opts);
  EXPECT_EQ(none, batch_not_received(dir, cfg, at));
  EXPECT_GT(none, 0);
  // The options are not ignored: without the yaw the antenna stands east of
  // the canyon, and a 9 dB cap drops paths of more than 3 reflections.
  std::vector<std::string> no_yaw = opts;
  no_yaw[3] = "0";
  EXPECT_NE(sky_classes(at, opts), sky_classes(at, no_yaw));
  std::vector<std::string> no_cap = opts;
  no_cap[5] = "1000";
  EXPECT_NE(sky_classes(at, opts), sky_classes(at, no_cap));
  const test::CliResult bad = run([&] {
    auto a = sky_args(at, kScenes + "street_canyon.toml");
    a.insert(a.end(), {"--up-axis", "x"});
    return a;
  }());
  EXPECT_NE(bad.status, 0);
}

TEST(BatchScene, ExcludedSatellitesDropFromGsa) {
  // Receiver with the residual test and fault exclusion in the canyon (up to
  // 4 exclusions: the canyon often has several NLOS satellites): GSA lists
  // exactly the satellites used, fewer than tracked when some were excluded.
  TempDir dir;
  const std::string cfg = dir.write(
      "c.toml", test::config_text(nav_path("brdc0010.22n"), "[receiver.solver]\nmax_exclusions = 4\n\n[scene]\nmesh = \"" +
                                                                kScenes + "street_canyon.toml\"\n"));
  const std::string truth = dir.write("t.csv", canyon_truth(100));
  const test::CliResult r =
      run({"batch", "--config", cfg, "--truth", truth, "--errors", dir.file("e.csv"), "--nmea", dir.file("o.nmea")});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv e = parse_csv(read_file(dir.file("e.csv")));
  std::vector<int> gsa_used;
  std::istringstream nmea(read_file(dir.file("o.nmea")));
  for (std::string line; std::getline(nmea, line);) {
    if (line.size() < 6 || line.substr(3, 3) != "GSA") continue;
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
    int n = 0;
    for (std::size_t i = 3; i < 15 && i < f.size(); ++i) n += !f[i].empty();
    gsa_used.push_back(n);
  }
  ASSERT_EQ(gsa_used.size(), e.rows.size());
  int excluded_epochs = 0;
  for (std::size_t i = 0; i < e.rows.size(); ++i) {
    if (e.cell(i, "e_m").empty()) continue;
    EXPECT_EQ(gsa_used[i], std::min(12, static_cast<int>(e.num(i, "nsat")))) << i;
    excluded_epochs += e.num(i, "nsat") < e.num(i, "ntracked");
  }
  EXPECT_GT(excluded_epochs, 0);
}

}  // namespace
}  // namespace gnssemu::cli::scene_cli_test

// SPDX-License-Identifier: Apache-2.0
// The include checker itself: planted bad includes must be found, with the
// file and line, and good ones must pass.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "include_rules.hpp"
#include "project_layers.hpp"

using namespace gnssemu::layering;

namespace {

// bottom <- middle <- top, plus a side layer beside middle and one header
// of top that side may read.
Rules small_rules() {
  Rules r;
  r.layers = {
      {"bottom", "lib/bottom", {}, {}},
      {"middle", "lib/middle", {"bottom"}, {}},
      {"side", "lib/side", {"bottom"}, {"lib/top/plain.hpp"}},
      {"top", "lib/top", {"middle"}, {}},
      {"app", "app", {"top", "side"}, {}},
  };
  r.externals = {{"boost/", {"app"}}};
  r.exceptions = {{"lib/middle/odd.cpp", "boost/any.hpp", "test"}};
  return r;
}

std::vector<std::string> reasons(const std::vector<Violation>& vs) {
  std::vector<std::string> out;
  for (const Violation& v : vs) out.push_back(to_string(v));
  return out;
}

}  // namespace

TEST(IncludesOf, DirectivesWithLinesOutsideComments) {
  const std::string text =
      "#include <vector>\n"
      "  #  include \"lib/a/b.hpp\"  // why\n"
      "// #include \"lib/commented.hpp\"\n"
      "/* #include \"lib/block.hpp\"\n"
      "#include \"lib/still_block.hpp\" */ #include \"lib/after_block.hpp\"\n"
      "#define X \"lib/not_an_include.hpp\"\n"
      "#pragma once\n"
      "#include \"unterminated.hpp\n"
      "#include\"tight.hpp\"";
  const std::vector<Include> inc = includes_of(text);
  ASSERT_EQ(inc.size(), 4u);
  EXPECT_EQ(inc[0].line, 1);
  EXPECT_EQ(inc[0].path, "vector");
  EXPECT_TRUE(inc[0].angled);
  EXPECT_EQ(inc[1].line, 2);
  EXPECT_EQ(inc[1].path, "lib/a/b.hpp");
  EXPECT_FALSE(inc[1].angled);
  EXPECT_EQ(inc[2].line, 5);
  EXPECT_EQ(inc[2].path, "lib/after_block.hpp");
  EXPECT_EQ(inc[3].line, 9);
  EXPECT_EQ(inc[3].path, "tight.hpp");
}

TEST(LayerChecker, DownwardAndTransitiveIncludesPass) {
  const LayerChecker c(small_rules());
  EXPECT_TRUE(c.check("lib/top/t.cpp", "#include \"lib/top/t.hpp\"\n#include \"lib/middle/m.hpp\"\n"
                                       "#include \"lib/bottom/b.hpp\"\n#include <vector>\n#include \"local.hpp\"\n")
                  .empty());
  EXPECT_TRUE(c.check("lib/side/s.cpp", "#include \"lib/top/plain.hpp\"\n").empty());
  EXPECT_TRUE(c.check("app/main.cpp", "#include \"lib/top/plain.hpp\"\n#include \"lib/side/s.hpp\"\n"
                                      "#include <boost/asio.hpp>\n")
                  .empty());
}

TEST(LayerChecker, PlantedUpwardIncludeIsFoundWithFileAndLine) {
  const LayerChecker c(small_rules());
  const std::vector<Violation> v = c.check("lib/bottom/b.cpp", "#include <cmath>\n\n#include \"lib/top/t.hpp\"\n");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(to_string(v[0]),
            "lib/bottom/b.cpp:3: #include \"lib/top/t.hpp\": layer 'bottom' may not include layer 'top' "
            "(not below it in the layer table)");
}

TEST(LayerChecker, SiblingsAndOtherHeadersOfAnAllowedFileAreRejected) {
  const LayerChecker c(small_rules());
  EXPECT_EQ(c.check("lib/side/s.cpp", "#include \"lib/middle/m.hpp\"\n").size(), 1u);
  EXPECT_EQ(c.check("lib/side/s.cpp", "#include \"lib/top/solver.hpp\"\n").size(), 1u);
  EXPECT_EQ(c.check("lib/middle/m.cpp", "#include \"lib/side/s.hpp\"\n").size(), 1u);
}

TEST(LayerChecker, RelativeUnknownAndUnplacedPathsAreRejected) {
  const LayerChecker c(small_rules());
  EXPECT_EQ(c.check("lib/top/t.cpp", "#include \"../bottom/b.hpp\"\n").size(), 1u);
  EXPECT_EQ(c.check("lib/top/t.cpp", "#include \"lib/nowhere/n.hpp\"\n").size(), 1u);
  const std::vector<Violation> v = c.check("misc/x.cpp", "#include <vector>\n");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].line, 0);
  EXPECT_NE(v[0].reason.find("no layer"), std::string::npos);
}

TEST(LayerChecker, ExternalHeadersStayInTheirFoldersExceptListedOnes) {
  const LayerChecker c(small_rules());
  const std::vector<Violation> v = c.check("lib/top/t.cpp", "#include <boost/asio.hpp>\n");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].reason, "headers under 'boost/' belong in app only");
  EXPECT_TRUE(c.check("lib/middle/odd.cpp", "#include <boost/any.hpp>\n").empty());
  EXPECT_EQ(c.check("lib/middle/odd.cpp", "#include <boost/asio.hpp>\n").size(), 1u);
}

TEST(LayerChecker, BadTablesAreRefused) {
  Rules cycle = small_rules();
  cycle.layers[0].uses = {"top"};
  EXPECT_THROW(LayerChecker{cycle}, std::invalid_argument);
  Rules unknown = small_rules();
  unknown.layers[1].uses = {"nothing"};
  EXPECT_THROW(LayerChecker{unknown}, std::invalid_argument);
  Rules twice = small_rules();
  twice.layers.push_back({"bottom", "lib/other", {}, {}});
  EXPECT_THROW(LayerChecker{twice}, std::invalid_argument);
}

TEST(LayerChecker, TreeScanReportsPlantedIncludeStrayFileAndUnusedException) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / ("gnssemu_layering_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(root);
  const auto write = [&](const std::string& rel, const std::string& text) {
    fs::create_directories((root / rel).parent_path());
    std::ofstream(root / rel) << text;
  };
  write("lib/bottom/b.hpp", "#pragma once\n");
  write("lib/middle/m.cpp", "#include \"lib/bottom/b.hpp\"\n#include \"lib/top/t.hpp\"\n");
  write("lib/stray/s.cpp", "\n");
  write("lib/top/notes.txt", "#include \"lib/app/x.hpp\"\n");  // not C++: not read
  const std::vector<std::string> got = reasons(LayerChecker(small_rules()).check_tree(root));
  fs::remove_all(root);
  const std::vector<std::string> want{
      "lib/middle/m.cpp:2: #include \"lib/top/t.hpp\": layer 'middle' may not include layer 'top' (not below it in "
      "the layer table)",
      "lib/stray/s.cpp:0: the file lies in no layer: add its folder to the layer table",
      "lib/middle/odd.cpp:0: #include \"boost/any.hpp\": an exception in the layer table matches no include: remove it",
  };
  EXPECT_EQ(got, want);
}

// The project's own table, with includes planted where they break it.
TEST(ProjectLayers, PlantedIncludesUpTheLayersAreFound) {
  const LayerChecker c(project_rules());
  const auto bad = [&](const std::string& file, const std::string& include) {
    return c.check(file, "#include " + include + "\n").size() == 1;
  };
  EXPECT_TRUE(bad("core/geo/geodesy.cpp", "\"core/receiver/receiver.hpp\""));
  EXPECT_TRUE(bad("core/time/gps_time.cpp", "\"core/orbit/ephemeris.hpp\""));
  EXPECT_TRUE(bad("core/observation/rinex_obs.cpp", "\"core/orbit/rinex_nav.hpp\""));
  EXPECT_TRUE(bad("core/scene/scene.cpp", "\"core/atmosphere/shells.hpp\""));
  EXPECT_TRUE(bad("core/signal/tracking.cpp", "\"core/world/world.hpp\""));
  EXPECT_TRUE(bad("core/world/world.cpp", "\"core/receiver/fix.hpp\""));
  EXPECT_TRUE(bad("core/protocol/nmea/nmea_encoder.hpp", "\"core/receiver/receiver.hpp\""));
  EXPECT_TRUE(bad("core/protocol/nmea/nmea_encoder.hpp", "\"core/protocol/ubx/wire/ubx_frame.hpp\""));
  EXPECT_TRUE(bad("core/receiver/receiver.cpp", "\"config/config.hpp\""));
  EXPECT_TRUE(bad("config/config.cpp", "\"daemon/daemon.hpp\""));
  EXPECT_TRUE(bad("daemon/daemon.cpp", "\"tools/gnssemu/batch/batch.hpp\""));
  EXPECT_TRUE(bad("core/time/gps_time.cpp", "\"tests/support/alloc_counter.hpp\""));
  EXPECT_TRUE(bad("tests/unit/geo/test_geodesy.cpp", "\"core/receiver/receiver.hpp\""));
  for (const char* ext : {"<boost/asio.hpp>", "<asio.hpp>", "<spdlog/spdlog.h>", "<fmt/format.h>", "<toml++/toml.h>",
                          "<nlohmann/json.hpp>", "<CLI/CLI.hpp>", "<embree3/rtcore.h>", "<GeographicLib/Geoid.hpp>"}) {
    EXPECT_TRUE(bad("core/receiver/receiver.cpp", ext)) << ext;
  }
}

TEST(ProjectLayers, DocumentedEdgesPass) {
  const LayerChecker c(project_rules());
  const auto good = [&](const std::string& file, const std::string& include) {
    return c.check(file, "#include " + include + "\n").empty();
  };
  EXPECT_TRUE(good("core/signal/link_budget.cpp", "\"core/atmosphere/shells.hpp\""));
  EXPECT_TRUE(good("core/atmosphere/klobuchar.hpp", "\"core/orbit/nav_data.hpp\""));
  EXPECT_TRUE(good("core/world/world.hpp", "\"core/scene/scene.hpp\""));
  EXPECT_TRUE(good("core/receiver/receiver.hpp", "\"core/world/world.hpp\""));
  EXPECT_TRUE(good("core/protocol/nmea/nmea_encoder.hpp", "\"core/receiver/fix.hpp\""));
  EXPECT_TRUE(good("core/protocol/ubx/wire/ubx_encoder.hpp", "\"core/receiver/fix.hpp\""));
  EXPECT_TRUE(good("core/protocol/ubx/wire/ubx_encoder.cpp", "\"core/protocol/ubx/config/ubx_gnss.hpp\""));
  EXPECT_TRUE(good("core/protocol/ubx/config/ubx_device_config.cpp", "\"core/protocol/ubx/wire/ubx_encoder.hpp\""));
  EXPECT_TRUE(good("daemon/daemon.cpp", "<boost/asio.hpp>"));
  EXPECT_TRUE(good("tools/gnssemu/sky.cpp", "\"daemon/truth_track.hpp\""));
  EXPECT_TRUE(good("tests/unit/nmea/test_nmea_alloc.cpp", "\"tests/support/alloc_counter.hpp\""));
  EXPECT_TRUE(good("tests/unit/cli/test_batch.cpp", "\"config/config.hpp\""));
  EXPECT_TRUE(good("config/setup/footprint_file.cpp", "<toml++/toml.h>"));
}

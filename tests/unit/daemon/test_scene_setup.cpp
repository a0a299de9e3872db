// SPDX-License-Identifier: Apache-2.0
// The daemon logs what the mesh reader skipped (count and first file:line).
#include <gtest/gtest.h>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/config.hpp"
#include "daemon/scene_setup.hpp"

namespace gnssemu::daemon {
namespace {

TEST(SceneSetup, SkippedMeshElementsAreLoggedAsAWarning) {
  const auto dir = std::filesystem::temp_directory_path() / "gnssemu_daemon_scene_test";
  std::filesystem::create_directories(dir);
  const std::string mesh = (dir / "w.obj").string();
  std::ofstream(mesh) << "v 500 -10 0\nv 500 10 0\nv 500 10 30\nv 500 -10 30\nf 1 2 3\nf 1 3 4\nf 1 2 9\n";
  const std::string text = "[origin]\nlat_deg = 48.8738\nlon_deg = 2.2950\nheight_m = 100.0\n\n[nav]\nfile = \"" +
                           std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n\"\n\n[scene]\nmesh = \"" + mesh + "\"\n";
  const config::Config cfg = config::parse_config(text, "t.toml", dir.string());

  std::ostringstream log;
  auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(log);
  auto previous = spdlog::default_logger();
  spdlog::set_default_logger(std::make_shared<spdlog::logger>("test", sink));
  const auto s = load_scene_logged(cfg);
  spdlog::set_default_logger(previous);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->triangle_count(), 2u);
  const std::string out = log.str();
  EXPECT_NE(out.find("[warning]"), std::string::npos) << out;
  EXPECT_NE(out.find("scene mesh: 1 bad elements skipped (1 bad index, 0 NaN/inf, 0 degenerate); first: " + mesh +
                     ":7: face refers to a vertex that does not exist"),
            std::string::npos)
      << out;
}

}  // namespace
}  // namespace gnssemu::daemon

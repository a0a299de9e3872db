// SPDX-License-Identifier: Apache-2.0
// Footprint files (config/footprint_file): the TOML text of extruded
// buildings, read into core/scene's FootprintBuilder; every error names
// file:line; config::load_mesh reads them by extension.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "config/setup/footprint_file.hpp"
#include "core/common/error.hpp"
#include "core/scene/scene.hpp"
#include "test_helpers.hpp"

namespace gnssemu::config {
namespace {

using scene::Mesh;
using scene::Ray;
using scene::Scene;

std::string temp_file(const std::string& name, const std::string& content) {
  const auto dir = std::filesystem::temp_directory_path() / "gnssemu_footprint_test";
  std::filesystem::create_directories(dir);
  const auto p = dir / name;
  std::ofstream(p, std::ios::binary | std::ios::trunc) << content;
  return p.string();
}

using test::expect_error;

TEST(Footprints, ExtrudedClosedBuildingsAndGround) {
  const std::string p = temp_file("fp.toml",
                                  "[ground]\nhalf_size_m = 500\nmaterial = \"concrete\"\n"
                                  "[[building]]\nfootprint = [[0, 0], [10, 0], [10, 20], [0, 20]]\nheight_m = 15\n"
                                  "material = \"glass\"\n"
                                  "[[building]]  # L-shaped, clockwise, concave\n"
                                  "footprint = [[30, 0], [30, 20], [35, 20], [35, 5], [50, 5], [50, 0]]\n"
                                  "height_m = 30\nbase_m = 2\n");
  const Mesh m = load_mesh(p);
  EXPECT_EQ(m.stats.skipped(), 0);
  // ground 2 + box (4 walls x 2 + roof 2 + floor 2) + L (6 walls x 2 + roof 4 + floor 4)
  EXPECT_EQ(m.triangles.size(), 2u + 12u + 20u);
  const Scene s(m);
  EXPECT_DOUBLE_EQ(s.bounds_max_m().z, 32.0);
  // Closed: a point inside the concave part is enclosed; the notch is open.
  EXPECT_TRUE(s.occluded(Ray{Vec3(32.0, 10.0, 10.0), Vec3(0, 0, 1), 0.0, 1e30}));
  EXPECT_TRUE(s.occluded(Ray{Vec3(32.0, 10.0, 10.0), Vec3(0, 0, -1), 0.0, 1e30}));
  EXPECT_FALSE(s.occluded(Ray{Vec3(45.0, 15.0, 10.0), Vec3(0, 0, 1), 0.0, 1e30}));
}

TEST(Footprints, ErrorsNameFileAndLine) {
  expect_error([] { load_mesh(temp_file("f1.toml", "[[building]]\nfootprint = [[0, 0], [1, 0]]\nheight_m = 5\n")); },
               {"f1.toml:2:", "at least 3"});
  expect_error([] { load_mesh(temp_file("f2.toml", "[[building]]\nfootprint = [[0,0],[1,0],[0,1]]\nheight_m = -5\n")); },
               {"f2.toml:3:", "height_m"});
  expect_error([] { load_mesh(temp_file("f3.toml", "[[building]]\nfootprint = [[0,0],[1,0],[0,1]]\nhieght_m = 5\n")); },
               {"f3.toml:3:", "unknown key 'hieght_m'"});
  expect_error([] {
    load_mesh(temp_file("f4.toml", "[[building]]\nfootprint = [[0,0],[4,4],[4,0],[0,3]]\nheight_m = 5\n"));
  }, {"f4.toml:2:", "self-intersecting"});
  expect_error([] { load_mesh(temp_file("f5.toml", "[[building]]\nfootprint = [[0,0],[1,0],[0,\n")); },
               {"f5.toml:", "TOML syntax"});
}

TEST(Footprints, RepeatedPointIsDroppedNotSelfIntersecting) {
  // A point entered twice (consecutively, or closing the ring) adds no edge.
  const Mesh m = load_mesh(temp_file(
      "dup.toml", "[[building]]\nfootprint = [[0,0],[10,0],[10,0],[10,20],[0,20],[0,0]]\nheight_m = 5\n"));
  EXPECT_EQ(m.triangles.size(), 12u);  // 4 walls + roof + floor
  EXPECT_EQ(m.stats.skipped(), 0);
  expect_error([] { load_mesh(temp_file("dup2.toml", "[[building]]\nfootprint = [[0,0],[1,0],[1,0],[0,0]]\nheight_m = 5\n")); },
               {"dup2.toml:2:", "at least 3 distinct points"});
}

TEST(Footprints, CoordinatesBeyondFloat32RangeAreRejected) {
  // Buildings and the ground name their own lines.
  expect_error([] {
    load_mesh(temp_file("farfp.toml", "[[building]]\nheight_m = 5\nfootprint = [[2000000, 0], [2000010, 0], [2000000, 10]]\n"));
  }, {"farfp.toml:3:", "beyond 1e6 m"});
  expect_error([] { load_mesh(temp_file("farground.toml", "\n[ground]\nhalf_size_m = 3000000\n")); },
               {"farground.toml:2:", "beyond 1e6 m"});
}

TEST(Footprints, WithoutTheConfigReaderCoreRefusesThem) {
  const std::string p = temp_file("core.toml", "[[building]]\nfootprint = [[0,0],[1,0],[0,1]]\nheight_m = 5\n");
  expect_error([&] { scene::load_mesh(p); }, {"core.toml", "footprint reader"});
  EXPECT_EQ(load_mesh(p).triangles.size(), 8u);
}

}  // namespace
}  // namespace gnssemu::config

// SPDX-License-Identifier: Apache-2.0
// [scene] (config/scene_keys): mesh path relative to the config file,
// placement, search effort, material losses; file:line errors; round trip
// through to_toml.
#include <gtest/gtest.h>

#include "test_helpers.hpp"

namespace gnssemu::config::scene_keys_test {
namespace {

using test::error_of;
using test::kBase;
using test::parse;

const std::string kScene = kBase +
                           "[scene]\n"                                   // line 7
                           "mesh = \"scenes/street_canyon.toml\"\n"
                           "offset_m = [10.0, -5.5, 0.25]\n"
                           "yaw_deg = 90.0\n"                            // line 10
                           "scale = 1.0\n"
                           "up_axis = \"z\"\n"
                           "rays = 512\n"
                           "azimuth_rays = 64\n"
                           "max_bounces = 8\n"                           // line 15
                           "reuse_distance_m = 0.5\n"
                           "reuse_angle_deg = 0.25\n"
                           "min_arrival_elevation_deg = 2.0\n"
                           "max_loss_db = 18.0\n"
                           "reflection_loss_db = 3.5\n"                  // line 20
                           "[scene.material_loss_db]\n"
                           "glass = 1.5\n";

TEST(ConfigScene, EveryKeyParsed) {
  const Config c = parse(kScene);
  ASSERT_TRUE(c.scene.has_value());
  const SceneConfig& s = *c.scene;
  EXPECT_EQ(s.mesh_file, test::kData + "/scenes/street_canyon.toml");
  EXPECT_EQ(s.placement.offset_m, Enu(10.0, -5.5, 0.25));
  EXPECT_NEAR(s.placement.yaw_rad, kPi / 2.0, 1e-15);
  EXPECT_FALSE(s.placement.y_up);
  EXPECT_EQ(s.search.rays, 512);
  EXPECT_EQ(s.search.azimuth_rays, 64);
  EXPECT_EQ(s.search.max_bounces, 8);
  EXPECT_EQ(s.search.reuse_distance_m, 0.5);
  EXPECT_NEAR(s.search.reuse_angle_rad, 0.25 * kDegToRad, 1e-15);
  EXPECT_NEAR(s.search.min_arrival_el_rad, 2.0 * kDegToRad, 1e-15);
  EXPECT_EQ(s.search.max_loss_db, 18.0);
  EXPECT_EQ(s.reflection_loss_db, 3.5);
  ASSERT_EQ(s.material_loss_db.size(), 1u);
  EXPECT_EQ(s.material_loss_db[0].name, "glass");
  EXPECT_EQ(s.material_loss_db[0].loss_db, 1.5);
  EXPECT_EQ(s.material_loss_db[0].line, 22);
}

TEST(ConfigScene, ErrorsNameFileAndLine) {
  EXPECT_NE(error_of(kBase + "[scene]\nmesh = \"scenes/nope.obj\"\n").find("t.toml:8: scene.mesh: 'scenes/nope.obj' not found"),
            std::string::npos);
  EXPECT_NE(error_of(kBase + "[scene]\nmesh = \"scenes/empty.obj\"\nrays = 3\n").find("t.toml:9:"), std::string::npos);
  EXPECT_NE(error_of(kBase + "[scene]\nmesh = \"scenes/empty.obj\"\nbounces = 3\n").find("t.toml:9:"),
            std::string::npos);
  EXPECT_NE(error_of(kBase + "[scene]\nmesh = \"scenes/empty.obj\"\noffset_m = [1, 2]\n").find("t.toml:9:"),
            std::string::npos);
  EXPECT_NE(error_of(kBase + "[scene]\nmesh = \"scenes/empty.obj\"\nup_axis = \"x\"\n").find("t.toml:9:"),
            std::string::npos);
  EXPECT_NE(error_of(kBase + "[scene]\nmesh = \"scenes/empty.obj\"\nscale = 0\n").find("t.toml:9:"), std::string::npos);
  EXPECT_NE(error_of(kBase + "[scene]\noffset_m = [0, 0, 0]\n").find("t.toml:7:"), std::string::npos);
}

TEST(ConfigScene, RoundTrip) {
  const Config c = parse(kScene);
  const std::string text = to_toml(c, test::kData);
  EXPECT_NE(text.find("mesh = \"scenes/street_canyon.toml\""), std::string::npos) << text;
  const Config back = parse_config(text, "written.toml", test::kData);
  ASSERT_TRUE(back.scene.has_value());
  EXPECT_EQ(back.scene->mesh_file, c.scene->mesh_file);
  EXPECT_EQ(back.scene->placement.offset_m, c.scene->placement.offset_m);
  EXPECT_EQ(back.scene->placement.yaw_rad, c.scene->placement.yaw_rad);
  EXPECT_EQ(back.scene->search.rays, 512);
  EXPECT_EQ(back.scene->search.azimuth_rays, 64);
  EXPECT_EQ(back.scene->search.reuse_angle_rad, c.scene->search.reuse_angle_rad);
  EXPECT_EQ(back.scene->search.min_arrival_el_rad, c.scene->search.min_arrival_el_rad);
  EXPECT_EQ(back.scene->search.max_loss_db, 18.0);
  ASSERT_EQ(back.scene->material_loss_db.size(), 1u);
  EXPECT_EQ(back.scene->material_loss_db[0].loss_db, 1.5);
  EXPECT_EQ(to_toml(back, test::kData), text);
}

}  // namespace
}  // namespace gnssemu::config::scene_keys_test

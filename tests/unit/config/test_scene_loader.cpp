// SPDX-License-Identifier: Apache-2.0
// load_scene (config/scene_loader): the configured mesh placed in the
// origin's ENU frame with its reflection losses; a material name the mesh
// does not have names the config file and line.
#include <gtest/gtest.h>

#include "config/setup/scene_loader.hpp"
#include "test_helpers.hpp"

namespace gnssemu::config::scene_loader_test {
namespace {

using test::kBase;
using test::parse;

// The mesh placed: turned 90 deg and offset.
const std::string kScene = kBase +
                           "[scene]\n"
                           "mesh = \"scenes/street_canyon.toml\"\n"
                           "offset_m = [10.0, -5.5, 0.25]\n"
                           "yaw_deg = 90.0\n";

TEST(ConfigScene, LoadsThePlacedMesh) {
  const Config c = parse(kScene);
  // The scene loads, placed: the 400 m ground turned 90 deg and offset.
  scene::MeshStats stats;
  const auto sc = load_scene(c, &stats);
  ASSERT_NE(sc, nullptr);
  EXPECT_EQ(stats.skipped(), 0);
  EXPECT_EQ(sc->triangle_count(), 2u + 12u + 12u);
  EXPECT_NEAR(sc->bounds_min_m().y, -5.5 - 400.0, 1e-3);
  EXPECT_NEAR(sc->bounds_max_m().x, 10.0 + 400.0, 1e-3);
  EXPECT_NEAR(sc->bounds_max_m().z, 30.25, 1e-3);
}

TEST(ConfigScene, NoSceneSectionNoScene) {
  const Config c = parse(kBase);
  EXPECT_FALSE(c.scene.has_value());
  EXPECT_EQ(load_scene(c), nullptr);
}

TEST(ConfigScene, UnknownMaterialNamesTheConfigLine) {
  // A material the mesh does not have: config file and line.
  const Config c = parse(kBase + "[scene]\nmesh = \"scenes/street_canyon.toml\"\n[scene.material_loss_db]\nmarble = 2\n");
  try {
    load_scene(c);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("t.toml:10: scene.material_loss_db.marble"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("concrete, glass"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gnssemu::config::scene_loader_test

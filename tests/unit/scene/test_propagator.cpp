// SPDX-License-Identifier: Apache-2.0
// Correctness anchors of the propagation search: closed-form one- and
// two-bounce paths, a closed building, grazing rays, an empty scene.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/common/error.hpp"
#include "core/scene/mesh.hpp"
#include "core/scene/propagator.hpp"
#include "core/scene/scene.hpp"
#include "scene_test_util.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::scene {
namespace {

using test::add_box;
using test::add_wall_y;
using test::direction;

constexpr double kFar = 5000.0;  // "infinite" walls: far beyond any path here

SatPath one(Propagator& p, const Enu& rx, const Enu& dir) {
  SatQuery q{1, dir};
  SatPath out;
  p.compute(rx, std::span<const SatQuery>(&q, 1), std::span<SatPath>(&out, 1));
  return out;
}

// Reflecting wall y = +D (infinite), receiver at the origin, a blocker wall
// y = -5 of height 10 m hides satellites to the south at 30 deg; the
// reflection leaves from high on the north wall and clears the blocker.
TEST(Propagation, OneInfiniteWallMatchesClosedForm) {
  const double d_m = 20.0, h_m = 1.5;
  MeshBuilder b("wall", {});
  add_wall_y(b, d_m, -kFar, kFar, -1.0, kFar);
  add_wall_y(b, -5.0, -kFar, kFar, -1.0, 10.0);
  const Mesh mesh = std::move(b).finish();
  const Scene scene(mesh);
  ASSERT_TRUE(scene.vertical_horizontal());
  for (const int azimuth_rays : {360, 0}) {  // elevation cone, then the whole hemisphere
  SearchConfig cfg;
  cfg.azimuth_rays = azimuth_rays;
  Propagator prop(scene, cfg);
  const Enu rx(0.0, 0.0, h_m);
  for (const double el : {25.0, 30.0, 40.0}) {
    for (const double daz : {0.0, 20.0, -35.0, 50.0}) {
      const SatPath p = one(prop, rx, direction(180.0 + daz, el));
      // Extra path of a plane wave reflected by a plane at distance D:
      // 2 D (d . n) = 2 D cos(el) cos(az - az_normal).
      const double expect_m = 2.0 * d_m * std::cos(el * kDegToRad) * std::cos(daz * kDegToRad);
      ASSERT_EQ(p.kind, PathKind::kNlos) << "el " << el << " daz " << daz;
      EXPECT_EQ(p.bounces, 1);
      EXPECT_NEAR(p.extra_delay_m, expect_m, 1e-4) << "el " << el << " daz " << daz;
      EXPECT_DOUBLE_EQ(p.loss_db, 3.0);
      // Arrives from the north wall, mirrored satellite direction.
      EXPECT_GT(p.arrival_dir.y, 0.0);
      EXPECT_NEAR(p.arrival_dir.z, std::sin(el * kDegToRad), 1e-9);
    }
  }
  // A satellite above the blocker is direct.
  const SatPath los = one(prop, rx, direction(180.0, 70.0));
  EXPECT_EQ(los.kind, PathKind::kLos);
  EXPECT_EQ(los.extra_delay_m, 0.0);
  EXPECT_EQ(los.loss_db, 0.0);
  }
}

// Ground plane and a wall floating above it (z in [7, 100] m) 20 m north:
// the direct ray to a satellite north at 20 deg meets the wall at 8.78 m;
// the ground reflection, unfolded from the image antenna at -h, passes at
// 5.78 m, under the wall. It arrives from -20 deg, so it exists only when
// min_arrival_el allows it; its extra path is 2 h sin(el). The elevation
// cone must launch the mirrored (downward) cone too.
TEST(Propagation, GroundReflectionUnderAFloatingWallConeAndHemisphere) {
  const double h_m = 1.5, el = 20.0;
  MeshBuilder b("ground_wall", {});
  test::add_quad(b, {-kFar, -kFar, 0.0}, {kFar, -kFar, 0.0}, {kFar, kFar, 0.0}, {-kFar, kFar, 0.0});
  add_wall_y(b, 20.0, -kFar, kFar, 7.0, 100.0);
  const Mesh mesh = std::move(b).finish();
  const Scene scene(mesh);
  ASSERT_TRUE(scene.vertical_horizontal());
  const Enu rx(0.0, 0.0, h_m);
  for (const int azimuth_rays : {128, 0}) {
    SearchConfig cfg;
    cfg.azimuth_rays = azimuth_rays;
    cfg.min_arrival_el_rad = -30.0 * kDegToRad;
    Propagator prop(scene, cfg);
    const SatPath p = one(prop, rx, direction(0.0, el));
    ASSERT_EQ(p.kind, PathKind::kNlos) << "azimuth_rays " << azimuth_rays;
    EXPECT_EQ(p.bounces, 1);
    EXPECT_NEAR(p.extra_delay_m, 2.0 * h_m * std::sin(el * kDegToRad), 1e-4);
    EXPECT_NEAR(p.arrival_dir.z, -std::sin(el * kDegToRad), 1e-9);
    // The default antenna mask (0 deg) rejects the arrival from below.
    SearchConfig masked = cfg;
    masked.min_arrival_el_rad = 0.0;
    Propagator prop0(scene, masked);
    EXPECT_EQ(one(prop0, rx, direction(0.0, el)).kind, PathKind::kNone) << "azimuth_rays " << azimuth_rays;
  }
}

// Sionna's simple_street_canyon (Apache-2.0, tests/data/scenes): an
// east-west street between 50.94 m towers (wood south, marble north at
// x in [-15, 16]). From the street centre a satellite due south at 30 deg
// is blocked; a N-S ray climbs tan(30) per metre, so the first path over
// the south tower is 5 bounces (N, S, N, S, N): unfolded, the antenna's
// image is at y5 = 6a + 4b (a, b: distances to the north and south
// facades) and the extra path is cos(el) y5; 5 x 3 dB. At 15 deg it takes
// 10 bounces starting south (image at 10 (a + b); 30 dB): not received
// under the 21 dB default cap.
TEST(Propagation, SionnaSimpleStreetCanyonDeepPathsClosedForm) {
  const Mesh mesh = load_mesh(std::string(GNSSEMU_TEST_DATA) + "/scenes/simple_street_canyon/simple_street_canyon.obj");
  EXPECT_EQ(mesh.triangles.size(), 74u);
  const Scene scene(mesh);
  ASSERT_TRUE(scene.vertical_horizontal());
  const Enu rx(0.0, 0.0, 1.5);
  const double a = scene.intersect(Ray{rx, Vec3(0.0, 1.0, 0.0), 0.0, 1e30}).t_m;
  const double b = scene.intersect(Ray{rx, Vec3(0.0, -1.0, 0.0), 0.0, 1e30}).t_m;
  ASSERT_NEAR(a, 9.57, 0.05);
  ASSERT_NEAR(b, 8.61, 0.05);
  for (const int azimuth_rays : {128, 0}) {
    SearchConfig cfg;
    cfg.azimuth_rays = azimuth_rays;
    cfg.rays = 4096;
    Propagator prop(scene, cfg);
    const SatPath p = one(prop, rx, direction(180.0, 30.0));
    ASSERT_EQ(p.kind, PathKind::kNlos) << azimuth_rays;
    EXPECT_EQ(p.bounces, 5);
    EXPECT_NEAR(p.extra_delay_m, std::cos(30.0 * kDegToRad) * (6.0 * a + 4.0 * b), 1e-3);
    EXPECT_DOUBLE_EQ(p.loss_db, 15.0);
    EXPECT_EQ(one(prop, rx, direction(180.0, 85.0)).kind, PathKind::kLos);
    EXPECT_EQ(one(prop, rx, direction(180.0, 15.0)).kind, PathKind::kNone);
    cfg.max_loss_db = 1000.0;
    Propagator uncapped(scene, cfg);
    const SatPath deep = one(uncapped, rx, direction(180.0, 15.0));
    ASSERT_EQ(deep.kind, PathKind::kNlos) << azimuth_rays;
    EXPECT_EQ(deep.bounces, 10);
    EXPECT_NEAR(deep.extra_delay_m, std::cos(15.0 * kDegToRad) * 10.0 * (a + b), 1e-3);
    EXPECT_DOUBLE_EQ(deep.loss_db, 30.0);
  }
}

// Street canyon: walls y = +-W/2 of height H. The south wall blocks the
// direct signal and the one-bounce path; the two-bounce path (south wall,
// then north wall) leaves high enough. Unfolded, its extra length is
// 2 W cos(el) cos(daz), independent of where the receiver stands across the street.
TEST(Propagation, TwoWallCanyonTwoBouncePaths) {
  const double w_m = 20.0, wall_m = 15.0, h_m = 1.5, el = 20.0;
  MeshBuilder b("canyon", {});
  add_wall_y(b, w_m / 2.0, -kFar, kFar, 0.0, wall_m);
  add_wall_y(b, -w_m / 2.0, -kFar, kFar, 0.0, wall_m);
  const Scene scene(std::move(b).finish());
  for (const int azimuth_rays : {360, 0}) {
  SearchConfig cfg;
  cfg.azimuth_rays = azimuth_rays;
  Propagator prop(scene, cfg);
  for (const double y0 : {0.0, -3.0}) {
    for (const double daz : {0.0, 15.0}) {
      const Enu dir = direction(180.0 + daz, el);
      const double c = std::cos(el * kDegToRad) * std::cos(daz * kDegToRad);  // |d.y|
      const double rise = std::tan(el * kDegToRad) / std::cos(daz * kDegToRad);  // dz per metre across
      // Heights where the one- and two-bounce paths cross the south wall top.
      const double one_bounce_z = h_m + (w_m / 2.0 - y0 + w_m) * rise;
      const double two_bounce_z = h_m + (y0 + w_m / 2.0 + 2.0 * w_m) * rise;
      ASSERT_LT(one_bounce_z, wall_m);
      ASSERT_GT(two_bounce_z, wall_m);
      const SatPath p = one(prop, Enu(0.0, y0, h_m), dir);
      ASSERT_EQ(p.kind, PathKind::kNlos) << "y0 " << y0 << " daz " << daz;
      EXPECT_EQ(p.bounces, 2);
      EXPECT_NEAR(p.extra_delay_m, 2.0 * w_m * c, 1e-4);
      EXPECT_DOUBLE_EQ(p.loss_db, 6.0);
    }
  }
  // Higher: the one-bounce path clears the wall and wins (less loss).
  const double el1 = 32.0;
  const SatPath p1 = one(prop, Enu(0.0, 0.0, h_m), direction(180.0, el1));
  ASSERT_EQ(p1.kind, PathKind::kNlos);
  EXPECT_EQ(p1.bounces, 1);
  EXPECT_NEAR(p1.extra_delay_m, 2.0 * (w_m / 2.0) * std::cos(el1 * kDegToRad), 1e-4);
  }
}

TEST(Propagation, PerMaterialLossEntersThePath) {
  MeshBuilder b("wall", {});
  b.set_material("glass");
  add_wall_y(b, 20.0, -kFar, kFar, -1.0, kFar);
  b.set_material("concrete");
  add_wall_y(b, -5.0, -kFar, kFar, -1.0, 10.0);
  Scene scene(std::move(b).finish());
  ASSERT_TRUE(scene.set_material_loss_db("glass", 1.5));
  EXPECT_FALSE(scene.set_material_loss_db("unobtainium", 1.0));
  Propagator prop(scene, SearchConfig{});
  const SatPath p = one(prop, Enu(0.0, 0.0, 1.5), direction(180.0, 30.0));
  ASSERT_EQ(p.kind, PathKind::kNlos);
  EXPECT_DOUBLE_EQ(p.loss_db, 1.5);
  // A loss cap turns the path off.
  SearchConfig capped;
  capped.max_loss_db = 1.0;
  Propagator weak(scene, capped);
  EXPECT_EQ(one(weak, Enu(0.0, 0.0, 1.5), direction(180.0, 30.0)).kind, PathKind::kNone);
}

TEST(Propagation, ReceiverInsideClosedBuildingReceivesNothing) {
  MeshBuilder b("box", {});
  add_box(b, {-10.0, -10.0, 0.0}, {10.0, 10.0, 30.0});
  add_box(b, {40.0, -10.0, 0.0}, {60.0, 10.0, 30.0});  // a neighbour to reflect on, outside
  const Scene scene(std::move(b).finish());
  SearchConfig cfg;
  cfg.rays = 4096;
  Propagator prop(scene, cfg);
  std::vector<SatQuery> sats;
  for (int i = 0; i < 24; ++i) sats.push_back({i, direction(15.0 * i, 5.0 + 3.5 * i)});
  std::vector<SatPath> out(sats.size());
  prop.compute(Enu(1.0, 2.0, 1.5), sats, out);
  for (const SatPath& p : out) EXPECT_EQ(p.kind, PathKind::kNone);
  EXPECT_EQ(prop.stats().searched, 24);
  // Outside, between the two buildings, satellites are received.
  prop.compute(Enu(25.0, 0.0, 1.5), sats, out);
  int received = 0;
  for (const SatPath& p : out) received += p.kind != PathKind::kNone;
  EXPECT_GT(received, 12);
}

// Rays through shared edges and vertices of a closed box must not leak
// through the cracks (Embree robust mode); rays along a face plane or
// touching a corner give a finite, deterministic answer.
TEST(Propagation, GrazingEdgesAndVertices) {
  MeshBuilder b("box", {});
  add_box(b, {0.0, 0.0, 0.0}, {10.0, 10.0, 20.0});
  const Scene scene(std::move(b).finish());
  // Through the vertical edge x = y = 0 into the interior.
  EXPECT_TRUE(scene.occluded(Ray{Vec3(-10.0, -10.0, 5.0), Vec3(1.0, 1.0, 0.05) / std::sqrt(2.0025), 0.0, 1e30}));
  // Through the diagonal shared by the two floor triangles (x = y) and the
  // roof diagonal, from below.
  for (double s = 0.5; s < 10.0; s += 0.5) {
    EXPECT_TRUE(scene.occluded(Ray{Vec3(s, s, -10.0), Vec3(0.0, 0.0, 1.0), 0.0, 1e30})) << s;
    EXPECT_TRUE(scene.occluded(Ray{Vec3(s, 10.0 - s, -10.0), Vec3(0.0, 0.0, 1.0), 0.0, 1e30})) << s;
  }
  // Through the corner vertex (0, 0, 20) into the roof-wall corner region.
  const Vec3 to_corner = Vec3(10.0, 10.0, 19.0) / std::sqrt(10.0 * 10.0 * 2.0 + 19.0 * 19.0);
  const Vec3 corner_dir = Vec3(10.0, 10.0, 21.0) / Vec3(10.0, 10.0, 21.0).norm();
  EXPECT_TRUE(scene.occluded(Ray{Vec3(-10.0, -10.0, 1.0), to_corner, 0.0, 1e30}));
  const bool touch1 = scene.occluded(Ray{Vec3(-10.0, -10.0, -1.0), corner_dir, 0.0, 1e30});
  const bool touch2 = scene.occluded(Ray{Vec3(-10.0, -10.0, -1.0), corner_dir, 0.0, 1e30});
  EXPECT_EQ(touch1, touch2);

  Propagator prop(scene, SearchConfig{});
  const std::vector<std::pair<Enu, Enu>> cases = {
      {Enu(0.0, -10.0, 5.0), Enu(0.0, 1.0, 0.1)},     // in the plane of the west wall
      {Enu(-5.0, 5.0, 20.0), Enu(1.0, 0.0, 0.0)},     // along the roof plane, el 0
      {Enu(-10.0, -10.0, -1.0), Enu(corner_dir)},     // touching the roof corner
      {Enu(10.0, 10.0, 0.0), Enu(1.0, 1.0, 1.0)},     // starting on the corner
      {Enu(5.0, -10.0, 20.0), Enu(0.0, 1.0, 1e-7)},   // skimming the roof
  };
  for (const auto& [rx, dir] : cases) {
    const SatPath p = one(prop, rx, dir);
    EXPECT_TRUE(std::isfinite(p.extra_delay_m));
    EXPECT_TRUE(std::isfinite(p.loss_db));
    EXPECT_TRUE(p.arrival_dir.finite());
    EXPECT_GE(p.extra_delay_m, -1e-3);
    const SatPath again = one(prop, rx, dir);
    EXPECT_EQ(again.kind, p.kind);
    EXPECT_EQ(again.extra_delay_m, p.extra_delay_m);
  }
}

TEST(Propagation, EmptySceneIsIdenticalToNoScene) {
  const Scene scene(Mesh{});
  EXPECT_TRUE(scene.empty());
  Propagator prop(scene, SearchConfig{});
  std::vector<SatQuery> sats;
  for (int i = 0; i < 12; ++i) sats.push_back({i, direction(30.0 * i, 2.0 + 7.0 * i)});
  std::vector<SatPath> out(sats.size());
  prop.compute(Enu(0.0, 0.0, 0.0), sats, out);
  for (const SatPath& p : out) {
    EXPECT_EQ(p.kind, PathKind::kLos);
    EXPECT_EQ(p.extra_delay_m, 0.0);
    EXPECT_EQ(p.loss_db, 0.0);
  }
  EXPECT_EQ(prop.stats().rays, 0u);  // no scene, no ray work
}

TEST(Propagation, ReuseKeepsThePathWithinThresholds) {
  MeshBuilder b("wall", {});
  add_wall_y(b, 20.0, -kFar, kFar, -1.0, kFar);
  add_wall_y(b, -5.0, -kFar, kFar, -1.0, 10.0);
  const Scene scene(std::move(b).finish());
  SearchConfig cfg;
  cfg.reuse_distance_m = 1.0;
  cfg.reuse_angle_rad = 0.01;
  Propagator prop(scene, cfg);
  const Enu dir = direction(180.0, 30.0);
  const SatPath p0 = one(prop, Enu(0.0, 0.0, 1.5), dir);
  EXPECT_EQ(prop.stats().searched, 1);
  EXPECT_NEAR(p0.extra_delay_m, 2.0 * 20.0 * std::cos(30.0 * kDegToRad), 1e-4);
  // Moved 0.5 m: no search; the path is re-solved on the same wall (LOS
  // ray, one bounce, exit ray) and its delay follows the receiver exactly.
  const SatPath p1 = one(prop, Enu(0.0, 0.5, 1.5), dir);
  EXPECT_EQ(prop.stats().reused, 1);
  EXPECT_EQ(prop.stats().searched, 0);
  EXPECT_EQ(prop.stats().rays, 3u);
  EXPECT_NEAR(p1.extra_delay_m, 2.0 * 19.5 * std::cos(30.0 * kDegToRad), 1e-4);
  const SatPath p2 = one(prop, Enu(0.0, 2.0, 1.5), dir);  // moved 2 m: searched again
  EXPECT_EQ(prop.stats().searched, 1);
  EXPECT_NEAR(p2.extra_delay_m, 2.0 * 18.0 * std::cos(30.0 * kDegToRad), 1e-4);
  prop.reset();
  one(prop, Enu(0.0, 2.0, 1.5), dir);
  EXPECT_EQ(prop.stats().reused, 0);
}

TEST(Propagation, ComputeDoesNotAllocateAfterConstruction) {
  MeshBuilder b("canyon", {});
  add_wall_y(b, 10.0, -kFar, kFar, 0.0, 15.0);
  add_wall_y(b, -10.0, -kFar, kFar, 0.0, 15.0);
  add_box(b, {30.0, -10.0, 0.0}, {50.0, 10.0, 40.0});
  const Scene scene(std::move(b).finish());
  SearchConfig cfg;
  cfg.reuse_distance_m = 0.3;
  Propagator prop(scene, cfg);
  std::vector<SatQuery> sats;
  for (int i = 0; i < 12; ++i) sats.push_back({i + 1, direction(30.0 * i, 5.0 + 6.0 * i)});
  std::vector<SatPath> out(sats.size());
  prop.compute(Enu(0.0, 0.0, 1.5), sats, out);
  const long before = support::allocation_count();
  int nlos = 0;
  for (int k = 0; k < 50; ++k) {
    prop.compute(Enu(0.25 * k, 0.1 * k - 2.0, 1.5), sats, out);
    for (const SatPath& p : out) nlos += p.kind == PathKind::kNlos;
  }
  EXPECT_EQ(support::allocation_count() - before, 0);
  EXPECT_GT(nlos, 0);
}

TEST(Propagation, BadSearchConfigThrows) {
  const Scene scene(Mesh{});
  SearchConfig c;
  c.rays = 3;
  EXPECT_THROW(Propagator p(scene, c), gnssemu::Error);
  c = SearchConfig{};
  c.max_bounces = 0;
  EXPECT_THROW(Propagator p(scene, c), gnssemu::Error);
  c = SearchConfig{};
  c.match_factor = std::nan("");
  EXPECT_THROW(Propagator p(scene, c), gnssemu::Error);
}

}  // namespace
}  // namespace gnssemu::scene

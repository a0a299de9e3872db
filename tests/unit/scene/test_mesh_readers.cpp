// SPDX-License-Identifier: Apache-2.0
// Mesh readers: OBJ, PLY (ascii and binary); placement; bad input ->
// file:line error or skipped-and-counted, never a crash. Footprint files
// are read above core: tests/unit/config/test_footprint_file.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/common/error.hpp"
#include "core/scene/mesh.hpp"
#include "core/scene/scene.hpp"
#include "scene_test_util.hpp"

namespace gnssemu::scene {
namespace {

using test::temp_file;

// Runs f, expects a gnssemu::Error whose message contains every piece.
template <class F>
void expect_error(F f, std::initializer_list<std::string> pieces) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    for (const std::string& p : pieces) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

TEST(ObjReader, ReadsPolygonsMaterialsAndRelativeIndices) {
  const std::string p = temp_file("ok.obj",
                                  "# comment\n"
                                  "mtllib x.mtl\n"
                                  "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\n"
                                  "vt 0 0\nvn 0 0 1\n"
                                  "usemtl glass\n"
                                  "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
                                  "usemtl brick\n"
                                  "v 0 0 5\nv 1 0 5\nv 0 1 5\n"
                                  "f -3 -2 -1\n");
  const Mesh m = load_mesh(p);
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(m.stats.faces_read, 2);
  EXPECT_EQ(m.stats.skipped(), 0);
  EXPECT_EQ(m.material_names.size(), 3u);  // "", glass, brick
  EXPECT_EQ(m.material_names[m.material[0]], "glass");
  EXPECT_EQ(m.material_names[m.material[2]], "brick");
  EXPECT_EQ(m.triangles[2][0], 4u);
  EXPECT_EQ(m.triangles[2][2], 6u);
}

TEST(ObjReader, BadElementsAreSkippedAndCounted) {
  const std::string p = temp_file("bad.obj",
                                  "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                  "v nan 0 0\n"
                                  "v 2 0 0\n"
                                  "f 1 2 3\n"     // ok
                                  "f 1 2 9\n"     // line 7: index out of range
                                  "f 1 2 4\n"     // line 8: NaN vertex
                                  "f 1 2 5\n"     // line 9: collinear
                                  "f 1 1 2\n"     // line 10: repeated index
                                  "f 1 2\n");     // line 11: two vertices
  const Mesh m = load_mesh(p);
  EXPECT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.stats.skipped_bad_index, 1);
  EXPECT_EQ(m.stats.skipped_nonfinite, 1);
  EXPECT_EQ(m.stats.skipped_degenerate, 3);
  EXPECT_NE(m.stats.first_problem.find("bad.obj:7:"), std::string::npos) << m.stats.first_problem;
  for (const Vec3& v : m.vertices_m) EXPECT_TRUE(v.finite());
  const Scene s(m);  // builds without the bad triangles
  EXPECT_EQ(s.triangle_count(), 1u);
}

TEST(ObjReader, SyntaxErrorsNameFileAndLine) {
  expect_error([] { load_mesh(temp_file("syn1.obj", "v 0 0 0\nv 1 x 0\n")); }, {"syn1.obj:2:", "not a number"});
  expect_error([] { load_mesh(temp_file("syn2.obj", "v 0 0\n")); }, {"syn2.obj:1:", "x y z"});
  expect_error([] { load_mesh(temp_file("syn3.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n")); },
               {"syn3.obj:4:", "non-zero"});
  expect_error([] { load_mesh("/nonexistent/city.obj"); }, {"/nonexistent/city.obj", "not found"});
  expect_error([] { load_mesh(temp_file("mesh.stl", "solid\n")); }, {"mesh.stl", "unknown mesh format"});
}

TEST(Placement, OffsetYawScaleAndYUp) {
  const std::string p = temp_file("place.obj", "v 1 0 0\nv 0 2 0\nv 0 0 3\nf 1 2 3\n");
  Placement pl;
  pl.offset_m = Enu(100.0, 200.0, 5.0);
  pl.yaw_rad = kPi / 2.0;  // east -> north
  pl.scale = 2.0;
  const Mesh m = load_mesh(p, pl);
  ASSERT_EQ(m.vertices_m.size(), 3u);
  EXPECT_NEAR(m.vertices_m[0].x, 100.0, 1e-12);
  EXPECT_NEAR(m.vertices_m[0].y, 202.0, 1e-12);
  EXPECT_NEAR(m.vertices_m[1].x, 96.0, 1e-12);
  EXPECT_NEAR(m.vertices_m[1].y, 200.0, 1e-12);
  EXPECT_NEAR(m.vertices_m[2].z, 11.0, 1e-12);
  Placement yup;
  yup.y_up = true;  // model y is up, model z is south
  const Mesh my = load_mesh(p, yup);
  EXPECT_NEAR(my.vertices_m[1].z, 2.0, 1e-12);
  EXPECT_NEAR(my.vertices_m[2].y, -3.0, 1e-12);
  pl.scale = 0.0;
  expect_error([&] { load_mesh(p, pl); }, {"scale"});
}

std::string binary_ply(bool big_endian, int n_faces_declared, bool truncate) {
  std::string h = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment test\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                  "property uchar red\nelement face " + std::to_string(n_faces_declared) +
                  "\nproperty list uchar int vertex_indices\nelement edge 0\nproperty int v1\nend_header\n";
  auto put = [&](const void* p, int n) {
    char b[8];
    std::memcpy(b, p, static_cast<std::size_t>(n));
    if (big_endian) std::reverse(b, b + n);
    h.append(b, static_cast<std::size_t>(n));
  };
  const float v[4][3] = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 7}};
  for (const auto& p : v) {
    for (const float c : p) put(&c, 4);
    h.push_back('\x7f');
  }
  const unsigned char four = 4;
  h.push_back(static_cast<char>(four));
  for (int32_t i : {0, 1, 2, 3}) put(&i, 4);
  if (n_faces_declared > 1) {
    h.push_back(3);
    for (int32_t i : {0, 1, 99}) put(&i, 4);
  }
  if (truncate) h.resize(h.size() - 6);
  return h;
}

TEST(PlyReader, BinaryBothEndiansAndAscii) {
  for (const bool be : {false, true}) {
    const Mesh m = load_mesh(temp_file(be ? "be.ply" : "le.ply", binary_ply(be, 2, false)));
    ASSERT_EQ(m.triangles.size(), 2u) << be;
    EXPECT_EQ(m.stats.skipped_bad_index, 1);
    EXPECT_FLOAT_EQ(static_cast<float>(m.vertices_m[3].z), 7.0f);
    EXPECT_FLOAT_EQ(static_cast<float>(m.vertices_m[2].x), 4.0f);
  }
  const Mesh a = load_mesh(temp_file("a.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                                     "property double z\nelement face 1\nproperty list uchar uint vertex_index\n"
                                     "end_header\n0 0 0\n1 0 0\n0 1 2.5\n3 0 1 2\n"));
  ASSERT_EQ(a.triangles.size(), 1u);
  EXPECT_DOUBLE_EQ(a.vertices_m[2].z, 2.5);
}

TEST(PlyReader, ErrorsNameFileAndLine) {
  expect_error([] { load_mesh(temp_file("t.ply", binary_ply(false, 1, true))); }, {"t.ply", "truncated"});
  expect_error([] { load_mesh(temp_file("h.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n")); },
               {"h.ply:4:", "unknown property type"});
  expect_error([] { load_mesh(temp_file("n.ply", "plx\n")); }, {"n.ply:1:", "not a PLY"});
  expect_error([] {
    load_mesh(temp_file("v.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                                 "property float z\nend_header\n0 0 0\n1 oops 0\n"));
  }, {"v.ply:9:", "oops"});
  expect_error([] {
    load_mesh(temp_file("nz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                  "end_header\n0 0\n"));
  }, {"nz.ply:3:", "x, y and z"});
}

TEST(PlyReader, SionnaStreetCanyon) {
  // Copied from ../shared/data (Apache-2.0): always present, never skipped.
  const std::string dir = std::string(GNSSEMU_TEST_DATA) + "/scenes/simple_street_canyon";
  const Mesh m = load_mesh(dir + "/meshes/building_1.ply");
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.stats.skipped(), 0);
  const Mesh obj = load_mesh(dir + "/simple_street_canyon.obj");
  EXPECT_EQ(obj.stats.faces_read, 74);
  EXPECT_EQ(obj.triangles.size(), 74u);
}

TEST(MeshLoad, NoTrianglesIsAnErrorNamingTheFile) {
  std::string garbage(4096, '\0');
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<char>((i * 131 + 7) % 256);
  expect_error([&] { load_mesh(temp_file("garbage.obj", garbage)); }, {"garbage.obj", "no triangles"});
  expect_error([] { load_mesh(std::string(GNSSEMU_TEST_DATA) + "/scenes/empty.obj"); }, {"empty.obj", "no triangles"});
  // Every face skipped: the count and the first problem are in the message.
  expect_error([] { load_mesh(temp_file("allbad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n")); },
               {"allbad.obj", "no triangles", "allbad.obj:3:", "does not exist"});
}

TEST(MeshLoad, CoordinatesBeyondFloat32RangeAreRejected) {
  expect_error([] { load_mesh(temp_file("far.obj", "v 0 0 0\nv 1 0 0\nv 4200000 0 0\nf 1 2 3\n")); },
               {"far.obj:3:", "beyond 1e6 m"});
  // After placement: an in-range model scaled out of range.
  Placement p;
  p.scale = 1000.0;
  expect_error([&] { load_mesh(temp_file("scaled.obj", "v 0 0 0\nv 1 0 0\nv 2000 0 0\nf 1 2 3\n"), p); },
               {"scaled.obj:3:", "after placement"});
  expect_error([] {
    load_mesh(temp_file("far.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                   "property float z\nend_header\n6378137 0 0\n"));
  }, {"far.ply:8:", "beyond 1e6 m"});
  EXPECT_EQ(load_mesh(temp_file("near.obj", "v 999999 0 0\nv 999999 1 0\nv 999998 0 5\nf 1 2 3\n")).triangles.size(), 1u);
}

TEST(PlyReader, HugeOrFractionalIndexAndBadCountAreErrors) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n"
                           "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(load_mesh(temp_file("fi.ply", head + "3 0 1 2\n")).triangles.size(), 1u);
  expect_error([&] { load_mesh(temp_file("big.ply", head + "3 0 1 1e19\n")); }, {"big.ply:13:", "1e+19", "not an integer"});
  expect_error([&] { load_mesh(temp_file("frac.ply", head + "3 0 1 1.5\n")); }, {"frac.ply:13:", "not an integer"});
  expect_error([] {
    load_mesh(temp_file("cnt.ply", "ply\nformat ascii 1.0\nelement vertex 1e10\nproperty float x\nend_header\n"));
  }, {"cnt.ply:3:", "1e10", "non-negative integer"});
  expect_error([] {
    load_mesh(temp_file("cnt2.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n"));
  }, {"cnt2.ply:3:", "larger than"});
}

}  // namespace
}  // namespace gnssemu::scene

namespace gnssemu::scene {
namespace {

TEST(PlyReader, ElementWithoutPropertiesIsAnErrorNotASpin) {
  // 53 bytes that made the reader loop 2e9 times over items of no bytes.
  expect_error([] {
    load_mesh(temp_file("noprop.ply", "ply\nformat ascii 1.0\nelement a 2000000000\nend_header\n"));
  }, {"noprop.ply:3:", "element a", "no property lines"});
  expect_error([] {
    load_mesh(temp_file("noprop_bin.ply", "ply\nformat binary_little_endian 1.0\nelement a 2000000000\nend_header\n"));
  }, {"noprop_bin.ply:3:", "no property lines"});
}

TEST(PlyReader, AsciiBodyEndingEarlyNamesTheElement) {
  expect_error([] {
    load_mesh(temp_file("short.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nend_header\n0 0 0\n1 0 0\n"));
  }, {"short.ply:9:", "ends before element vertex 2 of 3"});
}

TEST(PlyReader, UnderflowingCoordinateIsAValidNumber) {
  // 1e-320 is subnormal (strtod reports ERANGE): still a number, not infinity.
  const Mesh m = load_mesh(temp_file("tiny.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                                     "property double z\nelement face 1\nproperty list uchar uint vertex_index\n"
                                     "end_header\n1e-320 0 0\n1 0 0\n0 1 -1e-400\n3 0 1 2\n"));
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.stats.skipped(), 0);
  EXPECT_NEAR(m.vertices_m[0].x, 0.0, 1e-300);
  // Overflow stays an error of the value (infinite coordinate: skipped and counted).
  const Mesh big = load_mesh(temp_file("huge.ply",
                                       "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                                       "property double z\nelement face 2\nproperty list uchar uint vertex_index\n"
                                       "end_header\n1e400 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 2 3\n"));
  EXPECT_EQ(big.triangles.size(), 1u);
}

}  // namespace
}  // namespace gnssemu::scene

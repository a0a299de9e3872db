// SPDX-License-Identifier: Apache-2.0
#include "core/scene/scene.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/common/error.hpp"

namespace gnssemu::scene {

namespace {

constexpr double kDefaultLoss_db = 3.0;  // half the power per reflection (DESIGN.md §1: -3 dB per bounce)
constexpr std::size_t kStreamChunk = 64;

float to_f(double v) { return static_cast<float>(v); }

void fill(RTCRay& r, const Ray& in) {
  r.org_x = to_f(in.org_m.x);
  r.org_y = to_f(in.org_m.y);
  r.org_z = to_f(in.org_m.z);
  r.dir_x = to_f(in.dir.x);
  r.dir_y = to_f(in.dir.y);
  r.dir_z = to_f(in.dir.z);
  r.tnear = to_f(in.tnear_m);
  r.tfar = in.tfar_m >= 1.0e30 ? std::numeric_limits<float>::infinity() : to_f(in.tfar_m);
  r.time = 0.0f;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
}

}  // namespace

struct Scene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Impl() {
    if (scene != nullptr) rtcReleaseScene(scene);
    if (device != nullptr) rtcReleaseDevice(device);
  }
};

Scene::Scene(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice("threads=1");
  if (impl_->device == nullptr) throw Error("scene: cannot create an Embree device");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);

  const std::size_t nt = mesh.triangles.size();
  normals_.reserve(nt);
  offsets_.reserve(nt);
  material_ = mesh.material;
  material_.resize(nt, 0);
  material_names_ = mesh.material_names;
  if (material_names_.empty()) material_names_.emplace_back();
  loss_db_.assign(material_names_.size(), kDefaultLoss_db);
  for (uint16_t& m : material_) {
    if (m >= material_names_.size()) m = 0;
  }

  if (nt > 0) {
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), mesh.vertices_m.size()));
    auto* ib = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt));
    if (vb == nullptr || ib == nullptr) {
      rtcReleaseGeometry(geom);
      throw Error("scene: Embree could not allocate the mesh buffers");
    }
    lo_ = Vec3(1e300, 1e300, 1e300);
    hi_ = Vec3(-1e300, -1e300, -1e300);
    for (std::size_t i = 0; i < mesh.vertices_m.size(); ++i) {
      const Vec3& p = mesh.vertices_m[i];
      vb[3 * i] = to_f(p.x);
      vb[3 * i + 1] = to_f(p.y);
      vb[3 * i + 2] = to_f(p.z);
    }
    for (std::size_t i = 0; i < nt; ++i) {
      const auto& t = mesh.triangles[i];
      ib[3 * i] = t[0];
      ib[3 * i + 1] = t[1];
      ib[3 * i + 2] = t[2];
      // Plane from the float32 vertices Embree sees, so plane and BVH agree.
      const auto vf = [&](uint32_t k) { return Vec3(vb[3 * k], vb[3 * k + 1], vb[3 * k + 2]); };
      const Vec3 a = vf(t[0]), b = vf(t[1]), c = vf(t[2]);
      Vec3 n = (b - a).cross(c - a);
      const double len = n.norm();
      n = len > 0.0 ? n / len : Vec3(0.0, 0.0, 1.0);
      normals_.push_back(n);
      // Tolerance ~1e-5 rad: below any path's float32 resolution at street scale.
      if (std::fabs(n.z) > 1e-5 && std::fabs(n.z) < 1.0 - 1e-10) vertical_horizontal_ = false;
      offsets_.push_back(n.dot(a));
      for (const Vec3& p : {a, b, c}) {
        lo_ = Vec3(std::min(lo_.x, p.x), std::min(lo_.y, p.y), std::min(lo_.z, p.z));
        hi_ = Vec3(std::max(hi_.x, p.x), std::max(hi_.y, p.y), std::max(hi_.z, p.z));
      }
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  if (rtcGetDeviceError(impl_->device) != RTC_ERROR_NONE) throw Error("scene: Embree failed to build the BVH");
}

Scene::~Scene() = default;

bool Scene::set_material_loss_db(const std::string& name, double loss_db) {
  for (std::size_t i = 0; i < material_names_.size(); ++i) {
    if (material_names_[i] == name) {
      loss_db_[i] = loss_db;
      return true;
    }
  }
  return false;
}

void Scene::set_default_loss_db(double loss_db) { std::fill(loss_db_.begin(), loss_db_.end(), loss_db); }

bool Scene::occluded(const Ray& r) const noexcept {
  if (normals_.empty()) return false;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray;
  fill(ray, r);
  rtcOccluded1(impl_->scene, &ctx, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

Hit Scene::intersect(const Ray& r) const noexcept {
  Hit h;
  if (normals_.empty()) return h;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  alignas(16) RTCRayHit rh;
  fill(rh.ray, r);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    h.prim = static_cast<int32_t>(rh.hit.primID);
    h.t_m = rh.ray.tfar;
  }
  return h;
}

void Scene::intersect(std::span<const Ray> rays, std::span<Hit> hits) const noexcept {
  const std::size_t n = std::min(rays.size(), hits.size());
  if (normals_.empty()) {
    for (std::size_t i = 0; i < n; ++i) hits[i] = Hit{};
    return;
  }
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit buf[kStreamChunk];
  for (std::size_t base = 0; base < n; base += kStreamChunk) {
    const std::size_t m = std::min(kStreamChunk, n - base);
    for (std::size_t i = 0; i < m; ++i) {
      fill(buf[i].ray, rays[base + i]);
      buf[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      buf[i].hit.primID = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(impl_->scene, &ctx, buf, static_cast<unsigned int>(m), sizeof(RTCRayHit));
    for (std::size_t i = 0; i < m; ++i) {
      Hit& h = hits[base + i];
      if (buf[i].hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        h.prim = static_cast<int32_t>(buf[i].hit.primID);
        h.t_m = buf[i].ray.tfar;
      } else {
        h = Hit{};
      }
    }
  }
}

}  // namespace gnssemu::scene

// SPDX-License-Identifier: Apache-2.0
#include "core/scene/propagator.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"

namespace gnssemu::scene {

namespace {

// Rays leave a surface this far off it (float32 resolution at 1 km is 6e-5 m).
constexpr double kSurfaceOffset_m = 2e-3;
// Antenna rays start this far out so a receiver standing on a surface is not blocked by it.
constexpr double kStart_m = 1e-3;
// A verified path leaves within this of the satellite direction (cos of ~1.4e-4 rad).
constexpr double kExitCos = 1.0 - 1e-8;
constexpr double kGoldenAngle = 2.399963229728653;  // pi (3 - sqrt 5)

Vec3 unit(const Vec3& v) {
  const double n = v.norm();
  return n > 0.0 ? v / n : Vec3(0.0, 0.0, 1.0);
}

Vec3 reflect(const Vec3& u, const Vec3& n) { return u - n * (2.0 * u.dot(n)); }

uint64_t hash_prims(const int32_t* p, int k) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (int i = 0; i < k; ++i) {
    h ^= static_cast<uint32_t>(p[i]);
    h *= 1099511628211ull;
  }
  return h ^ static_cast<uint64_t>(k);
}

bool better(const SatPath& a, const SatPath& b) {
  if (b.kind != PathKind::kNlos) return true;
  if (a.loss_db != b.loss_db) return a.loss_db < b.loss_db;
  return a.extra_delay_m < b.extra_delay_m;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("scene search: " + what);
}

}  // namespace

void validate(const SearchConfig& c) {
  using R = SearchRanges;
  require(R::rays.contains(c.rays), "rays must be in " + format_range(R::rays));
  require(R::azimuth_rays.contains(c.azimuth_rays), "azimuth_rays must be in " + format_range(R::azimuth_rays));
  require(R::max_bounces.contains(c.max_bounces), "max_bounces must be in " + format_range(R::max_bounces));
  require(R::match_factor.contains(c.match_factor), "match_factor must be in " + format_range(R::match_factor));
  require(std::isfinite(c.reuse_distance_m) && c.reuse_distance_m >= 0.0, "reuse_distance_m must be >= 0");
  require(std::isfinite(c.reuse_angle_rad) && c.reuse_angle_rad >= 0.0, "reuse_angle_rad must be >= 0");
  require(std::isfinite(c.min_arrival_el_rad) && c.min_arrival_el_rad > -kPi / 2.0 && c.min_arrival_el_rad < kPi / 2.0,
          "min_arrival_el_rad must be in (-pi/2, pi/2)");
  require(!std::isnan(c.max_loss_db) && c.max_loss_db > 0.0, "max_loss_db must be > 0");
}

Propagator::Propagator(const Scene& scene, const SearchConfig& config) : scene_(scene), config_(config) {
  validate(config_);
  const auto m = static_cast<std::size_t>(config_.rays);
  sin_min_arrival_ = std::sin(config_.min_arrival_el_rad);
  // Fibonacci spiral over the cap z >= sin(min_arrival): near-uniform directions.
  launch_.resize(m);
  const double z0 = sin_min_arrival_;
  for (std::size_t i = 0; i < m; ++i) {
    const double z = 1.0 - (1.0 - z0) * (static_cast<double>(i) + 0.5) / static_cast<double>(m);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = kGoldenAngle * static_cast<double>(i);
    launch_[i] = Vec3(r * std::cos(phi), r * std::sin(phi), z);
  }
  const double solid_angle_sr = 2.0 * kPi * (1.0 - z0);
  const double spacing_rad = std::sqrt(solid_angle_sr / static_cast<double>(m));
  cos_match_ = std::cos(std::min(kPi / 2.0, config_.match_factor * spacing_rad));
  // Cone search: up to kMaxConeSats satellites, each with its cone and the mirrored one.
  const std::size_t front =
      std::max(m, 2 * static_cast<std::size_t>(config_.azimuth_rays) * static_cast<std::size_t>(kMaxConeSats));
  rays_.resize(front);
  hits_.resize(front);
  ray_id_.resize(front);
  ray_sat_.resize(front);
  next_rays_.resize(front);
  next_id_.resize(front);
  next_sat_.resize(front);
  prims_.resize(front * static_cast<std::size_t>(config_.max_bounces));
  // Lower bound of one reflection's loss over the materials in use.
  min_loss_db_ = 1e300;
  for (std::size_t p = 0; p < scene_.triangle_count(); ++p) {
    min_loss_db_ = std::min(min_loss_db_, scene_.reflection_loss_db(static_cast<int32_t>(p)));
  }
  if (scene_.triangle_count() == 0) min_loss_db_ = 0.0;
}

void Propagator::reset() noexcept {
  for (Cached& c : cache_) c.valid = false;
}

bool Propagator::settled(const Blocked& b, int k) const noexcept {
  // No path of k or more bounces can beat the best one found (equal loss
  // may still win on delay, hence the strict comparison).
  return b.best.kind == PathKind::kNlos && b.best.loss_db < min_loss_db_ * k - 1e-9;
}

void Propagator::compute(const Enu& rx_m, std::span<const SatQuery> sats, std::span<SatPath> out) noexcept {
  stats_ = PropagatorStats{};
  const std::size_t n = std::min(sats.size(), out.size());
  const bool reuse = config_.reuse_distance_m > 0.0 || config_.reuse_angle_rad > 0.0;
  const double cos_reuse = std::cos(config_.reuse_angle_rad);
  int n_blocked = 0;
  std::array<bool, kMaxSats> fresh{};  // slot got a full search (cache anchor moves)
  for (std::size_t i = 0; i < n; ++i) {
    SatPath& o = out[i];
    o = SatPath{};
    if (i >= static_cast<std::size_t>(kMaxSats)) {
      o.kind = PathKind::kNone;
      continue;
    }
    const Vec3 d = unit(sats[i].dir);
    o.arrival_dir = Enu(d);
    if (scene_.empty()) continue;
    const int id = sats[i].id;
    const bool cacheable = id >= 0 && id < kMaxIds;
    const Cached* c = reuse && cacheable ? &cache_[static_cast<std::size_t>(id)] : nullptr;
    const bool near = c != nullptr && c->valid && (rx_m - c->rx_m).norm() <= config_.reuse_distance_m &&
                      d.dot(c->dir) >= cos_reuse;
    ++stats_.los_checked;
    ++stats_.rays;
    const bool los = !scene_.occluded(Ray{rx_m, d, kStart_m, 1.0e30});
    Blocked& b = blocked_[static_cast<std::size_t>(n_blocked)];
    b.slot = static_cast<int>(i);
    b.dir = d;
    b.best = SatPath{};
    b.best.kind = PathKind::kNone;
    b.best.arrival_dir = Enu(d);
    b.n_seen = 0;
    if (near) {
      if (los && c->path.kind == PathKind::kLos) {
        ++stats_.reused;
        continue;
      }
      if (!los && c->path.kind == PathKind::kNone) {
        o = b.best;
        ++stats_.reused;
        continue;
      }
      if (!los && c->path.kind == PathKind::kNlos) {
        ++stats_.retraced;
        if (refine(rx_m, c->prims.data(), c->path.bounces, b)) {
          o = b.best;
          ++stats_.reused;
          continue;
        }
      }
    }
    if (los) {
      if (cacheable) fresh[static_cast<std::size_t>(i)] = true;
      continue;
    }
    b.best = SatPath{};
    b.best.kind = PathKind::kNone;
    b.best.arrival_dir = Enu(d);
    b.n_seen = 0;
    if (cacheable) fresh[static_cast<std::size_t>(i)] = true;
    ++n_blocked;
  }
  if (n_blocked > 0) search(rx_m, n_blocked);
  for (int j = 0; j < n_blocked; ++j) {
    const Blocked& b = blocked_[static_cast<std::size_t>(j)];
    out[static_cast<std::size_t>(b.slot)] = b.best;
  }
  stats_.searched = n_blocked;
  if (!reuse) return;
  for (std::size_t i = 0; i < n && i < static_cast<std::size_t>(kMaxSats); ++i) {
    const int id = sats[i].id;
    if (id < 0 || id >= kMaxIds || !fresh[i]) continue;
    Cached& c = cache_[static_cast<std::size_t>(id)];
    c.valid = true;
    c.rx_m = rx_m;
    c.dir = unit(sats[i].dir);
    c.path = out[i];
  }
  for (int j = 0; j < n_blocked; ++j) {
    const Blocked& b = blocked_[static_cast<std::size_t>(j)];
    const int id = sats[static_cast<std::size_t>(b.slot)].id;
    if (id >= 0 && id < kMaxIds) cache_[static_cast<std::size_t>(id)].prims = b.best_prims;
  }
}

void Propagator::search(const Vec3& rx_m, int n_blocked) noexcept {
  const int max_b = config_.max_bounces;
  // Deeper paths than the loss cap allows cannot be received.
  int depth = max_b;
  if (min_loss_db_ > 0.0) depth = static_cast<int>(std::min<double>(max_b, std::floor(config_.max_loss_db / min_loss_db_ + 1e-9)));
  std::size_t n_active = 0;
  if (scene_.vertical_horizontal() && config_.azimuth_rays > 0 && n_blocked <= kMaxConeSats) {
    // |u.z| is invariant under reflections on vertical and horizontal faces:
    // only the cone of a satellite's elevation can reach it.
    const int n_az = config_.azimuth_rays;
    for (int j = 0; j < n_blocked; ++j) {
      Blocked& b = blocked_[static_cast<std::size_t>(j)];
      const double ch = std::hypot(b.dir.x, b.dir.y);
      const double az0 = std::atan2(b.dir.x, b.dir.y);
      const double step = 2.0 * kPi / n_az;
      b.cos_match = std::cos(std::min(kPi / 2.0, config_.match_factor * step * ch));
      // The cone at +el, and its mirror at -el (first bounce on a horizontal
      // face, e.g. the ground) when arrivals from below are allowed.
      for (int side = 0; side < 2; ++side) {
        const double z = side == 0 ? b.dir.z : -b.dir.z;
        if (side == 1 && (!(b.dir.z > 0.0) || z < sin_min_arrival_)) continue;
        for (int i = 0; i < n_az; ++i) {
          const double az = az0 + step * (i + 0.5);
          rays_[n_active] = Ray{rx_m, Vec3(ch * std::sin(az), ch * std::cos(az), z), kStart_m, 1.0e30};
          ray_id_[n_active] = static_cast<int32_t>(n_active);
          ray_sat_[n_active] = static_cast<int16_t>(j);
          ++n_active;
        }
      }
    }
  } else {
    n_active = launch_.size();
    for (std::size_t i = 0; i < n_active; ++i) {
      rays_[i] = Ray{rx_m, launch_[i], kStart_m, 1.0e30};
      ray_id_[i] = static_cast<int32_t>(i);
      ray_sat_[i] = -1;
    }
    for (int j = 0; j < n_blocked; ++j) blocked_[static_cast<std::size_t>(j)].cos_match = cos_match_;
  }
  for (int k = 1; k <= depth && n_active > 0; ++k) {
    bool all_settled = true;
    for (int j = 0; j < n_blocked; ++j) all_settled = all_settled && settled(blocked_[static_cast<std::size_t>(j)], k);
    if (all_settled) break;
    scene_.intersect(std::span<const Ray>(rays_.data(), n_active), std::span<Hit>(hits_.data(), n_active));
    stats_.rays += n_active;
    std::size_t n_next = 0;
    for (std::size_t i = 0; i < n_active; ++i) {
      const Hit& h = hits_[i];
      if (h.prim < 0) continue;  // escaped to the sky
      const Ray& r = rays_[i];
      Vec3 nrm = scene_.normal(h.prim);
      if (nrm.dot(r.dir) > 0.0) nrm = -nrm;
      const Vec3 u = unit(reflect(r.dir, nrm));
      const int32_t id = ray_id_[i];
      const int16_t target = ray_sat_[i];
      int32_t* seq = &prims_[static_cast<std::size_t>(id) * static_cast<std::size_t>(max_b)];
      seq[k - 1] = h.prim;
      if (target >= 0) {
        Blocked& b = blocked_[static_cast<std::size_t>(target)];
        if (settled(b, k)) continue;  // its satellite has its best path: drop the ray
        if (u.dot(b.dir) >= b.cos_match) refine(rx_m, seq, k, b);
      } else {
        for (int j = 0; j < n_blocked; ++j) {
          Blocked& b = blocked_[static_cast<std::size_t>(j)];
          if (u.dot(b.dir) < b.cos_match || settled(b, k)) continue;
          refine(rx_m, seq, k, b);
        }
      }
      if (k < depth) {
        const Vec3 p = r.org_m + r.dir * h.t_m + nrm * kSurfaceOffset_m;
        next_rays_[n_next] = Ray{p, u, 0.0, 1.0e30};
        next_sat_[n_next] = target;
        next_id_[n_next++] = id;
      }
    }
    std::swap(rays_, next_rays_);
    std::swap(ray_id_, next_id_);
    std::swap(ray_sat_, next_sat_);
    n_active = n_next;
  }
}

bool Propagator::refine(const Vec3& rx_m, const int32_t* prims, int k, Blocked& b) noexcept {
  const uint64_t h = hash_prims(prims, k);
  for (int i = 0; i < b.n_seen; ++i) {
    if (b.seen[static_cast<std::size_t>(i)] == h) return false;
  }
  if (b.n_seen < static_cast<int>(b.seen.size())) b.seen[static_cast<std::size_t>(b.n_seen++)] = h;
  ++stats_.candidates;
  // Launch direction whose k reflections on these planes leave along b.dir.
  Vec3 u = b.dir;
  for (int i = k - 1; i >= 0; --i) u = reflect(u, scene_.normal(prims[i]));
  u = unit(u);
  if (u.z < sin_min_arrival_) return false;
  const Vec3 arrival = u;
  Vec3 p = rx_m;        // exact path point (double)
  Vec3 q = rx_m;        // query origin (offset off the surface)
  double tnear = kStart_m;
  double length_m = 0.0, loss_db = 0.0;
  std::array<int32_t, kMaxBounces> traced{};
  for (int i = 0; i < k; ++i) {
    const Hit hit = scene_.intersect(Ray{q, u, tnear, 1.0e30});
    ++stats_.rays;
    if (hit.prim < 0) return false;
    Vec3 nrm = scene_.normal(hit.prim);
    const double un = u.dot(nrm);
    if (std::fabs(un) < 1e-9) return false;  // grazing: no specular reflection
    const double t = (scene_.plane_offset_m(hit.prim) - nrm.dot(p)) / un;
    if (!(t > -kSurfaceOffset_m) || !std::isfinite(t)) return false;
    p = p + u * t;
    length_m += t;
    if (un > 0.0) nrm = -nrm;
    u = unit(reflect(u, nrm));
    loss_db += scene_.reflection_loss_db(hit.prim);
    traced[static_cast<std::size_t>(i)] = hit.prim;
    q = p + nrm * kSurfaceOffset_m;
    tnear = 0.0;
  }
  if (u.dot(b.dir) < kExitCos) return false;  // hit other planes than the candidate's
  ++stats_.rays;
  if (scene_.occluded(Ray{q, b.dir, 0.0, 1.0e30})) return false;
  if (loss_db > config_.max_loss_db) return false;
  SatPath cand;
  cand.kind = PathKind::kNlos;
  cand.bounces = k;
  cand.extra_delay_m = length_m - b.dir.dot(p - rx_m);
  cand.loss_db = loss_db;
  cand.arrival_dir = Enu(arrival);
  if (better(cand, b.best)) {
    b.best = cand;
    b.best_prims = traced;
  }
  return true;
}

}  // namespace gnssemu::scene

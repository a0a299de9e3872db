// SPDX-License-Identifier: Apache-2.0
#pragma once
// Propagator: per-satellite signal path from the scene for one receiver.
// Line of sight first (one occlusion ray per satellite); only blocked
// satellites get a reflection search: rays launched over the upper hemisphere
// from the antenna are bounced specularly (up to max_bounces); after each
// bounce a ray leaving close to a blocked satellite's direction names a
// sequence of planes, whose exact specular path is then solved (image method
// for a source at infinity) and verified with Embree. Paths are plane-wave
// paths: extra delay = path length - projection of the antenna-to-last-point
// vector on the satellite direction.
//
// Per-epoch path: no allocation and no exception after construction.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/common/range.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/scene/scene.hpp"

namespace gnssemu::scene {

enum class PathKind : uint8_t {
  kLos = 0,   ///< direct signal (no scene term)
  kNlos = 1,  ///< blocked; received via reflections only
  kNone = 2,  ///< blocked and no viable reflection path: not received
};

/// The signal path the receiver tracks for one satellite (the strongest:
/// lowest loss, then shortest delay).
struct SatPath {
  PathKind kind = PathKind::kLos;
  int bounces = 0;
  double extra_delay_m = 0.0;  ///< reflected path minus direct path, m (>= 0 in practice)
  double loss_db = 0.0;        ///< sum of reflection losses, dB
  Enu arrival_dir;             ///< unit ENU vector from the antenna towards where the signal arrives from
};

/// One satellite to evaluate: id (SatId::index()) in [0, Propagator::kMaxIds)
/// keys the reuse cache; dir is the unit ENU vector from the antenna to the satellite.
struct SatQuery {
  int id = 0;
  Enu dir;
};

/// Search effort. Defaults: measured by `gnssemu bench multipath` (docs/benchmarks.md).
struct SearchConfig {
  int rays = 1024;                  ///< launch directions over the arrival hemisphere (>= 16)
  /// Scenes of vertical and horizontal faces only: per blocked satellite,
  /// rays on the cone of its elevation (the only launch directions that can
  /// reach it), this many in azimuth, and as many on the mirrored cone
  /// (-elevation, a first bounce on the ground) when min_arrival_el_rad
  /// allows arrivals from there; 0: always the hemisphere.
  int azimuth_rays = 128;
  int max_bounces = 16;             ///< reflections per path at most [1, 32]
  double match_factor = 1.5;        ///< candidate tolerance in units of the mean ray spacing (> 0)
  /// Path reuse: within reuse_distance_m of the antenna position and
  /// reuse_angle_rad of the satellite direction at a satellite's last full
  /// search, the search is skipped: its LOS ray is still cast, a reflected
  /// path is re-solved on the same planes (exact delay at the new position),
  /// and only if that fails is the satellite searched again. 0 and 0: off.
  double reuse_distance_m = 0.0;    ///< m
  double reuse_angle_rad = 0.0;     ///< rad
  double min_arrival_el_rad = 0.0;  ///< arrivals from below this elevation are rejected (antenna gain), rad
  /// Paths weaker than this are not received, dB: 45 dB-Hz nominal minus
  /// ~24 dB-Hz tracking threshold. The one default of every entry point
  /// (config [scene] max_loss_db, gnssemu sky, bench multipath).
  double max_loss_db = 21.0;
};

/// Throws gnssemu::Error naming the first bad field (SearchRanges).
void validate(const SearchConfig& c);

/// Work done by the last compute() call.
struct PropagatorStats {
  uint64_t rays = 0;       ///< Embree rays cast (LOS, launch, bounces, refinement)
  int los_checked = 0;     ///< satellites given an LOS ray
  int searched = 0;        ///< satellites given a full reflection search
  int retraced = 0;        ///< reflected paths re-solved on their last planes (reuse)
  int reused = 0;          ///< satellites whose last path was reused
  int candidates = 0;      ///< exact-path refinements tried
};

class Propagator {
public:
  static constexpr int kMaxIds = kNumSats;          ///< reuse-cache slots: one per satellite
  static constexpr int kMaxSats = kMaxSatsInView;   ///< satellites per compute() call at most
  static constexpr int kMaxBounces = 32;
  static constexpr int kMaxConeSats = 32;  ///< blocked satellites given cone rays per epoch at most

  /// scene must outlive the propagator. Allocates every buffer. Throws on a bad config.
  Propagator(const Scene& scene, const SearchConfig& config);

  /// Paths for sats (out[i] for sats[i]) seen from the antenna at rx_m (ENU
  /// m). Directions need not be normalised; ids outside [0, kMaxIds) bypass
  /// the reuse cache; satellites past kMaxSats are not received. Never
  /// throws, never allocates.
  void compute(const Enu& rx_m, std::span<const SatQuery> sats, std::span<SatPath> out) noexcept;

  /// Forget the reuse cache (e.g. after a jump of the vehicle).
  void reset() noexcept;

  const SearchConfig& config() const noexcept { return config_; }
  const PropagatorStats& stats() const noexcept { return stats_; }

private:
  struct Cached {
    bool valid = false;
    Vec3 rx_m, dir;                 ///< at the last full search
    SatPath path;
    std::array<int32_t, kMaxBounces> prims{};  ///< planes of path (NLOS)
  };
  /// Plane sequences remembered per blocked satellite so as not to refine one twice.
  static constexpr std::size_t kMaxSeenSequences = 32;
  struct Blocked {
    int slot;          ///< index into sats/out
    Vec3 dir;          ///< unit
    SatPath best;
    double cos_match = 1.0;        ///< candidate tolerance (cos of the angle)
    std::array<int32_t, kMaxBounces> best_prims{};
    int n_seen = 0;    ///< plane sequences already refined
    std::array<uint64_t, kMaxSeenSequences> seen{};
  };

  void search(const Vec3& rx_m, int n_blocked) noexcept;
  /// Solves and verifies the exact path on planes prims[0..k); true if it
  /// is viable (then b.best is updated if it is better).
  bool refine(const Vec3& rx_m, const int32_t* prims, int k, Blocked& b) noexcept;
  bool settled(const Blocked& b, int k) const noexcept;

  const Scene& scene_;
  SearchConfig config_;
  double cos_match_ = 1.0;
  double min_loss_db_ = 0.0;
  double sin_min_arrival_ = 0.0;
  std::vector<Vec3> launch_;
  // Active ray front (structure of arrays, preallocated to config_.rays).
  std::vector<Ray> rays_;
  std::vector<Hit> hits_;
  std::vector<int32_t> ray_id_;      ///< launch index of each active ray
  std::vector<int16_t> ray_sat_;     ///< blocked index a cone ray serves, -1: all (hemisphere)
  std::vector<int16_t> next_sat_;
  std::vector<int32_t> prims_;       ///< [launch index * max_bounces + bounce] plane sequence
  std::vector<Ray> next_rays_;
  std::vector<int32_t> next_id_;
  std::array<Blocked, kMaxSats> blocked_{};
  std::array<Cached, kMaxIds> cache_{};
  PropagatorStats stats_;
};

/// Valid values of SearchConfig's fields as a configuration gives them
/// (angles in degrees). validate() checks rays, azimuth_rays, max_bounces and
/// match_factor against them and only the sign of the others, which
/// programs may set wider than a configuration does.
struct SearchRanges {
  static constexpr Range rays{16.0, 4.0e6, ""};                  ///< integer
  static constexpr Range azimuth_rays{0.0, 100000.0, ""};        ///< integer
  static constexpr Range max_bounces{1.0, Propagator::kMaxBounces, ""};  ///< integer
  static constexpr Range match_factor{0.0, 20.0, "", true};
  static constexpr Range reuse_distance_m{0.0, 1000.0, "m"};
  static constexpr Range reuse_angle_deg{0.0, 90.0, "deg"};
  static constexpr Range min_arrival_elevation_deg{-89.0, 89.0, "deg"};
  static constexpr Range max_loss_db{0.0, 1000.0, "dB", true};
};

}  // namespace gnssemu::scene

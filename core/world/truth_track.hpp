// SPDX-License-Identifier: Apache-2.0
#pragma once
// TruthTrack: a vehicle's truth samples in time order, and its truth at any
// time between them by linear interpolation (velocity interpolated when the
// samples carry it, else the segment's mean velocity). Two rules for the
// ends and gaps:
//  - recorded truth (a trajectory file): none outside [first, last] (1 us
//    of rounding allowed), and a segment touching a no-truth sample has
//    truth only at its valid end;
//  - live truth (a simulator's packets): extrapolated at most a given time
//    past either end with the velocity there, then held with zero velocity.
// Live truth reserves its storage up front: add() never allocates; no
// query ever does.
#include <cstddef>
#include <vector>

#include "core/common/vec3.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/truth.hpp"

namespace gnssemu::world {

/// One truth sample, ECEF.
struct TruthSample {
  time::GpsTime t;     ///< GPS time of the sample
  Ecef pos_m;          ///< antenna position, ECEF m
  Ecef vel_m_s;        ///< antenna velocity, ECEF m/s (valid when has_vel)
  bool has_vel = false;
  /// false: no truth from this sample until the next valid one (antenna
  /// lost); pos_m and vel_m_s are then unset.
  bool valid = true;
};

class TruthTrack {
public:
  /// Live truth keeping the newest capacity samples (>= 2).
  explicit TruthTrack(std::size_t capacity);
  /// Recorded truth: samples strictly increasing in time, at least one.
  explicit TruthTrack(std::vector<TruthSample> samples);

  /// Appends s (later than the newest sample); beyond the capacity of live
  /// truth the oldest sample is dropped (no allocation).
  void add(const TruthSample& s) noexcept;
  void clear() noexcept { samples_.clear(); }

  /// Recorded truth at t: linear between the neighbouring samples; the
  /// sample itself for a single one; valid == false outside [first, last]
  /// and inside a segment with a no-truth end, except at a valid end itself.
  Truth at(const time::GpsTime& t) const noexcept;
  /// Live truth at t: linear inside the samples; past the newest one moved
  /// on with the velocity there for at most max_extrapolation_s (s), then
  /// held there with zero velocity; before the oldest one moved back with its
  /// velocity, and invalid beyond max_extrapolation_s. Invalid when empty.
  Truth extrapolated(const time::GpsTime& t, double max_extrapolation_s) const noexcept;

  std::size_t size() const noexcept { return samples_.size(); }
  /// k = 0 oldest ... size()-1 newest.
  const TruthSample& sample(std::size_t k) const noexcept { return samples_[k]; }
  const TruthSample& newest() const noexcept { return samples_.back(); }
  const time::GpsTime& first() const noexcept { return samples_.front().t; }
  const time::GpsTime& last() const noexcept { return samples_.back().t; }

private:
  /// Index a of the segment [a, a + 1] holding t (size() >= 2).
  std::size_t segment(const time::GpsTime& t) const noexcept;
  /// Truth at t on the segment from a to b.
  static Truth between(const TruthSample& a, const TruthSample& b, const time::GpsTime& t) noexcept;
  /// Velocity at the newest (or oldest) end: the sample's own, else the mean
  /// of its segment (zero for a single sample).
  Ecef velocity_at_end(bool newest_end) const noexcept;

  std::vector<TruthSample> samples_;
  std::size_t capacity_ = 0;      ///< live truth: samples kept; 0: all (recorded truth)
  mutable std::size_t hint_ = 0;  ///< last segment; epochs usually move forward
};

}  // namespace gnssemu::world

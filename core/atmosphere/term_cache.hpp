// SPDX-License-Identifier: Apache-2.0
#pragma once
// Per-satellite cache of slowly varying terms (iono and tropo delay,
// attenuation): recomputed every refresh_s seconds, in between either held or
// extrapolated linearly from the last two refreshes (the first slope after a
// start comes from the next call, one epoch later). Fixed storage, no
// allocation; the caching error is measured in tests/unit/atmosphere.
#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/common/sat_id.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::atmosphere {

enum class CacheMode {
  kHold,    ///< value of the last refresh
  kLinear,  ///< last value plus the slope between the last two refreshes
};

/// N doubles per satellite (SatId::index(); an invalid id bypasses the cache).
template <std::size_t N>
class SlowTermCache {
public:
  using Values = std::array<double, N>;

  /// refresh_s: refresh interval, s (>= 0; 0 computes on every call).
  explicit SlowTermCache(double refresh_s, CacheMode mode = CacheMode::kHold) : refresh_s_(refresh_s), mode_(mode) {
    if (!std::isfinite(refresh_s) || refresh_s < 0.0)
      throw Error("atmosphere cache", 0, "refresh interval must be >= 0 s, got " + std::to_string(refresh_s));
  }

  double refresh_s() const noexcept { return refresh_s_; }
  CacheMode mode() const noexcept { return mode_; }

  /// Terms for sat at t; compute() -> Values is called when a refresh is due
  /// (first use, interval elapsed, time went backwards, or after invalidate).
  template <class Compute>
  Values get(SatId sat, const time::GpsTime& t, Compute&& compute) noexcept {
    if (!sat.valid() || refresh_s_ <= 0.0) return compute();
    Slot& s = slots_[static_cast<std::size_t>(sat.index())];
    const double age_s = s.valid ? t - s.t1 : 0.0;
    // Linear mode bootstraps its slope from the next call after a (re)start.
    const bool need_slope = mode_ == CacheMode::kLinear && s.valid && !s.has_slope && age_s > 0.0;
    if (!s.valid || age_s >= refresh_s_ || age_s < 0.0 || need_slope) {
      const Values v = compute();
      // A slope needs two refreshes one interval apart; after a gap start over.
      s.has_slope = s.valid && age_s > 0.0 && age_s <= 2.0 * refresh_s_;
      if (s.has_slope)
        for (std::size_t i = 0; i < N; ++i) s.slope[i] = (v[i] - s.v1[i]) / age_s;
      s.v1 = v;
      s.t1 = t;
      s.valid = true;
      ++refreshes_;
      return v;
    }
    if (mode_ == CacheMode::kHold || !s.has_slope) return s.v1;
    Values out;
    for (std::size_t i = 0; i < N; ++i) out[i] = s.v1[i] + s.slope[i] * age_s;
    return out;
  }

  void invalidate(SatId sat) noexcept {
    if (sat.valid()) slots_[static_cast<std::size_t>(sat.index())] = Slot{};
  }
  void clear() noexcept { slots_.fill(Slot{}); }
  /// Number of compute() calls made through the cache (for benchmarks).
  long refreshes() const noexcept { return refreshes_; }

private:
  struct Slot {
    Values v1{};
    Values slope{};
    time::GpsTime t1;
    bool valid = false;
    bool has_slope = false;
  };
  double refresh_s_;
  CacheMode mode_;
  std::array<Slot, kNumSats> slots_{};
  long refreshes_ = 0;
};

}  // namespace gnssemu::atmosphere

// SPDX-License-Identifier: Apache-2.0
#include "core/world/truth_track.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gnssemu::world {

namespace {
// Epoch times are built as first + k/rate; allow rounding at the ends.
constexpr double kEndTolerance_s = 1e-6;
}  // namespace

TruthTrack::TruthTrack(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 2)) {
  samples_.reserve(capacity_);
}

TruthTrack::TruthTrack(std::vector<TruthSample> samples) : samples_(std::move(samples)) {}

void TruthTrack::add(const TruthSample& s) noexcept {
  if (capacity_ > 0 && samples_.size() == capacity_) samples_.erase(samples_.begin());
  samples_.push_back(s);
}

std::size_t TruthTrack::segment(const time::GpsTime& t) const noexcept {
  if (hint_ + 1 >= samples_.size() || t - samples_[hint_].t < 0.0) hint_ = 0;
  while (hint_ + 2 < samples_.size() && samples_[hint_ + 1].t - t <= 0.0) ++hint_;
  return hint_;
}

Truth TruthTrack::between(const TruthSample& a, const TruthSample& b, const time::GpsTime& t) noexcept {
  Truth out;
  out.t = t;
  if (!a.valid || !b.valid) {
    // A segment touching a no-truth sample has truth only at its valid end.
    const TruthSample* end = a.valid && std::fabs(t - a.t) <= kEndTolerance_s   ? &a
                             : b.valid && std::fabs(b.t - t) <= kEndTolerance_s ? &b
                                                                                : nullptr;
    if (end == nullptr) return out;
    out.valid = true;
    out.pos_m = end->pos_m;
    out.vel_m_s = end->has_vel ? end->vel_m_s : Ecef();
    return out;
  }
  out.valid = true;
  const double span_s = b.t - a.t;
  double w = (t - a.t) / span_s;
  if (w < 0.0) w = 0.0;
  if (w > 1.0) w = 1.0;
  out.pos_m = Ecef(a.pos_m + (b.pos_m - a.pos_m) * w);
  if (a.has_vel && b.has_vel) {
    out.vel_m_s = Ecef(a.vel_m_s + (b.vel_m_s - a.vel_m_s) * w);
  } else {
    out.vel_m_s = Ecef((b.pos_m - a.pos_m) / span_s);
  }
  return out;
}

Truth TruthTrack::at(const time::GpsTime& t) const noexcept {
  Truth out;
  out.t = t;
  if (samples_.empty()) return out;
  const double from_first_s = t - samples_.front().t;
  const double to_last_s = samples_.back().t - t;
  if (from_first_s < -kEndTolerance_s || to_last_s < -kEndTolerance_s) return out;
  if (samples_.size() == 1) {
    out.valid = samples_.front().valid;
    out.pos_m = samples_.front().pos_m;
    out.vel_m_s = samples_.front().has_vel ? samples_.front().vel_m_s : Ecef();
    return out;
  }
  const std::size_t a = segment(t);
  return between(samples_[a], samples_[a + 1], t);
}

Ecef TruthTrack::velocity_at_end(bool newest_end) const noexcept {
  const std::size_t n = samples_.size();
  const TruthSample& s = newest_end ? samples_[n - 1] : samples_[0];
  if (s.has_vel) return s.vel_m_s;
  if (n < 2) return Ecef{};
  const TruthSample& a = newest_end ? samples_[n - 2] : samples_[0];
  const TruthSample& b = newest_end ? samples_[n - 1] : samples_[1];
  return Ecef((b.pos_m - a.pos_m) / (b.t - a.t));
}

Truth TruthTrack::extrapolated(const time::GpsTime& t, double max_extrapolation_s) const noexcept {
  Truth out;
  out.t = t;
  if (samples_.empty()) return out;
  const TruthSample& last = samples_.back();
  if (!(t < last.t)) {
    const double dt = std::min(t - last.t, max_extrapolation_s);
    const Ecef v = velocity_at_end(true);
    out.pos_m = Ecef(last.pos_m + v * dt);
    // Held after max_extrapolation_s: a held position does not move, so the
    // velocity is zero (a frozen fix that claims motion misleads an EKF).
    out.vel_m_s = t - last.t > max_extrapolation_s ? Ecef{} : v;
    out.valid = true;
    return out;
  }
  const TruthSample& first = samples_.front();
  if (t < first.t) {
    const double dt = first.t - t;
    if (dt > max_extrapolation_s) return out;
    const Ecef v = velocity_at_end(false);
    out.pos_m = Ecef(first.pos_m - v * dt);
    out.vel_m_s = v;
    out.valid = true;
    return out;
  }
  // first.t <= t < last.t: the segment holding t.
  const std::size_t a = segment(t);
  return between(samples_[a], samples_[a + 1], t);
}

}  // namespace gnssemu::world

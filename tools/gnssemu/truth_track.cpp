#include "tools/gnssemu/truth_track.hpp"

#include <cmath>
#include <utility>

namespace gnssemu::cli {

namespace {
// Epoch times are built as first + k/rate; allow rounding at the ends.
constexpr double kEndTolerance_s = 1e-6;
}  // namespace

TruthTrack::TruthTrack(std::vector<TruthSample> samples) : samples_(std::move(samples)) {}

world::Truth TruthTrack::at(const time::GpsTime& t) const noexcept {
  world::Truth out;
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
  if (hint_ + 1 >= samples_.size() || t - samples_[hint_].t < 0.0) hint_ = 0;
  while (hint_ + 2 < samples_.size() && samples_[hint_ + 1].t - t <= 0.0) ++hint_;
  const TruthSample& a = samples_[hint_];
  const TruthSample& b = samples_[hint_ + 1];
  if (!a.valid || !b.valid) {
    // A segment touching a no-truth row has truth only at its valid end.
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

}  // namespace gnssemu::cli

#include "daemon/truth_track.hpp"

#include <algorithm>

namespace gnssemu::daemon {

TruthTrack::AddResult TruthTrack::add(double sim_time_s, const time::GpsTime& t, const Ecef& pos_m,
                                      const std::optional<Ecef>& vel_m_s, double arrival_s) noexcept {
  if (last_sim_time_s_ && !(sim_time_s > *last_sim_time_s_)) return AddResult::kSimTimeBackwards;
  last_sim_time_s_ = sim_time_s;
  last_arrival_s_ = arrival_s;
  AddResult result = AddResult::kAdded;
  if (count_ > 0 && !(t > newest().t)) {
    count_ = 0;
    result = AddResult::kRestarted;
  }
  Sample s{t, pos_m, vel_m_s.value_or(Ecef{}), vel_m_s.has_value()};
  if (count_ < kHistory) {
    ring_[(head_ + count_) % kHistory] = s;
    ++count_;
  } else {
    ring_[head_] = s;
    head_ = (head_ + 1) % kHistory;
  }
  return result;
}

bool TruthTrack::fresh(double now_s, const TrackParams& params) const noexcept {
  return last_sim_time_s_.has_value() && now_s - last_arrival_s_ <= params.timeout_s;
}

Ecef TruthTrack::velocity_at_end(bool newest_end) const noexcept {
  const Sample& s = newest_end ? newest() : sample(0);
  if (s.has_vel) return s.vel_m_s;
  if (count_ < 2) return Ecef{};
  const Sample& a = newest_end ? sample(count_ - 2) : sample(0);
  const Sample& b = newest_end ? newest() : sample(1);
  return Ecef((b.pos_m - a.pos_m) / (b.t - a.t));
}

world::Truth TruthTrack::truth_at(const time::GpsTime& t, double now_s,
                                     const TrackParams& params) const noexcept {
  world::Truth out;
  out.t = t;
  if (count_ == 0 || !fresh(now_s, params)) return out;

  const Sample& last = newest();
  if (!(t < last.t)) {
    const double dt = std::min(t - last.t, params.max_extrapolation_s);
    const Ecef v = velocity_at_end(true);
    out.pos_m = Ecef(last.pos_m + v * dt);
    // Held after max_extrapolation_s: a held position does not move, so the
    // velocity is zero (a frozen fix that claims motion misleads an EKF).
    out.vel_m_s = t - last.t > params.max_extrapolation_s ? Ecef{} : v;
    out.valid = true;
    return out;
  }
  const Sample& first = sample(0);
  if (t < first.t) {
    const double dt = first.t - t;
    if (dt > params.max_extrapolation_s) return out;
    const Ecef v = velocity_at_end(false);
    out.pos_m = Ecef(first.pos_m - v * dt);
    out.vel_m_s = v;
    out.valid = true;
    return out;
  }
  // first.t <= t < last.t: newest bracketing pair.
  std::size_t k = count_ - 1;
  while (k > 0 && t < sample(k - 1).t) --k;
  const Sample& a = sample(k - 1);
  const Sample& b = sample(k);
  const double span = b.t - a.t;
  const double w = (t - a.t) / span;
  out.pos_m = Ecef(a.pos_m + (b.pos_m - a.pos_m) * w);
  out.vel_m_s = (a.has_vel && b.has_vel) ? Ecef(a.vel_m_s + (b.vel_m_s - a.vel_m_s) * w)
                                         : Ecef((b.pos_m - a.pos_m) / span);
  out.valid = true;
  return out;
}

}  // namespace gnssemu::daemon

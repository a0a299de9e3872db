// SPDX-License-Identifier: Apache-2.0
#include "daemon/truth/vehicle_track.hpp"

namespace gnssemu::daemon {

VehicleTrack::AddResult VehicleTrack::add(double sim_time_s, const time::GpsTime& t, const Ecef& pos_m,
                                          const std::optional<Ecef>& vel_m_s, double arrival_s) noexcept {
  if (last_sim_time_s_ && !(sim_time_s > *last_sim_time_s_)) return AddResult::kSimTimeBackwards;
  last_sim_time_s_ = sim_time_s;
  last_arrival_s_ = arrival_s;
  AddResult result = AddResult::kAdded;
  if (track_.size() > 0 && !(t > track_.newest().t)) {
    track_.clear();
    result = AddResult::kRestarted;
  }
  last_step_ = track_.size() > 0 ? Step{(pos_m - track_.newest().pos_m).norm(), t - track_.newest().t} : Step{};
  world::TruthSample s;
  s.t = t;
  s.pos_m = pos_m;
  s.vel_m_s = vel_m_s.value_or(Ecef{});
  s.has_vel = vel_m_s.has_value();
  if (!s.has_vel && track_.size() > 0 && t - track_.newest().t < kVelocityBaselineS) {
    // High-rate packets without velocity: difference over >= the baseline
    // (the newest sample at least that old, else the oldest held).
    std::size_t k = track_.size() - 1;
    while (k > 0 && t - track_.sample(k).t < kVelocityBaselineS) --k;
    const world::TruthSample& ref = track_.sample(k);
    const double dt = t - ref.t;
    if (dt > 0.0) {
      s.vel_m_s = Ecef((pos_m - ref.pos_m) * (1.0 / dt));
      s.has_vel = true;
    }
  }
  track_.add(s);
  return result;
}

bool VehicleTrack::fresh(double now_s, const TrackParams& params) const noexcept {
  return last_sim_time_s_.has_value() && now_s - last_arrival_s_ <= params.timeout_s;
}

world::Truth VehicleTrack::truth_at(const time::GpsTime& t, double now_s, const TrackParams& params) const noexcept {
  if (!fresh(now_s, params)) {
    world::Truth none;
    none.t = t;
    return none;
  }
  return track_.extrapolated(t, params.max_extrapolation_s);
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#include "daemon/truth/truth_router.hpp"

#include <limits>

namespace gnssemu::daemon {

TruthRouter::TruthRouter(const TrackParams& params, config::TimeMode mode, std::string driving_vehicle)
    : params_(params), mode_(mode), driving_id_(driving_vehicle), wanted_(std::move(driving_vehicle)) {
  vehicles_.reserve(kMaxVehicles);
}

TruthRouter::Ingest TruthRouter::ingest(const TruthSample& sample, const time::GpsTime& clock_gps,
                                        double now_s) {
  Ingest r;
  int idx = -1;
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    if (vehicles_[i].id == sample.vehicle) idx = static_cast<int>(i);
  }
  if (idx < 0) {
    if (vehicles_.size() >= kMaxVehicles) {
      r.reason = DropReason::kTooManyVehicles;
      return r;
    }
    vehicles_.push_back(Vehicle{sample.vehicle, VehicleTrack{}, SimClockMap{}});
    idx = static_cast<int>(vehicles_.size() - 1);
    r.new_vehicle = true;
  }
  Vehicle& v = vehicles_[static_cast<std::size_t>(idx)];

  // A vehicle silent past the timeout starts afresh: a restarted simulator
  // may begin its clock at zero again.
  if (!v.track.fresh(now_s, params_)) {
    v.track.reset();
    v.clock.reset();
  }
  if (v.track.last_sim_time_s() && !(sample.sim_time_s > *v.track.last_sim_time_s())) {
    r.reason = DropReason::kSimTimeBackwards;
    return r;
  }

  if (sample.gps_time) {
    r.stamp = *sample.gps_time;
  } else if (mode_ == config::TimeMode::kRealtime) {
    const SimClockMap::Mapped m = v.clock.map(sample.sim_time_s, clock_gps);
    r.stamp = m.t;
    r.reanchored = m.reanchored;
  } else {
    if (!v.clock.anchored()) {
      v.clock.anchor(sample.sim_time_s, clock_gps);
      r.reanchored = true;
    }
    r.stamp = v.clock.to_gps(sample.sim_time_s);
  }

  const auto added = v.track.add(sample.sim_time_s, r.stamp, sample.pos_m, sample.vel_m_s, now_s);
  if (added == VehicleTrack::AddResult::kSimTimeBackwards) {
    r.reason = DropReason::kSimTimeBackwards;
    return r;
  }
  r.restarted = added == VehicleTrack::AddResult::kRestarted;
  r.step = v.track.last_step();
  r.accepted = true;

  if (driver_ < 0 && (driving_id_.empty() || driving_id_ == v.id)) {
    driver_ = idx;
    driving_id_ = v.id;
  }
  r.driving = driver_ == idx;
  return r;
}

world::Truth TruthRouter::truth_at(const time::GpsTime& t, double now_s) const noexcept {
  if (driver_ < 0) {
    world::Truth none;
    none.t = t;
    return none;
  }
  return vehicles_[static_cast<std::size_t>(driver_)].track.truth_at(t, now_s, params_);
}

bool TruthRouter::driver_fresh(double now_s) const noexcept {
  return driver_ >= 0 && vehicles_[static_cast<std::size_t>(driver_)].track.fresh(now_s, params_);
}

double TruthRouter::driver_age_s(double now_s) const noexcept {
  if (driver_ < 0) return std::numeric_limits<double>::quiet_NaN();
  return now_s - vehicles_[static_cast<std::size_t>(driver_)].track.last_arrival_s();
}

std::optional<time::GpsTime> TruthRouter::driver_newest() const noexcept {
  if (driver_ < 0) return std::nullopt;
  const VehicleTrack& tr = vehicles_[static_cast<std::size_t>(driver_)].track;
  if (tr.size() == 0) return std::nullopt;
  return tr.newest().t;
}

void TruthRouter::set_driving_vehicle(const std::string& id) {
  wanted_ = id;
  if (id.empty() || id == driving_id_) return;
  driving_id_ = id;
  driver_ = -1;
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    if (vehicles_[i].id == id) driver_ = static_cast<int>(i);
  }
}

void TruthRouter::on_clock_jump() noexcept {
  for (Vehicle& v : vehicles_) {
    v.track.clear_samples();
    v.clock.reset();
  }
}

}  // namespace gnssemu::daemon

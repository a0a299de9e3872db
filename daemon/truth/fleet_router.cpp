// SPDX-License-Identifier: Apache-2.0
#include "daemon/truth/fleet_router.hpp"

#include <algorithm>

namespace gnssemu::daemon {

FleetRouter::FleetRouter(const TrackParams& params, config::TimeMode mode, const std::vector<std::string>& ids,
                         const std::string& driving)
    : params_(params), mode_(mode), single_(ids.size() == 1 && ids.front().empty()), ids_(ids) {
  routers_.reserve(ids.size());
  for (const std::string& id : ids) routers_.emplace_back(params, mode, single_ ? driving : id);
  attitude_.resize(ids.size());
  for (std::size_t v = 0; v < ids.size(); ++v) by_id_.emplace_back(ids[v], v);
  std::sort(by_id_.begin(), by_id_.end());
}

std::optional<std::size_t> FleetRouter::find(std::string_view id) const noexcept {
  if (single_) return 0;
  const auto it = std::lower_bound(by_id_.begin(), by_id_.end(), id,
                                   [](const auto& e, std::string_view k) { return std::string_view(e.first) < k; });
  if (it == by_id_.end() || it->first != id) return std::nullopt;
  return it->second;
}

FleetRouter::Routed FleetRouter::ingest(const TruthSample& sample, const time::GpsTime& clock_gps, double now_s) {
  Routed r;
  r.vehicle = find(sample.vehicle);
  if (!r.vehicle) {
    r.in.reason = DropReason::kUnknownVehicle;
    return r;
  }
  r.in = routers_[*r.vehicle].ingest(sample, clock_gps, now_s);
  if (r.in.accepted && r.in.driving && sample.attitude) attitude_[*r.vehicle] = sample.attitude;
  return r;
}

bool FleetRouter::any_fresh(double now_s) const noexcept {
  return std::any_of(routers_.begin(), routers_.end(), [now_s](const TruthRouter& r) { return r.driver_fresh(now_s); });
}

std::optional<time::GpsTime> FleetRouter::reached(double now_s) const noexcept {
  std::optional<time::GpsTime> oldest;
  for (const TruthRouter& r : routers_) {
    if (!r.driver_fresh(now_s)) continue;
    const std::optional<time::GpsTime> newest = r.driver_newest();
    if (newest && (!oldest || *newest < *oldest)) oldest = newest;
  }
  return oldest;
}

void FleetRouter::set_params(const TrackParams& params) noexcept {
  params_ = params;
  for (TruthRouter& r : routers_) r.set_params(params);
}

std::vector<std::optional<std::size_t>> FleetRouter::reshape(const std::vector<std::string>& ids) {
  std::vector<std::optional<std::size_t>> moved(ids_.size());
  std::vector<TruthRouter> routers;
  std::vector<std::optional<Attitude>> attitude;
  routers.reserve(ids.size());
  for (std::size_t v = 0; v < ids.size(); ++v) {
    const std::optional<std::size_t> old = find(ids[v]);
    if (old) {
      routers.push_back(std::move(routers_[*old]));
      attitude.push_back(attitude_[*old]);
      moved[*old] = v;
    } else {
      routers.emplace_back(params_, mode_, ids[v]);
      attitude.emplace_back();
    }
  }
  ids_ = ids;
  routers_ = std::move(routers);
  attitude_ = std::move(attitude);
  by_id_.clear();
  for (std::size_t v = 0; v < ids_.size(); ++v) by_id_.emplace_back(ids_[v], v);
  std::sort(by_id_.begin(), by_id_.end());
  return moved;
}

}  // namespace gnssemu::daemon

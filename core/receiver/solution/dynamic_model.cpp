// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/solution/dynamic_model.hpp"

#include <array>

namespace gnssemu::receiver {

namespace {

struct Entry {
  DynamicModel model;
  DynamicModelParams params;
};

// Limits: u-blox dynamic platform table (max altitude m, max horizontal and
// vertical velocity m/s, sanity check "altitude and velocity" or "altitude");
// the M8's operational limits (OperationalLimits) apply on top.
// Process noise: sigma_a^2 tau_a of typical manoeuvres, e.g. automotive
// 2 m/s^2 over 1 s horizontally (0.3 g turns and braking pass), 0.5 m/s^2
// vertically; a walker 0.7 m/s^2 over 1 s; aircraft their g class over 1 s.
constexpr std::array<Entry, 9> kModels{{
    {DynamicModel::kPortable, {1.0, 0.5, 12000.0, 310.0, 50.0, true, true, false}},
    {DynamicModel::kStationary, {0.0, 0.0, 9000.0, 10.0, 6.0, true, true, true}},
    {DynamicModel::kPedestrian, {0.5, 0.1, 9000.0, 30.0, 20.0, true, true, false}},
    {DynamicModel::kAutomotive, {4.0, 0.25, 6000.0, 100.0, 15.0, true, true, false}},
    {DynamicModel::kSea, {0.5, 0.01, 500.0, 25.0, 5.0, true, true, false}},
    {DynamicModel::kAirborne1g, {100.0, 100.0, 80000.0, 100.0, 6400.0, false, false, false}},
    {DynamicModel::kAirborne2g, {400.0, 400.0, 80000.0, 250.0, 10000.0, false, false, false}},
    {DynamicModel::kAirborne4g, {1600.0, 1600.0, 80000.0, 500.0, 20000.0, false, false, false}},
    {DynamicModel::kWrist, {0.3, 0.1, 9000.0, 30.0, 20.0, true, true, false}},
}};

}  // namespace

const DynamicModelParams& dynamic_model_params(DynamicModel m) noexcept {
  for (const Entry& e : kModels)
    if (e.model == m) return e.params;
  return kModels[0].params;
}

std::optional<DynamicModel> dynamic_model_from_ubx(std::uint8_t dyn_model) noexcept {
  for (const Entry& e : kModels)
    if (static_cast<std::uint8_t>(e.model) == dyn_model) return e.model;
  return std::nullopt;
}

std::string_view dynamic_model_name(DynamicModel m) noexcept {
  for (const DynamicModelName& n : kDynamicModelNames)
    if (n.model == m) return n.name;
  return kDynamicModelNames[0].name;
}

}  // namespace gnssemu::receiver

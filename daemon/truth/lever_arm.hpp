// SPDX-License-Identifier: Apache-2.0
#pragma once
// The antenna's truth from the vehicle's: the truth packets give the
// vehicle's reference point, a receiver's antenna sits lever_arm_m from it
// in the body frame (forward, right, down), turned by the body's attitude
// (docs/configuration.md §Vehicles). Pure; never throws or allocates.
#include <optional>

#include "core/common/vec3.hpp"
#include "core/world/truth.hpp"
#include "daemon/truth/truth_packet.hpp"

namespace gnssemu::daemon {

/// Below this horizontal speed, m/s, a vehicle without attitude keeps heading north.
inline constexpr double kMinHeadingSpeed_m_s = 0.5;

/// The body -> local north/east/down rotation of att applied to body_m
/// (forward, right, down, m): the same vector in north, east, down, m.
Vec3 body_to_ned(const Attitude& att, const Vec3& body_m) noexcept;

/// The attitude used for a lever arm: att when the packets carry one (the
/// binary record), else level with the heading of the horizontal velocity
/// (north when slower than kMinHeadingSpeed_m_s).
Attitude lever_attitude(const std::optional<Attitude>& att, const world::Truth& vehicle) noexcept;

/// vehicle's truth at the antenna lever_body_m (forward, right, down, m,
/// each within ±config::kMaxLeverArmM) away, with attitude att (see
/// lever_attitude). The velocity is the vehicle's (the rotation rate's
/// part, under 1 m/s for a 1 m arm below 1 rad/s, is left out). Invalid
/// truth and a zero arm pass through unchanged.
world::Truth antenna_truth(const world::Truth& vehicle, const Vec3& lever_body_m,
                           const std::optional<Attitude>& att) noexcept;

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Dynamic platform models of a u-blox receiver (CFG-NAV5 dynModel): what the
// navigation filter assumes about the vehicle's motion (its process noise)
// and the sanity limits beyond which the position is invalid. Limits from
// the u-blox dynamic platform table (MAX-M10M / ZED-F9 integration manuals,
// "Dynamic platform model details"); the process noise is ours (u-blox does
// not publish it): docs/models.md "Navigation filter".
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace gnssemu::receiver {

/// CFG-NAV5 dynModel; the values are u-blox's.
enum class DynamicModel : std::uint8_t {
  kPortable = 0,
  kStationary = 2,
  kPedestrian = 3,
  kAutomotive = 4,
  kSea = 5,
  kAirborne1g = 6,
  kAirborne2g = 7,
  kAirborne4g = 8,
  kWrist = 9,
};

/// A model and its name in configuration files and tools.
struct DynamicModelName {
  DynamicModel model;
  std::string_view name;
};

/// Every model with its name, in dynModel order.
inline constexpr std::array<DynamicModelName, 9> kDynamicModelNames{{
    {DynamicModel::kPortable, "portable"},
    {DynamicModel::kStationary, "stationary"},
    {DynamicModel::kPedestrian, "pedestrian"},
    {DynamicModel::kAutomotive, "automotive"},
    {DynamicModel::kSea, "sea"},
    {DynamicModel::kAirborne1g, "airborne1g"},
    {DynamicModel::kAirborne2g, "airborne2g"},
    {DynamicModel::kAirborne4g, "airborne4g"},
    {DynamicModel::kWrist, "wrist"},
}};

/// The name of m ("portable", ...).
std::string_view dynamic_model_name(DynamicModel m) noexcept;

/// What one model assumes and allows.
struct DynamicModelParams {
  /// White-acceleration power spectral density of the filter's motion model,
  /// horizontal and vertical, m^2/s^3 (>= 0): about sigma_a^2 tau_a of the
  /// vehicle's manoeuvres (acceleration sigma_a correlated over tau_a).
  double accel_psd_h_m2_s3;
  double accel_psd_v_m2_s3;
  double max_altitude_m;              ///< above it the position is invalid, m
  double max_h_speed_m_s;             ///< horizontal speed limit, m/s (checked when check_velocity)
  double max_v_speed_m_s;             ///< vertical speed limit, m/s (checked when check_velocity)
  bool check_velocity;                ///< false: altitude check only (airborne)
  bool allows_2d;                     ///< false: no 2D fixes (airborne)
  bool zero_velocity;                 ///< velocity held at 0 (stationary)
};

/// The parameters of m.
const DynamicModelParams& dynamic_model_params(DynamicModel m) noexcept;

/// The model of a CFG-NAV5 dynModel value; nullopt for values an M8 rejects (1, > 9).
std::optional<DynamicModel> dynamic_model_from_ubx(std::uint8_t dyn_model) noexcept;

}  // namespace gnssemu::receiver

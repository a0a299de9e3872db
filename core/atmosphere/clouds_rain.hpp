// SPDX-License-Identifier: Apache-2.0
#pragma once
// Cloud and fog layers (ITU-R P.840 Rayleigh absorption by liquid water) and
// rain (ITU-R P.838-3 specific attenuation) along the slant path. At L1 both
// are hundredths of a dB; they are modelled for honesty, not for effect.
#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "core/common/range.hpp"

namespace gnssemu::atmosphere {

/// P.840 specific attenuation coefficient of cloud liquid water,
/// (dB/km)/(g/m^3): K_l = 0.819 f / (eps'' (1 + eta^2)), double-Debye
/// permittivity of water. freq_hz > 0; temperature_k > 0 (P.840 uses 273.15 K).
/// 2.32e-3 at L1 and 0 deg C (reference §3.2).
double cloud_specific_attenuation_coeff(double freq_hz, double temperature_k) noexcept;

/// One cloud (or fog) layer. Heights above the surface, m.
struct CloudLayer {
  double base_m = 0.0;
  double thickness_m = 0.0;            ///< >= 0
  double liquid_water_g_m3 = 0.0;      ///< liquid water density, g/m^3 (>= 0)
  double temperature_k = 273.15;       ///< droplet temperature, K (> 0)
};

/// Named presets (order-of-magnitude climatology, see docs/models.md):
/// "fog" (0-100 m, 0.05 g/m^3), "thick_fog" (0-100 m, 0.5), "stratus"
/// (500 m + 500 m, 0.3), "cumulus" (1000 m + 1500 m, 1.0), "cumulonimbus" and
/// its alias "thunderstorm" (1000 m + 10000 m, 2.5). Throws gnssemu::Error
/// naming the known presets for an unknown name.
CloudLayer cloud_preset(std::string_view name);
/// The names cloud_preset knows, in its order.
std::vector<std::string_view> cloud_preset_names();

/// Rain: uniform rate from the surface up to the rain height.
struct RainConfig {
  double rate_mm_h = 0.0;         ///< rain rate, mm/h (>= 0; 0 = no rain)
  double rain_height_m = 3000.0;  ///< P.839 h_R = h_0 + 360 m; mid-latitudes ~2.5-4 km (>= 0)
  /// P.838-3 coefficients for circular polarisation at L1 (k = (kH + kV) / 2,
  /// alpha = (kH aH + kV aV) / 2k; reference §3.3). gamma = k R^alpha dB/km.
  double k = 5.60e-5;
  double alpha = 0.957;
};

/// Rain specific attenuation k R^alpha, dB/km.
double rain_specific_attenuation_db_km(double rate_mm_h, double k = 5.60e-5, double alpha = 0.957) noexcept;

inline constexpr std::size_t kMaxCloudLayers = 8;

struct CloudsRainConfig {
  std::array<CloudLayer, kMaxCloudLayers> layers{};
  std::size_t layer_count = 0;
  RainConfig rain;
  double freq_hz = 1575.42e6;  ///< carrier, Hz
};

struct CloudsRainAttenuation {
  double clouds_db = 0.0;
  double rain_db = 0.0;
};

/// Valid values of CloudLayer's, RainConfig's and CloudsRainConfig's fields.
struct CloudLayerRanges {
  static constexpr Range base_m{-1000.0, 30000.0, "m"};
  static constexpr Range thickness_m{0.0, 30000.0, "m"};
  static constexpr Range liquid_water_g_m3{0.0, 20.0, "g/m^3"};
  static constexpr Range temperature_k{0.0, 5000.0, "K", true};
};
struct RainRanges {
  static constexpr Range rate_mm_h{0.0, 500.0, "mm/h"};
  static constexpr Range rain_height_m{0.0, 10000.0, "m"};
  static constexpr Range k{0.0, 1.0, ""};
  static constexpr Range alpha{0.0, 5.0, "", true};
};
struct CloudsRainRanges {
  static constexpr Range freq_hz{0.0, 1.0e12, "Hz", true};
};

/// Throws gnssemu::Error for a value out of its range or more than
/// kMaxCloudLayers layers.
void validate(const CloudsRainConfig& cfg);

/// Validated clouds and rain. Throws gnssemu::Error on bad values (validate).
class CloudsRain {
public:
  explicit CloudsRain(const CloudsRainConfig& cfg);

  const CloudsRainConfig& config() const noexcept { return cfg_; }

  /// Attenuation along the slant path from a receiver at rx_height_m (above
  /// the surface) at elevation el_rad, dB (>= 0). Spherical-Earth path
  /// geometry (slant_path_in_shell_m); no P.618 horizontal reduction factor,
  /// so rain is slightly overestimated at low elevation.
  CloudsRainAttenuation attenuation(double rx_height_m, double el_rad) const noexcept;

private:
  CloudsRainConfig cfg_;
  std::array<double, kMaxCloudLayers> gamma_db_m_{};  // K_l * density per layer, dB/m
  double rain_gamma_db_m_ = 0.0;
};

}  // namespace gnssemu::atmosphere

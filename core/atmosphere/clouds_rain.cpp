// SPDX-License-Identifier: Apache-2.0
#include "core/atmosphere/clouds_rain.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/atmosphere/shells.hpp"
#include "core/common/error.hpp"

namespace gnssemu::atmosphere {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("clouds/rain config", 0, what);
}

struct Preset {
  std::string_view name;
  CloudLayer layer;
};

// Fog densities: ITU-R P.840 §2 (0.05 g/m^3 medium fog, visibility ~300 m;
// 0.5 g/m^3 thick fog, ~50 m). Cloud liquid water contents: typical values of
// cloud microphysics climatologies (e.g. Pruppacher & Klett, Microphysics of
// Clouds and Precipitation, 1997, ch. 2), order of magnitude only.
constexpr Preset kPresets[] = {
    {"fog", {0.0, 100.0, 0.05, 283.15}},
    {"thick_fog", {0.0, 100.0, 0.5, 283.15}},
    {"stratus", {500.0, 500.0, 0.3, 278.15}},
    {"cumulus", {1000.0, 1500.0, 1.0, 278.15}},
    {"cumulonimbus", {1000.0, 10000.0, 2.5, 273.15}},
    {"thunderstorm", {1000.0, 10000.0, 2.5, 273.15}},
};

}  // namespace

double cloud_specific_attenuation_coeff(double freq_hz, double temperature_k) noexcept {
  if (!(freq_hz > 0.0) || !(temperature_k > 0.0)) return 0.0;
  const double f = freq_hz * 1e-9;
  const double theta = 300.0 / temperature_k;
  const double eps0 = 77.66 + 103.3 * (theta - 1.0);
  const double eps1 = 0.0671 * eps0;
  const double eps2 = 3.52;
  const double fp = 20.20 - 146.0 * (theta - 1.0) + 316.0 * (theta - 1.0) * (theta - 1.0);
  const double fs = 39.8 * fp;
  const double rp = f / fp, rs = f / fs;
  const double eps_im = f * (eps0 - eps1) / (fp * (1.0 + rp * rp)) + f * (eps1 - eps2) / (fs * (1.0 + rs * rs));
  const double eps_re = (eps0 - eps1) / (1.0 + rp * rp) + (eps1 - eps2) / (1.0 + rs * rs) + eps2;
  const double eta = (2.0 + eps_re) / eps_im;
  return 0.819 * f / (eps_im * (1.0 + eta * eta));
}

CloudLayer cloud_preset(std::string_view name) {
  for (const Preset& p : kPresets)
    if (p.name == name) return p.layer;
  std::string known;
  for (const Preset& p : kPresets) known += (known.empty() ? "" : ", ") + std::string(p.name);
  throw Error("clouds config", 0, "unknown cloud preset '" + std::string(name) + "' (known: " + known + ")");
}

std::vector<std::string_view> cloud_preset_names() {
  std::vector<std::string_view> out;
  for (const Preset& p : kPresets) out.push_back(p.name);
  return out;
}

double rain_specific_attenuation_db_km(double rate_mm_h, double k, double alpha) noexcept {
  if (!(rate_mm_h > 0.0)) return 0.0;
  return k * std::pow(rate_mm_h, alpha);
}

void validate(const CloudsRainConfig& cfg) {
  const std::string what = "clouds/rain config";
  require(cfg.layer_count <= kMaxCloudLayers,
          "at most " + std::to_string(kMaxCloudLayers) + " cloud layers, got " + std::to_string(cfg.layer_count));
  check_range(cfg.freq_hz, CloudsRainRanges::freq_hz, what, "freq_hz");
  for (std::size_t i = 0; i < cfg.layer_count; ++i) {
    const CloudLayer& l = cfg.layers[i];
    const std::string n = "cloud layer " + std::to_string(i + 1);
    using L = CloudLayerRanges;
    check_ranges(what, {{l.base_m, L::base_m, n + " base_m"}, {l.thickness_m, L::thickness_m, n + " thickness_m"},
                        {l.liquid_water_g_m3, L::liquid_water_g_m3, n + " liquid_water_g_m3"},
                        {l.temperature_k, L::temperature_k, n + " temperature_k"}});
  }
  using R = RainRanges;
  const RainConfig& r = cfg.rain;
  check_ranges(what, {{r.rate_mm_h, R::rate_mm_h, "rain.rate_mm_h"}, {r.rain_height_m, R::rain_height_m, "rain.rain_height_m"},
                      {r.k, R::k, "rain.k"}, {r.alpha, R::alpha, "rain.alpha"}});
}

CloudsRain::CloudsRain(const CloudsRainConfig& cfg) : cfg_(cfg) {
  validate(cfg);
  for (std::size_t i = 0; i < cfg.layer_count; ++i) {
    const CloudLayer& l = cfg.layers[i];
    gamma_db_m_[i] = cloud_specific_attenuation_coeff(cfg.freq_hz, l.temperature_k) * l.liquid_water_g_m3 * 1e-3;
  }
  const RainConfig& r = cfg.rain;
  rain_gamma_db_m_ = rain_specific_attenuation_db_km(r.rate_mm_h, r.k, r.alpha) * 1e-3;
}

CloudsRainAttenuation CloudsRain::attenuation(double rx_height_m, double el_rad) const noexcept {
  CloudsRainAttenuation a;
  for (std::size_t i = 0; i < cfg_.layer_count; ++i) {
    if (gamma_db_m_[i] <= 0.0) continue;
    const CloudLayer& l = cfg_.layers[i];
    a.clouds_db += gamma_db_m_[i] * slant_path_in_shell_m(rx_height_m, el_rad, l.base_m, l.base_m + l.thickness_m);
  }
  if (rain_gamma_db_m_ > 0.0) {
    const double bottom = std::isfinite(rx_height_m) ? std::min(0.0, rx_height_m) : 0.0;
    a.rain_db = rain_gamma_db_m_ * slant_path_in_shell_m(rx_height_m, el_rad, bottom, cfg_.rain.rain_height_m);
  }
  return a;
}

}  // namespace gnssemu::atmosphere

// SPDX-License-Identifier: Apache-2.0
#include "core/world/measurement/propagation.hpp"

#include <cmath>

namespace gnssemu::world {

AtmospherePropagation::AtmospherePropagation(const AtmosphereConfig& cfg)
    : cfg_(cfg),
      iono_(cfg.ionosphere),
      tropo_(cfg.troposphere),
      shells_(cfg.shells),
      clouds_rain_(cfg.clouds_rain),
      iono_on_(cfg.ionosphere.enabled),
      tropo_on_(cfg.troposphere.enabled),
      gases_on_(cfg.gases),
      clouds_rain_on_(cfg.clouds_rain.layer_count > 0 || cfg.clouds_rain.rain.rate_mm_h > 0.0) {}

void AtmospherePropagation::set_klobuchar_shape(const orbit::KlobucharParams& p) {
  if (!p.valid || cfg_.ionosphere.shape.valid) return;
  atmosphere::IonosphereConfig c = cfg_.ionosphere;
  c.shape = p;
  iono_ = atmosphere::Ionosphere(c);
}

SlowTerms AtmospherePropagation::slow_terms(const Lla& rx, double az_rad, double el_rad, double tow_s,
                                            double doy) noexcept {
  SlowTerms s{};
  if (iono_on_) {
    const double per_tecu = iono_.mapping(el_rad) * atmosphere::iono_m_per_tecu(cfg_.ionosphere.freq_hz);
    s[kIonoMPerTecu] = per_tecu;
    s[kIonoM] = iono_.vtec_tecu(rx.lat_rad, rx.lon_rad, az_rad, el_rad, tow_s) * per_tecu;
  }
  if (tropo_on_) {
    const atmosphere::NiellMapping m = atmosphere::niell_mapping(el_rad, rx.lat_rad, rx.height_m, doy);
    s[kTropoM] = tropo_.zhd_m(rx.lat_rad, rx.height_m) * m.hydro + tropo_.zwd_m(rx.height_m) * m.wet;
    s[kNmfWet] = m.wet;
  }
  // Shells and layers are heights above the surface; the ellipsoidal height
  // stands in for it (no terrain model).
  if (gases_on_) s[kAttenDb] += gas_table_.total_db(shells_, rx.height_m, el_rad);
  if (clouds_rain_on_) {
    const atmosphere::CloudsRainAttenuation a = clouds_rain_.attenuation(rx.height_m, el_rad);
    s[kAttenDb] += a.clouds_db + a.rain_db;
  }
  return s;
}

}  // namespace gnssemu::world

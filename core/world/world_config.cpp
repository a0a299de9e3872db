// SPDX-License-Identifier: Apache-2.0
#include "core/world/world_config.hpp"

#include <string>

namespace gnssemu::world {

void validate(const WorldConfig& c) {
  using Gm = GaussMarkovRanges;
  using E = ErrorModelRanges;
  using K = ClockRanges;
  using A = AtmosphereRanges;
  const ErrorModelConfig& e = c.errors;
  const ErrorModelConfig::Gradient& g = e.gradient;
  const ClockConfig& k = c.clock;
  const AtmosphereConfig& a = c.atmosphere;
  check_ranges(
      "world config",
      {{static_cast<double>(c.bands), WorldRanges::bands, "bands"},
       {c.receiver_ifb_m, WorldRanges::receiver_ifb_m, "receiver_ifb_m"},
       {e.thermal_sigma_m, E::thermal_sigma_m, "errors.thermal_sigma_m"},
       {e.doppler_sigma_m_s, E::doppler_sigma_m_s, "errors.doppler_sigma_m_s"},
       {e.orbit_clock.sigma_m, Gm::sigma_m, "errors.orbit_clock.sigma_m"},
       {e.orbit_clock.tau_s, Gm::tau_s, "errors.orbit_clock.tau_s"},
       {e.multipath.sigma_m, Gm::sigma_m, "errors.multipath.sigma_m"},
       {e.multipath.tau_s, Gm::tau_s, "errors.multipath.tau_s"},
       {g.north_m, E::gradient_north_m, "errors.gradient.north_m"}, {g.east_m, E::gradient_east_m, "errors.gradient.east_m"},
       {g.north_diurnal_m, E::gradient_north_diurnal_m, "errors.gradient.north_diurnal_m"},
       {g.north_peak_h, E::gradient_north_peak_h, "errors.gradient.north_peak_h"},
       {g.east_diurnal_m, E::gradient_east_diurnal_m, "errors.gradient.east_diurnal_m"},
       {g.east_peak_h, E::gradient_east_peak_h, "errors.gradient.east_peak_h"},
       {g.process.sigma_m, Gm::sigma_m, "errors.gradient.sigma_m"}, {g.process.tau_s, Gm::tau_s, "errors.gradient.tau_s"},
       {e.iono_scale.sigma, E::iono_scale_sigma, "errors.iono_scale.sigma"},
       {e.iono_scale.tau_s, E::iono_scale_tau_s, "errors.iono_scale.tau_s"},
       {k.bias_s, K::bias_s, "clock.bias_s"}, {k.drift_s_s, K::drift_s_s, "clock.drift_s_s"},
       {k.drift_noise_s_s_sqrt_s, K::drift_noise_s_s_sqrt_s, "clock.drift_noise_s_s_sqrt_s"},
       {k.jump_threshold_s, K::jump_threshold_s, "clock.jump_threshold_s"},
       {c.nominal_cn0_dbhz, WorldRanges::nominal_cn0_dbhz, "nominal_cn0_dbhz"},
       {a.zwd_perturbation.sigma_m, A::zwd_perturbation_sigma_m, "atmosphere.zwd_perturbation.sigma_m"},
       {a.zwd_perturbation.tau_s, A::zwd_perturbation_tau_s, "atmosphere.zwd_perturbation.tau_s"},
       {a.cache_refresh_s, A::cache_refresh_s, "atmosphere.cache_refresh_s"}});
  atmosphere::validate(a.ionosphere);
  atmosphere::validate(a.troposphere);
  atmosphere::validate(a.shells);
  atmosphere::validate(a.clouds_rain);
  signal::validate(c.signal.link);
  signal::validate(c.signal.dll);
  validate(c.carrier);
}

void use_klobuchar_ionosphere(AtmosphereConfig& a, double scale, double sigma_tecu, double tau_s) noexcept {
  atmosphere::IonosphereConfig& io = a.ionosphere;
  io.enabled = true;
  io.source = atmosphere::VtecSource::kKlobucharShape;
  io.klobuchar_scale = scale > 0.0 ? scale : 0.0;
  io.mapping = atmosphere::IonoMapping::kObliquityFactor;
  io.obliquity_pivot_deg = 95.4;  // IS-GPS-200 20.3.3.5.2.5: F = 1 + 16 (0.53 - E)^3, E in semicircles
  io.perturbation = {sigma_tecu, tau_s};
}

void use_receiver_troposphere(AtmosphereConfig& a) noexcept {
  atmosphere::TroposphereConfig& tr = a.troposphere;
  tr.enabled = true;
  tr.zhd_model = atmosphere::ZhdModel::kSaastamoinen;
  tr.zwd_model = atmosphere::ZwdModel::kSaastamoinen;
  tr.rel_humidity = 0.7;  // the receiver's standard atmosphere
  a.zwd_perturbation.sigma_m = 0.0;
}

}  // namespace gnssemu::world

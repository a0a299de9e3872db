#include "core/world/world_config.hpp"

#include <cmath>
#include <string>

#include "core/common/error.hpp"

namespace gnssemu::world {

namespace {

void check(bool ok, const std::string& what) {
  if (!ok) throw Error("world config: " + what);
}

}  // namespace

void validate(const WorldConfig& c) {
  const ErrorModelConfig& e = c.errors;
  check(std::isfinite(e.thermal_sigma_m) && e.thermal_sigma_m >= 0.0, "errors.thermal_sigma_m must be >= 0");
  check(std::isfinite(e.orbit_clock.sigma_m) && e.orbit_clock.sigma_m >= 0.0,
        "errors.orbit_clock.sigma_m must be >= 0");
  check(std::isfinite(e.orbit_clock.tau_s) && e.orbit_clock.tau_s > 0.0, "errors.orbit_clock.tau_s must be > 0");
  check(std::isfinite(e.multipath.sigma_m) && e.multipath.sigma_m >= 0.0, "errors.multipath.sigma_m must be >= 0");
  check(std::isfinite(e.multipath.tau_s) && e.multipath.tau_s > 0.0, "errors.multipath.tau_s must be > 0");
  check(std::isfinite(e.gradient.north_m) && std::isfinite(e.gradient.east_m),
        "errors.gradient.north_m / east_m must be finite");
  check(std::isfinite(e.gradient.north_diurnal_m) && e.gradient.north_diurnal_m >= 0.0 &&
            std::isfinite(e.gradient.east_diurnal_m) && e.gradient.east_diurnal_m >= 0.0,
        "errors.gradient.north_diurnal_m / east_diurnal_m must be >= 0");
  check(e.gradient.north_peak_h >= 0.0 && e.gradient.north_peak_h < 24.0 && e.gradient.east_peak_h >= 0.0 &&
            e.gradient.east_peak_h < 24.0,
        "errors.gradient.north_peak_h / east_peak_h must be in [0, 24) h");
  check(std::isfinite(e.gradient.process.sigma_m) && e.gradient.process.sigma_m >= 0.0,
        "errors.gradient.sigma_m must be >= 0");
  check(std::isfinite(e.gradient.process.tau_s) && e.gradient.process.tau_s > 0.0,
        "errors.gradient.tau_s must be > 0");
  check(std::isfinite(e.doppler_sigma_m_s) && e.doppler_sigma_m_s >= 0.0, "errors.doppler_sigma_m_s must be >= 0");
  const ClockConfig& k = c.clock;
  check(std::isfinite(k.bias_s) && std::fabs(k.bias_s) < 1.0, "clock.bias_s must be finite and below 1 s");
  check(std::isfinite(k.drift_s_s) && std::fabs(k.drift_s_s) < 1e-3, "clock.drift_s_s must be below 1e-3");
  check(std::isfinite(k.drift_noise_s_s_sqrt_s) && k.drift_noise_s_s_sqrt_s >= 0.0,
        "clock.drift_noise_s_s_sqrt_s must be >= 0");
  check(std::isfinite(k.jump_threshold_s) && k.jump_threshold_s >= 0.0 && k.jump_threshold_s < 1.0,
        "clock.jump_threshold_s must be in [0, 1)");
  check(std::isfinite(c.nominal_cn0_dbhz) && c.nominal_cn0_dbhz > 0.0, "nominal_cn0_dbhz must be > 0");
  const AtmosphereConfig& a = c.atmosphere;
  check(std::isfinite(a.zwd_perturbation.sigma_m) && a.zwd_perturbation.sigma_m >= 0.0,
        "atmosphere.zwd_perturbation.sigma_m must be >= 0");
  check(std::isfinite(a.zwd_perturbation.tau_s) && a.zwd_perturbation.tau_s > 0.0,
        "atmosphere.zwd_perturbation.tau_s must be > 0");
  signal::validate(c.signal.dll);
}

}  // namespace gnssemu::world

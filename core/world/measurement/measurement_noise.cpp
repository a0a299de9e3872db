// SPDX-License-Identifier: Apache-2.0
#include "core/world/measurement/measurement_noise.hpp"

namespace gnssemu::world {

MeasurementNoise MeasurementNoise::of(const WorldConfig& c) noexcept {
  MeasurementNoise n;
  n.thermal_model = c.errors.thermal_model;
  n.thermal_sigma_m = c.errors.thermal_sigma_m;
  n.dll = c.signal.dll;
  n.doppler_sigma_m_s = c.errors.doppler_sigma_m_s;
  n.carrier = c.carrier;
  return n;
}

double MeasurementNoise::code_sigma_m(double cn0_dbhz) const noexcept {
  return thermal_model == ThermalModel::kDll ? signal::dll_thermal_sigma_m(cn0_dbhz, dll) : thermal_sigma_m;
}

double MeasurementNoise::range_rate_sigma_m_s(double cn0_dbhz, double wavelength_m) const noexcept {
  return carrier.doppler_model == DopplerModel::kFll ? fll_range_rate_sigma_m_s(cn0_dbhz, carrier, wavelength_m)
                                                     : doppler_sigma_m_s;
}

void validate(const MeasurementNoise& n) {
  signal::validate(n.dll);
  validate(n.carrier);
}

}  // namespace gnssemu::world

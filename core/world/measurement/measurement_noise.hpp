// SPDX-License-Identifier: Apache-2.0
#pragma once
// MeasurementNoise: how much white noise the world puts on a pseudorange and
// a range rate at a given C/N0 (errors.thermal_model, signal.dll,
// carrier.doppler_model). One owner, so the world and the fault stage —
// which adds the difference when a jammer lowers C/N0 — never disagree.
#include "core/signal/dll_jitter.hpp"
#include "core/world/measurement/carrier.hpp"
#include "core/world/world_config.hpp"

namespace gnssemu::world {

struct MeasurementNoise {
  ThermalModel thermal_model = ThermalModel::kDll;
  double thermal_sigma_m = 0.3;     ///< kFixed: at every C/N0, m
  signal::DllParams dll;            ///< kDll: code loop jitter versus C/N0
  double doppler_sigma_m_s = 0.03;  ///< DopplerModel::kFixed: at every C/N0, m/s
  CarrierConfig carrier;            ///< FLL jitter (kFll), PLL slips

  /// The noise settings of a world configuration.
  static MeasurementNoise of(const WorldConfig& c) noexcept;
  /// 1-sigma thermal pseudorange noise at cn0_dbhz, m.
  double code_sigma_m(double cn0_dbhz) const noexcept;
  /// 1-sigma range-rate noise at cn0_dbhz of a carrier of wavelength_m (m), m/s.
  double range_rate_sigma_m_s(double cn0_dbhz, double wavelength_m = kL1Wavelength_m) const noexcept;
};

/// Throws gnssemu::Error on parameters out of their ranges.
void validate(const MeasurementNoise& n);

}  // namespace gnssemu::world

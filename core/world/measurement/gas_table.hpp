// SPDX-License-Identifier: Apache-2.0
#pragma once
// Gaseous attenuation against elevation for one receiver height, filled
// lazily on a 0.25-degree grid and interpolated with the cubic through the
// four nearest nodes. AtmosphereShells::gas_attenuation integrates 256
// quadrature points (512 exp) per call; a static receiver needs each node
// once. Interpolation error against the quadrature: below 1e-5 dB above
// 2 degrees, below 3e-5 dB from 0.75 degrees (tests/unit/world/test_gas_table.cpp).
// Lower rays bend from crossing the shells to grazing the ground, a kink
// a cubic does not follow (0.02 dB): there every call integrates.
// Fixed storage, no allocation, no exceptions.
#include <array>

#include "core/atmosphere/shells.hpp"

namespace gnssemu::world {

class GasAttenuationTable {
public:
  /// The receiver may move this far up or down before the table starts
  /// over at its new height (the world's slow-term cache uses the same).
  static constexpr double kMaxHeightChange_m = 5.0;

  /// Total gaseous attenuation, dB, at rx_height_m along el_rad: the table's
  /// value when el_rad lies on it, the shells' quadrature otherwise.
  double total_db(const atmosphere::AtmosphereShells& shells, double rx_height_m, double el_rad) noexcept;

  /// Quadrature evaluations so far (for benchmarks and tests).
  long evaluations() const noexcept { return evaluations_; }

private:
  static constexpr double kStep_rad = 0.25 * 3.14159265358979323846 / 180.0;
  static constexpr double kFirst_rad = 0.5 * 3.14159265358979323846 / 180.0;  // node 0
  static constexpr int kNodes = 362;                                             // 0.5 deg .. 90.75 deg
  double node(const atmosphere::AtmosphereShells& shells, int i) noexcept;

  std::array<double, kNodes> db_{};
  std::array<bool, kNodes> have_{};
  double height_m_ = 0.0;
  bool valid_ = false;
  long evaluations_ = 0;
};

}  // namespace gnssemu::world

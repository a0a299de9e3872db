// SPDX-License-Identifier: Apache-2.0
#include "core/world/measurement/gas_table.hpp"

#include <cmath>

namespace gnssemu::world {

double GasAttenuationTable::node(const atmosphere::AtmosphereShells& shells, int i) noexcept {
  const auto k = static_cast<std::size_t>(i);
  if (!have_[k]) {
    db_[k] = shells.gas_attenuation(height_m_, kFirst_rad + i * kStep_rad).total_db;
    have_[k] = true;
    ++evaluations_;
  }
  return db_[k];
}

double GasAttenuationTable::total_db(const atmosphere::AtmosphereShells& shells, double rx_height_m,
                                     double el_rad) noexcept {
  const double x = (el_rad - kFirst_rad) / kStep_rad;
  // Nodes i-1 .. i+2 around x (i = floor(x)) must exist.
  if (!std::isfinite(rx_height_m) || !(x >= 1.0) || !(x < kNodes - 2.0)) {
    ++evaluations_;
    return shells.gas_attenuation(rx_height_m, el_rad).total_db;
  }
  if (!valid_ || std::fabs(rx_height_m - height_m_) > kMaxHeightChange_m) {
    have_.fill(false);
    height_m_ = rx_height_m;
    valid_ = true;
  }
  const int i = static_cast<int>(x);
  const double t = x - i;
  const double y0 = node(shells, i - 1), y1 = node(shells, i), y2 = node(shells, i + 1), y3 = node(shells, i + 2);
  // Lagrange cubic on the nodes -1, 0, 1, 2 at t.
  const double tm1 = t - 1.0, tm2 = t - 2.0, tp1 = t + 1.0;
  return -y0 * t * tm1 * tm2 / 6.0 + y1 * tp1 * tm1 * tm2 / 2.0 - y2 * tp1 * t * tm2 / 2.0 + y3 * tp1 * t * tm1 / 6.0;
}

}  // namespace gnssemu::world

// SPDX-License-Identifier: Apache-2.0
#include "core/faults/interference.hpp"

#include <algorithm>
#include <cmath>

#include "core/signal/link_budget.hpp"

namespace gnssemu::faults {

double spectral_factor(JammerKind kind) noexcept {
  switch (kind) {
    case JammerKind::kCw:
    case JammerKind::kNarrowband: return 1.0;
    case JammerKind::kWideband: return 2.0;
  }
  return 2.0;
}

double jammer_power_dbw(double eirp_dbw, double distance_m, double gain_dbi, double freq_hz) noexcept {
  return eirp_dbw - signal::free_space_path_loss_db(distance_m > 0.1 ? distance_m : 0.1, freq_hz) + gain_dbi;
}

double default_jammer_width_hz(JammerKind kind) noexcept {
  return kind == JammerKind::kWideband ? 2.0 * kCaChipRate_hz : 0.0;
}

double band_overlap_fraction(const JammerBand& j, const SignalBand& s) noexcept {
  const double s_lo = s.centre_hz - s.half_width_hz, s_hi = s.centre_hz + s.half_width_hz;
  if (!(j.width_hz > 0.0)) return j.centre_hz >= s_lo && j.centre_hz <= s_hi ? 1.0 : 0.0;
  const double j_lo = j.centre_hz - 0.5 * j.width_hz, j_hi = j.centre_hz + 0.5 * j.width_hz;
  const double overlap = std::min(j_hi, s_hi) - std::max(j_lo, s_lo);
  return overlap > 0.0 ? std::min(overlap / j.width_hz, 1.0) : 0.0;
}

double interference_density_w_hz(double j_w, JammerKind kind, const JammerBand& j, const SignalBand& s) noexcept {
  const double frac = band_overlap_fraction(j, s);
  if (!(frac > 0.0) || !(s.half_width_hz > 0.0)) return 0.0;
  if (kind == JammerKind::kWideband && j.width_hz > 0.0)
    return j_w / j.width_hz * (frac * j.width_hz / (2.0 * s.half_width_hz));
  return j_w * frac / (spectral_factor(kind) * s.half_width_hz);
}

double interference_density_w_hz_of_w(double j_w, JammerKind kind) noexcept {
  return j_w / (spectral_factor(kind) * kCaChipRate_hz);
}

double interference_density_w_hz(double j_dbw, JammerKind kind) noexcept {
  return interference_density_w_hz_of_w(std::pow(10.0, j_dbw / 10.0), kind);
}

double effective_cn0_dbhz(double cn0_dbhz, double n0_dbw_hz, double i0_w_hz) noexcept {
  if (!(i0_w_hz > 0.0)) return cn0_dbhz;
  const double n0_w_hz = std::pow(10.0, n0_dbw_hz / 10.0);
  return cn0_dbhz - 10.0 * std::log10(1.0 + i0_w_hz / n0_w_hz);
}

double agc_rise_db(double j_w, double n0_dbw_hz) noexcept {
  if (!(j_w > 0.0)) return 0.0;
  const double floor_w = std::pow(10.0, n0_dbw_hz / 10.0) * kFrontEndBandwidth_hz;
  return 10.0 * std::log10(1.0 + j_w / floor_w);
}

}  // namespace gnssemu::faults

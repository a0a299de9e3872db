// SPDX-License-Identifier: Apache-2.0
#include "core/world/measurement/carrier.hpp"

#include <algorithm>
#include <cmath>

#include "core/signal/dll_jitter.hpp"

namespace gnssemu::world {

namespace {

/// ln I0(x) for x >= 0 by the polynomial approximations of Abramowitz &
/// Stegun 9.8.1 (x <= 3.75) and 9.8.2 (beyond; relative error < 2e-7).
double log_bessel_i0(double x) noexcept {
  if (x <= 3.75) {
    const double t = (x / 3.75) * (x / 3.75);
    return std::log(1.0 + t * (3.5156229 + t * (3.0899424 + t * (1.2067492 + t * (0.2659732 + t * (0.0360768 + t * 0.0045813))))));
  }
  const double t = 3.75 / x;
  const double p = 0.39894228 + t * (0.01328592 + t * (0.00225319 + t * (-0.00157565 + t * (0.00916281 +
                   t * (-0.02057706 + t * (0.02635537 + t * (-0.01647633 + t * 0.00392377)))))));
  return x - 0.5 * std::log(x) + std::log(p);
}

}  // namespace

void validate(const CarrierConfig& c) {
  using R = CarrierRanges;
  check_ranges("carrier config", {{c.pll_bandwidth_hz, R::pll_bandwidth_hz, "pll_bandwidth_hz"},
                                  {c.fll_bandwidth_hz, R::fll_bandwidth_hz, "fll_bandwidth_hz"},
                                  {c.integration_s, R::integration_s, "integration_s"},
                                  {c.oscillator_sigma_rad, R::oscillator_sigma_rad, "oscillator_sigma_rad"},
                                  {c.lock_break_m, R::lock_break_m, "lock_break_m"}});
}

double pll_jitter_rad(double cn0_dbhz, double bandwidth_hz, double integration_s) noexcept {
  const double cn0 = signal::cn0_ratio_hz(cn0_dbhz);
  return std::sqrt(bandwidth_hz / cn0 * (1.0 + 1.0 / (2.0 * integration_s * cn0)));
}

double fll_range_rate_sigma_m_s(double cn0_dbhz, const CarrierConfig& c, double wavelength_m) noexcept {
  const double cn0 = signal::cn0_ratio_hz(cn0_dbhz);
  const double t = c.integration_s;
  const double sigma_hz = std::sqrt(4.0 * c.fll_bandwidth_hz / cn0 * (1.0 + 1.0 / (t * cn0))) / (2.0 * kPi * t);
  return wavelength_m * sigma_hz;
}

double cycle_slip_probability(double sigma_rad, double bandwidth_hz, double dt_s) noexcept {
  if (!(dt_s > 0.0) || !(bandwidth_hz > 0.0)) return 0.0;
  if (!(sigma_rad > 0.0)) return 0.0;
  const double rho = 1.0 / (4.0 * sigma_rad * sigma_rad);
  const double log_t = std::log(kPi * kPi * rho / (2.0 * bandwidth_hz)) + 2.0 * log_bessel_i0(rho);
  const double rate = std::exp(-log_t);  // slips per second
  return -std::expm1(-rate * dt_s);
}

}  // namespace gnssemu::world

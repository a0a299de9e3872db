#include "core/signal/dll_jitter.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/common/error.hpp"

namespace gnssemu::signal {

void validate(const DllParams& p) {
  using R = DllRanges;
  check_ranges("DLL config", {{p.loop_bandwidth_hz, R::loop_bandwidth_hz, "loop_bandwidth_hz"},
                              {p.integration_s, R::integration_s, "integration_s"},
                              {p.spacing_chips, R::spacing_chips, "spacing_chips"}, {p.chip_m, R::chip_m, "chip_m"}});
}

double dll_thermal_sigma_m(double cn0_dbhz, const DllParams& p) noexcept {
  const double cn0_db = std::isfinite(cn0_dbhz) ? std::clamp(cn0_dbhz, 0.0, 70.0) : 0.0;
  const double cn0 = std::pow(10.0, cn0_db / 10.0);
  const double d = p.spacing_chips;
  const double squaring = p.discriminator == DllDiscriminator::kDotProduct
                              ? 1.0 + 1.0 / (p.integration_s * cn0)
                              : 1.0 + 2.0 / (p.integration_s * cn0 * (2.0 - d));
  const double var_chips2 = p.loop_bandwidth_hz * d / (2.0 * cn0) * squaring;
  return std::sqrt(var_chips2) * p.chip_m;
}

void validate(const WeightModel& w) {
  if (!(std::isfinite(w.a_m) && w.a_m >= 0.0 && std::isfinite(w.b_m) && w.b_m >= 0.0 &&
        std::isfinite(w.c_m_sqrt_hz) && w.c_m_sqrt_hz >= 0.0))
    throw Error("weight model config", 0, "coefficients a, b, c must be finite and >= 0");
  if (!(std::isfinite(w.min_el_rad) && w.min_el_rad > 0.0 && w.min_el_rad < 1.5707963267948966))
    throw Error("weight model config", 0, "min_el_rad must be in (0, pi/2)");
}

double pseudorange_sigma_m(double cn0_dbhz, double el_rad, const WeightModel& w) noexcept {
  const double el = std::isfinite(el_rad) ? std::max(el_rad, w.min_el_rad) : w.min_el_rad;
  const double s = std::sin(std::min(el, 1.5707963267948966));
  const double cn0_db = std::isfinite(cn0_dbhz) ? std::clamp(cn0_dbhz, 0.0, 70.0) : 0.0;
  const double var = w.a_m * w.a_m + w.b_m * w.b_m / (s * s) +
                     w.c_m_sqrt_hz * w.c_m_sqrt_hz * std::pow(10.0, -cn0_db / 10.0);
  return std::sqrt(var);
}

double pseudorange_weight(double cn0_dbhz, double el_rad, const WeightModel& w) noexcept {
  const double s = pseudorange_sigma_m(cn0_dbhz, el_rad, w);
  return s > 0.0 ? 1.0 / (s * s) : 0.0;
}

}  // namespace gnssemu::signal

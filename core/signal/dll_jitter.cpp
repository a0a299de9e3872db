// SPDX-License-Identifier: Apache-2.0
#include "core/signal/dll_jitter.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/common/error.hpp"

namespace gnssemu::signal {

void validate(const DllParams& p) {
  using R = DllRanges;
  check_ranges("DLL config", {{p.loop_bandwidth_hz, R::loop_bandwidth_hz, "loop_bandwidth_hz"},
                              {p.integration_s, R::integration_s, "integration_s"},
                              {p.spacing_chips, R::spacing_chips, "spacing_chips"}, {p.chip_m, R::chip_m, "chip_m"}});
}

double cn0_ratio_hz(double cn0_dbhz) noexcept {
  const double db = std::isfinite(cn0_dbhz) ? std::clamp(cn0_dbhz, 0.0, 70.0) : 0.0;
  return std::exp(db * (std::numbers::ln10 / 10.0));  // 10^(dB/10); exp costs half of pow
}

double dll_thermal_sigma_m(double cn0_dbhz, const DllParams& p) noexcept {
  const double cn0 = cn0_ratio_hz(cn0_dbhz);
  const double d = p.spacing_chips;
  const double squaring = p.discriminator == DllDiscriminator::kDotProduct
                              ? 1.0 + 1.0 / (p.integration_s * cn0)
                              : 1.0 + 2.0 / (p.integration_s * cn0 * (2.0 - d));
  const double var_chips2 = p.loop_bandwidth_hz * d / (2.0 * cn0) * squaring;
  return std::sqrt(var_chips2) * p.chip_m;
}

}  // namespace gnssemu::signal

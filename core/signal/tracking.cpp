// SPDX-License-Identifier: Apache-2.0
#include "core/signal/tracking.hpp"

#include <string>

#include "core/common/error.hpp"

namespace gnssemu::signal {

std::optional<Violation> check_hysteresis(const TrackingThresholds& t) {
  if (!(t.lose_dbhz > t.acquire_dbhz)) return std::nullopt;
  return Violation{"lose_dbhz", "acquire_dbhz",
                   "lose_dbhz " + format_number(t.lose_dbhz) + " exceeds acquire_dbhz " + format_number(t.acquire_dbhz) +
                       " (hysteresis needs lose <= acquire)"};
}

void validate(const TrackingThresholds& t) {
  check_ranges("tracking config", {{t.acquire_dbhz, TrackingRanges::acquire_dbhz, "acquire_dbhz"},
                                   {t.lose_dbhz, TrackingRanges::lose_dbhz, "lose_dbhz"}});
  if (check_hysteresis(t))
    throw Error("tracking config", 0,
                "thresholds must be finite with lose <= acquire (acquire " + std::to_string(t.acquire_dbhz) +
                    " dB-Hz, lose " + std::to_string(t.lose_dbhz) + " dB-Hz)");
}

}  // namespace gnssemu::signal

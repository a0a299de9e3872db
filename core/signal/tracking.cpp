#include "core/signal/tracking.hpp"

#include <cmath>
#include <string>

#include "core/common/error.hpp"

namespace gnssemu::signal {

void validate(const TrackingThresholds& t) {
  if (!std::isfinite(t.acquire_dbhz) || !std::isfinite(t.lose_dbhz) || t.lose_dbhz > t.acquire_dbhz)
    throw Error("tracking config", 0,
                "thresholds must be finite with lose <= acquire (acquire " + std::to_string(t.acquire_dbhz) +
                    " dB-Hz, lose " + std::to_string(t.lose_dbhz) + " dB-Hz)");
}

}  // namespace gnssemu::signal

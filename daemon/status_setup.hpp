#pragma once
// The status producer's settings from a configuration, and the [status]
// section's checks (docs/status.md).
#include <string>

#include "config/config.hpp"
#include "daemon/status_producer.hpp"

namespace gnssemu::daemon {

/// Elevation mask, tracking thresholds, rate and time mode of cfg.
StatusSettings status_settings(const config::Config& cfg);

/// Throws gnssemu::Error naming cfg.source unless bind is an IP address.
void validate_status(const config::Config& cfg);

/// bind is a loopback address (127.0.0.0/8, ::1).
bool is_loopback(const std::string& bind);

}  // namespace gnssemu::daemon

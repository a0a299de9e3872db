// SPDX-License-Identifier: Apache-2.0
#pragma once
// The status producer's settings from a configuration, and where the page
// listens (docs/status.md).
#include <string>

#include "config/config.hpp"
#include "daemon/status/status_producer.hpp"

namespace gnssemu::daemon {

/// Elevation mask, tracking thresholds, rate and time mode of cfg.
StatusSettings status_settings(const config::Config& cfg);

/// bind is a loopback address (127.0.0.0/8, ::1).
bool is_loopback(const std::string& bind);

}  // namespace gnssemu::daemon

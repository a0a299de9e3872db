// SPDX-License-Identifier: Apache-2.0
#pragma once
// The promises of the observation reader (core/observation/rinex_obs.hpp),
// for the RINEX and Compact RINEX fuzz targets.
#include <string>

namespace gnssemu::fuzz {

/// Read path with read_rinex_obs. Oracles: errors are gnssemu::Error naming
/// the file; accepted epochs hold valid satellites of the SatId table with
/// one value per type of their system, times within the week, finite
/// values and clock offsets, and one-digit indicators.
void check_obs_file(const std::string& path);

}  // namespace gnssemu::fuzz

// SPDX-License-Identifier: Apache-2.0
#pragma once
// RINEX 2.10/2.11 and 3.00-3.05 observation file reader, GPS satellites only
// (others skipped and counted). Layouts: RINEX 2.11 Table A1, RINEX 3.05
// Tables A1-A3. Gzip-compressed files (.gz) are read transparently.
#include <istream>
#include <string>

#include "core/observation/obs_data.hpp"

namespace gnssemu::observation {

/// Read an observation file (plain or gzip). Throws gnssemu::Error
/// ("file:line: reason") on a missing file, an unsupported version, a time
/// system other than GPS, or a malformed header or record.
ObsData read_rinex_obs(const std::string& path);
/// Same, from an uncompressed stream; name is used in error messages.
ObsData read_rinex_obs(std::istream& in, const std::string& name);

}  // namespace gnssemu::observation

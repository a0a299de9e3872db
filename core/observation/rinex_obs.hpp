// SPDX-License-Identifier: Apache-2.0
#pragma once
// RINEX 2.10/2.11 and 3.00-3.05 observation file reader, every system of
// the SatId table (G R E C J S; others, e.g. NavIC, skipped and counted).
// Layouts: RINEX 2.11 Table A1, RINEX 3.05 Tables A1-A3. Gzip-compressed
// files (.gz) are read transparently, and so is Compact RINEX (Hatanaka
// 1.0/3.0, .crx/.d, plain or gzip): it is decoded epoch by epoch into the
// same reader (crinex_decoder.hpp).
#include <istream>
#include <string>

#include "core/observation/obs_data.hpp"

namespace gnssemu::observation {

/// Read an observation file (plain, gzip, Compact RINEX), keeping the
/// records of `systems` (others are checked as far as their satellite and
/// then passed over without reading their values: a GPS-only solution
/// reads a multi-GNSS day several times faster). Throws gnssemu::Error
/// ("file:line: reason") on a missing file, an unsupported version, a time
/// system other than GPS, or a malformed header or record.
ObsData read_rinex_obs(const std::string& path, SystemSet systems = SystemSet::all());
/// Same, from an uncompressed stream; name is used in error messages.
ObsData read_rinex_obs(std::istream& in, const std::string& name, SystemSet systems = SystemSet::all());

}  // namespace gnssemu::observation

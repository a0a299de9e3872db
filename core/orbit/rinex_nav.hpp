// SPDX-License-Identifier: Apache-2.0
#pragma once
// RINEX 2.10/2.11 and 3.x navigation file reader for every system in the
// system table: RINEX 3 mixed (M) or single-system files (G, R, E, C, J, S
// records; 3.05 5-line GLONASS), RINEX 2 GPS (N), GLONASS (G) and SBAS (H)
// files. Records of systems without a table row (I/NavIC) are skipped and
// counted. Layouts: RINEX 2.11 Tables A3-A16, RINEX 3.04 Tables A5-A16,
// 3.05 Table A11 (shared/reference/gps-orbits.md §6-7, multi-gnss.md §3).
#include <istream>
#include <string>
#include <vector>

#include "core/orbit/nav_data.hpp"

namespace gnssemu::orbit {

/// Read a navigation file, plain or gzip, line by line: the first line is
/// checked before the rest is read; lines over 1 KiB, files over 512 MiB
/// (decompressed) and more than 500000 ephemerides are refused. Throws
/// gnssemu::Error("file:line: reason") on a missing file, an unsupported
/// version, a malformed header/record (GLONASS frequency number outside
/// -7..+6, a Galileo record with both clock bits 8 and 9, a satellite number
/// outside its system's range, a record of another system in a
/// single-system file, an unknown system letter) or a limit.
NavData read_rinex_nav(const std::string& path);
/// Same, from a stream; name is used in error messages.
NavData read_rinex_nav(std::istream& in, const std::string& name);
/// Every file of paths read as above and merged into one (merge()); a
/// missing file or one without ephemerides is an error naming it.
NavData read_rinex_nav_files(const std::vector<std::string>& paths);

}  // namespace gnssemu::orbit

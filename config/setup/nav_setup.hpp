// SPDX-License-Identifier: Apache-2.0
#pragma once
// The nav data a configuration names ([nav] file, files, folder, almanac)
// and the constellation they give a run starting at a given time
// (docs/models.md §Orbits for any date). Load time.
#include <string>
#include <vector>

#include "config/config.hpp"
#include "core/orbit/constellation.hpp"
#include "core/orbit/nav_data.hpp"

namespace gnssemu::config {

/// True for RINEX navigation file names: "*.yyn" / "*.yyN" (RINEX 2) and
/// "*_xN.rnx" (RINEX 3 long names), each also with ".gz".
bool is_nav_file_name(const std::string& name);

/// nav_file, nav.files, then the RINEX nav files of nav.folder (by name).
/// Throws gnssemu::Error for a folder that cannot be listed or holds none.
std::vector<std::string> nav_paths(const Config& c);

/// Every nav file of nav_paths(c), read (plain or gzip) and merged (one
/// ephemeris store, orbit::merge). Throws gnssemu::Error naming file:line.
orbit::NavData load_nav(const Config& c);

/// The run's constellation for a run starting at start (GPS): nav.mode over
/// nav (load_nav), or nav.almanac_file for mode almanac. Throws
/// gnssemu::Error naming the data's coverage when the start cannot be served.
orbit::Constellation make_constellation(const Config& c, const orbit::NavData& nav, const time::GpsTime& start);

}  // namespace gnssemu::config

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Truth trajectory CSV for `gnssemu batch`: one header line, columns read by
// name (docs/cli.md). Positions as lat_deg,lon_deg,height_m or x_m,y_m,z_m;
// velocities optional as ve_m_s,vn_m_s,vu_m_s (local ENU at the sample);
// an optional `valid` column (1/0) marks rows where the antenna has no truth.
#include <istream>
#include <string>
#include <vector>

#include "core/common/vec3.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/truth_track.hpp"

namespace gnssemu::cli {

/// Read a truth CSV file, one sample per row converted to ECEF (a `valid` 0
/// row is a no-truth sample). Rows are strictly increasing in time. Throws
/// gnssemu::Error("file:line: column 'name': reason") on any bad input.
std::vector<world::TruthSample> read_truth_csv(const std::string& path);
/// Same, from a stream; name is used in error messages.
std::vector<world::TruthSample> read_truth_csv(std::istream& in, const std::string& name);

}  // namespace gnssemu::cli

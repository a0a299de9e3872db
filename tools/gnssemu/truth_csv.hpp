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

namespace gnssemu::cli {

/// One truth row, converted to ECEF.
struct TruthSample {
  time::GpsTime t;     ///< GPS time of the sample
  Ecef pos_m;          ///< antenna position, ECEF m
  Ecef vel_m_s;        ///< antenna velocity, ECEF m/s (valid when has_vel)
  bool has_vel = false;
  /// false: no truth from this row until the next valid one (antenna lost);
  /// pos_m and vel_m_s are then unset.
  bool valid = true;
};

/// Read a truth CSV file. Rows are strictly increasing in time. Throws
/// gnssemu::Error("file:line: column 'name': reason") on any bad input.
std::vector<TruthSample> read_truth_csv(const std::string& path);
/// Same, from a stream; name is used in error messages.
std::vector<TruthSample> read_truth_csv(std::istream& in, const std::string& name);

}  // namespace gnssemu::cli

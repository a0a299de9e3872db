// SPDX-License-Identifier: Apache-2.0
#pragma once
// Trajectories the C++ sender replays (docs/truth-protocol.md §C++ sender):
// a circle around the configured origin and a CSV file in the format of
// send_truth.py. Records carry no vehicle id; the caller sets it.
#include <string>
#include <vector>

#include "tools/senders/truth_record.hpp"

namespace gnssemu::senders {

struct CircleParams {
  double radius_m = 30.0;  ///< circle radius around the origin, m, > 0
  double speed_m_s = 5.0;  ///< speed along the circle (counter-clockwise seen from above), m/s, [0, 1000]
  double up_m = 0.0;       ///< height above the origin, m
};

/// The circle t_s seconds after it starts due east of the origin: ENU
/// position, ENU velocity, and as attitude the heading along the track
/// (roll = pitch = 0).
TruthRecord circle_at(const CircleParams& circle, double t_s) noexcept;

/// Reads a CSV trajectory: a header line naming the columns, then one row
/// per sample. Columns: sim_time_s (s, strictly increasing); one position
/// as lat_deg,lon_deg,height_m or e_m,n_m,u_m or x_m,y_m,z_m; optional ENU
/// velocity ve_m_s,vn_m_s,vu_m_s; optional gps_week,gps_tow_s. Blank lines
/// and lines starting with '#' are skipped. Throws gnssemu::Error naming
/// file:line on any bad input.
std::vector<TruthRecord> read_trajectory_csv(const std::string& path);

}  // namespace gnssemu::senders

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Truth trajectories a sweep makes instead of reading a file: a straight
// drive at constant speed and heading (speed 0: a static antenna), and the
// shift of any trajectory to a start hour of its GPS day.
#include <string>
#include <string_view>
#include <vector>

#include "core/world/truth_track.hpp"

namespace gnssemu::cli::sweep {

/// An inline table { generator = "line", name, week, tow_s, duration_s,
/// lat_deg, lon_deg, height_m, step_s, speed_m_s, heading_deg }.
struct TruthGenerator {
  std::string name;            ///< label in tasks.csv and plots
  int week = 0;                ///< GPS week of the first sample [0, 9999]
  double tow_s = 0.0;          ///< seconds of week of the first sample [0, 604800)
  double duration_s = 0.0;     ///< (0, 7 days]
  double step_s = 1.0;         ///< sample spacing (0, 3600]
  double lat_deg = 0.0, lon_deg = 0.0, height_m = 0.0;  ///< start point ([-90, 90], [-180, 180], [-1e4, 1e6])
  double speed_m_s = 0.0;      ///< ground speed [0, 1000]
  double heading_deg = 0.0;    ///< course from north, clockwise [0, 360)
};

/// Parse and check the inline table text (as sweep files write it). Errors
/// are gnssemu::Error(file, line, "truth generator: ...").
TruthGenerator parse_generator(std::string_view inline_toml, const std::string& file, int line);

/// True for an axis value that is a generator (inline table) rather than a path.
bool is_generator_text(std::string_view text) noexcept;

/// The samples: flat-earth ENU drive from the start point (accurate for the
/// few tens of km a drive covers; heights held).
std::vector<world::TruthSample> generate_truth(const TruthGenerator& g);

/// samples moved in time so the first is start_h hours after GPS midnight of
/// its own GPS day (start_h in [0, 24)).
void shift_to_hour(std::vector<world::TruthSample>& samples, double start_h);

/// A truth CSV that read_truth_csv reads back to the same samples to 0.1 mm:
/// gps_week,tow_s,x_m,y_m,z_m,ve_m_s,vn_m_s,vu_m_s,valid.
std::string truth_csv_text(const std::vector<world::TruthSample>& samples);

}  // namespace gnssemu::cli::sweep

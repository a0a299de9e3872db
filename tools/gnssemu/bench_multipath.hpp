// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu bench multipath`: time per epoch of the scene stage for a sweep of
// search effort (rays, bounces, reuse thresholds), next to the error each
// setting costs against a dense reference: satellites misclassified
// (LOS / NLOS / none), NLOS delay error, and the position error of the fix.
// Prints figures; never a test.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "core/scene/propagator.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::cli {

struct BenchMultipathArgs {
  std::string scene_path;           ///< .obj/.ply/.toml in the ENU frame of origin; or
  int city_blocks = 0;              ///< > 0: procedural city of city_blocks^2 blocks instead
  std::string write_city;           ///< write the generated city here as OBJ (optional)
  std::vector<double> origin;       ///< lat_deg, lon_deg, height_m of the scene frame
  std::vector<std::string> nav_paths;  ///< RINEX nav files (one store)
  std::optional<time::GpsTime> start;  ///< first epoch; default: nav coverage start + 2 h
  std::vector<double> path_en_m;    ///< drive polyline e0,n0,e1,n1,... (ENU m)
  double speed_m_s = 10.0;
  double rate_hz = 1.0;
  double antenna_height_m = 1.5;    ///< above the scene's z = 0
  double mask_deg = 5.0;
  int reference_rays = 65536;       ///< dense reference: rays (16 bounces, no reuse)
  int repeats = 3;                  ///< timing passes: the median one (by mean) gives mean, p95 and max
  /// Settings to run instead of the built-in sweep, 5 numbers each:
  /// azimuth_rays, rays, max_bounces, reuse_m, reuse_deg (empty: the sweep).
  std::vector<double> settings;
  double max_loss_db = scene::SearchConfig{}.max_loss_db;  ///< loss cap for reference and sweep, dB (1000: off)
};

/// Index of the median of the per-repeat means (the lower median for an
/// even count): the repeat whose mean, p95 and max are reported.
std::size_t median_repeat(const std::vector<double>& repeat_means);

/// Runs the sweep; CSV on out (one row per setting), context on err.
/// Throws gnssemu::Error on bad input.
void run_bench_multipath(const BenchMultipathArgs& args, std::ostream& out, std::ostream& err);

}  // namespace gnssemu::cli

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Pseudorange residuals of a real receiver at a known antenna position, the
// input of `gnssemu calibrate` (docs/cli.md, method step 1): C1C minus the
// geometric range, the broadcast satellite clock, the receiver's own
// corrections and the epoch's clock estimate.
#include <limits>
#include <vector>

#include "core/common/constants.hpp"
#include "core/common/vec3.hpp"
#include "core/observation/obs_data.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"

namespace gnssemu::cli {

/// One station-day (or any stretch) of observations of a receiver at a
/// known position.
struct CalibrationInput {
  const observation::ObsData* obs = nullptr;
  const orbit::NavData* nav = nullptr;
  std::string nav_path;         ///< written into the config
  Ecef station_m;               ///< known antenna position, ECEF m
  double mask_rad = 5.0 * kDegToRad;  ///< elevation mask, rad
};

/// Grid index stride between station-days: residuals of day d carry grid
/// d * kDayGridStride + epoch index, so no lag ever pairs two days.
inline constexpr int kDayGridStride = 1000000;

/// One satellite's pseudorange residual at the known position: pseudorange
/// minus geometric range, broadcast clock, the receiver's corrections and the
/// epoch's clock estimate (scaled by sqrt(n / (n - 1)) for the removed mean).
struct Residual {
  int grid = 0;               ///< epoch index on the regular grid (+ day * kDayGridStride)
  int day = 0;                ///< index of the station-day it came from
  double tow_s = 0.0;         ///< GPS time of week, s
  SatId sat;
  double el_rad = 0.0, az_rad = 0.0;
  double range_m = 0.0;       ///< geometric range, m
  double value_m = 0.0;       ///< residual, m
  double cn0_dbhz = std::numeric_limits<double>::quiet_NaN();  ///< S1C, dB-Hz (NaN if absent)
  double klobuchar_m = 0.0;   ///< broadcast Klobuchar delay the receiver removed, m
  double nmf_wet = 0.0;       ///< Niell wet mapping factor at el
};

/// Sampling interval of obs: the header INTERVAL, else the median epoch spacing, s.
double grid_step_s(const observation::ObsData& obs);

/// Residuals of every epoch with at least 5 satellites above in.mask_rad
/// (blunders beyond 30 m of the epoch median left out), in epoch order, tagged
/// with day. epochs_used: epochs that gave residuals. Throws gnssemu::Error
/// when the file has no C1C (RINEX 2: C1).
std::vector<Residual> station_residuals(const CalibrationInput& in, const orbit::EphemerisStore& store, double step_s,
                                        int day, int& epochs_used);

}  // namespace gnssemu::cli

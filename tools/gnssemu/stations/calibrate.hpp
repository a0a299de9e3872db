// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu calibrate`: fit the world's error model to real receivers at
// known positions, one or several station-days pooled (docs/cli.md,
// docs/validation.md "An error model that holds on unseen stations").
// Pseudorange residuals are formed at the known antenna position with the
// receiver's own corrections and a per-epoch clock estimate; their
// statistics give the model's means, random processes and correlation
// times, and S1C against elevation gives the C/N0 curve.
#include <ostream>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "core/common/vec3.hpp"
#include "core/statistics/statistics.hpp"
#include "tools/gnssemu/stations/calibration_fit.hpp"
#include "tools/gnssemu/stations/calibration_residuals.hpp"

namespace gnssemu::cli {

/// What one station-day gave.
struct DayCalibration {
  std::string source;                  ///< observation file
  int epochs = 0;                      ///< epochs with residuals (5+ satellites)
  int residuals = 0;                   ///< satellite residuals used
  statistics::PositionErrorStats spp;  ///< the data's own single-point errors (receiver solver)
  int spp_fixes = 0;
};

struct CalibrationResult {
  config::Config config;        ///< the fitted configuration (at the first station)
  int epochs = 0;               ///< epochs with residuals, all days
  int residuals = 0;            ///< satellite residuals used, all days
  double residual_rms_m = 0.0;  ///< RMS of the per-satellite residuals (clock removed)
  NoiseFit range_noise;         ///< one GM + white fitted to the pooled autocovariance (summary)
  AtmosphereBiasFit bias;       ///< means of the common terms and their processes
  AtmosphereBiasFit zwd_diagnostic;  ///< the means with a free ZWD offset (reported, not used)
  ProcessFit processes;         ///< the fitted per-satellite processes
  Cn0Fit cn0;                   ///< the C/N0 curve (n < 10: none, base antenna kept)
  std::vector<Residual> residual_rows;  ///< every residual used by the fit
  std::vector<DayCalibration> days;     ///< per station-day, in input order
};

/// Fit base's world model to the pooled data of days (all with the same
/// sampling interval and mask). Throws gnssemu::Error when a day gives too
/// few residuals (fewer than 100 epochs with 5+ satellites) or the days are
/// sampled differently.
CalibrationResult calibrate(const std::vector<CalibrationInput>& days, const config::Config& base);
/// One station-day.
CalibrationResult calibrate(const CalibrationInput& in, const config::Config& base);

/// base with the fitted error model of r (site-independent: the world's
/// troposphere is the receiver's own standard atmosphere at any height).
world::WorldConfig fitted_world(const CalibrationResult& r, const world::WorldConfig& base);

/// The fitted config as TOML (config::to_toml, paths relative to out_dir),
/// headed by comments with the fit.
std::string calibration_toml(const CalibrationResult& r, const std::string& out_dir);

/// `tow_s,sat,prn,el_deg,az_deg,residual_m,cn0_dbhz,klobuchar_m,nmf_wet` rows.
void write_residuals_csv(const CalibrationResult& r, std::ostream& out);

/// `parameter,value,unit` rows of the fit and the data's SPP statistics
/// (spp_* for one day; spp1_*, spp2_*, ... per day for several).
void write_calibration_report(const CalibrationResult& r, std::ostream& out);

}  // namespace gnssemu::cli

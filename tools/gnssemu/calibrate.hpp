#pragma once
// `gnssemu calibrate`: fit the receiver's error model to a real receiver at a
// known position (docs/cli.md, docs/validation.md "Calibration against a real
// receiver"). Pseudorange residuals are formed at the known antenna position
// with the receiver's own corrections and a per-epoch clock estimate; their
// statistics give the model's sigmas and correlation times, and S1C against
// elevation gives the C/N0 curve.
#include <ostream>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "core/common/vec3.hpp"
#include "core/observation/obs_data.hpp"
#include "core/orbit/nav_data.hpp"

namespace gnssemu::cli {

struct CalibrationInput {
  const observation::ObsData* obs = nullptr;
  const orbit::NavData* nav = nullptr;
  std::string nav_path;         ///< written into the config
  Ecef station_m;               ///< known antenna position, ECEF m
  double mask_rad = 5.0 * 0.017453292519943295;  ///< elevation mask, rad
};

/// First-order Gauss–Markov plus white noise fitted to an autocovariance.
struct NoiseFit {
  double gm_sigma_m = 0.0;   ///< Gauss–Markov steady-state sigma, m
  double gm_tau_s = 0.0;     ///< its correlation time, s
  double white_sigma_m = 0.0;///< white part, m
};

/// Statistics of a position-error series (fix minus truth, local ENU).
struct ErrorStats {
  int n = 0;
  double mean_e_m = 0.0, mean_n_m = 0.0, mean_u_m = 0.0;
  double sigma_e_m = 0.0, sigma_n_m = 0.0, sigma_u_m = 0.0;  ///< standard deviations
  double cep50_m = 0.0, cep95_m = 0.0;  ///< 50 % / 95 % quantiles of hypot(e, n)
  /// Lag at which the mean autocorrelation of e, n, u (about their means)
  /// first falls below 1/e, s (linear interpolation between lags).
  double corr_time_s = 0.0;
};

/// e, n, u series on a regular grid of step_s seconds (gaps are not allowed).
ErrorStats error_stats(const std::vector<Enu>& errors, double step_s);

/// Fit sigma^2 exp(-lag/tau) to autocovariance lags 1..K (least squares,
/// tau on a log grid 30 s..6 h) and the white part from lag 0.
/// acov[k] at lag k * step_s, m^2 (k = 0..K).
NoiseFit fit_gauss_markov(const std::vector<double>& acov, double step_s);

struct CalibrationResult {
  config::Config config;        ///< the fitted configuration
  int epochs = 0;               ///< epochs with residuals (4+ satellites)
  int residuals = 0;            ///< satellite residuals used
  double residual_rms_m = 0.0;  ///< RMS of the per-satellite residuals (clock removed)
  NoiseFit range_noise;         ///< per-satellite residual process
  double cn0_rms_db = 0.0;      ///< S1C minus the fitted C/N0 curve, RMS, dB-Hz
  double cn0_zenith_dbhz = 0.0; ///< fitted C/N0 at 90 deg and at the mean range
  double cn0_slope_db = 0.0;    ///< fitted antenna gain change zenith -> horizon, dB
  int cn0_samples = 0;
  ErrorStats spp;               ///< the data's own single-point errors (receiver solver)
  int spp_fixes = 0;
};

/// Fit base's receiver model to the data. Throws gnssemu::Error when the data
/// give too few residuals (fewer than 100 epochs with 5+ satellites).
CalibrationResult calibrate(const CalibrationInput& in, const config::Config& base);

/// The fitted config as TOML (config::to_toml, paths relative to out_dir),
/// headed by comments with the fit.
std::string calibration_toml(const CalibrationResult& r, const std::string& out_dir);

/// `parameter,value,unit` rows of the fit and the data's SPP statistics.
void write_calibration_report(const CalibrationResult& r, std::ostream& out);

}  // namespace gnssemu::cli

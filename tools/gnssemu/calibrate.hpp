#pragma once
// `gnssemu calibrate`: fit the receiver's error model to a real receiver at a
// known position (docs/cli.md, docs/validation.md "Calibration against a real
// receiver"). Pseudorange residuals are formed at the known antenna position
// with the receiver's own corrections and a per-epoch clock estimate; their
// statistics give the model's sigmas and correlation times, and S1C against
// elevation gives the C/N0 curve.
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "core/common/vec3.hpp"
#include "core/observation/obs_data.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/statistics/statistics.hpp"

namespace gnssemu::cli {

struct CalibrationInput {
  const observation::ObsData* obs = nullptr;
  const orbit::NavData* nav = nullptr;
  std::string nav_path;         ///< written into the config
  Ecef station_m;               ///< known antenna position, ECEF m
  double mask_rad = 5.0 * 0.017453292519943295;  ///< elevation mask, rad
};

/// One satellite's pseudorange residual at the known position: pseudorange
/// minus geometric range, broadcast clock, the receiver's corrections and the
/// epoch's clock estimate (scaled by sqrt(n / (n - 1)) for the removed mean).
struct Residual {
  int grid = 0;               ///< epoch index on the regular grid
  double tow_s = 0.0;         ///< GPS time of week, s
  int prn = 0;
  double el_rad = 0.0, az_rad = 0.0;
  double range_m = 0.0;       ///< geometric range, m
  double value_m = 0.0;       ///< residual, m
  double cn0_dbhz = std::numeric_limits<double>::quiet_NaN();  ///< S1C, dB-Hz (NaN if absent)
  double klobuchar_m = 0.0;   ///< broadcast Klobuchar delay the receiver removed, m
  double nmf_wet = 0.0;       ///< Niell wet mapping factor at el
  double local_time_rad = 0.0;  ///< local mean solar time at the station, 2 pi per day
};

/// First-order Gauss–Markov plus white noise fitted to an autocovariance.
struct NoiseFit {
  double gm_sigma_m = 0.0;   ///< Gauss–Markov steady-state sigma, m
  double gm_tau_s = 0.0;     ///< its correlation time, s
  double white_sigma_m = 0.0;///< white part, m
};

/// Fit sigma^2 exp(-lag/tau) to autocovariance lags 1..K (least squares,
/// tau on a log grid 30 s..6 h) and the white part from lag 0.
/// acov[k] at lag k * step_s, m^2 (k = 0..K).
NoiseFit fit_gauss_markov(const std::vector<double>& acov, double step_s);

/// What is common to the satellites of an epoch, fitted with the epoch clock
/// removed: residual = alpha Klobuchar + beta Niell_wet + G_N cos(az) + G_E sin(az)
/// + clock (least squares over all epochs, each epoch demeaned), where
/// G_N = gradient_north_m + north_cos_m cos(LT) + north_sin_m sin(LT) (E alike)
/// when the daily cycle is fitted (data spanning kMinDiurnalSpan_s or more).
struct AtmosphereBiasFit {
  double klobuchar_alpha = 0.0;  ///< world ionosphere = (1 + alpha) x Klobuchar
  double zwd_beta_m = 0.0;       ///< world zenith wet delay minus the receiver's, m
  double correlation = 0.0;      ///< correlation of the Klobuchar and wet regressors (conditioning)
  double gradient_north_m = 0.0, gradient_east_m = 0.0;  ///< mean azimuthal pattern, m
  bool diurnal = false;          ///< the daily cycle was fitted
  double north_cos_m = 0.0, north_sin_m = 0.0;  ///< daily cycle of G_N, m
  double east_cos_m = 0.0, east_sin_m = 0.0;    ///< daily cycle of G_E, m
  /// G_N, G_E of residual r (mean plus daily cycle), m.
  double north_at(const Residual& r) const;
  double east_at(const Residual& r) const;
  /// Variation of G_N, G_E about the mean: per-epoch estimates, their
  /// autocovariance less what the per-satellite processes leak into them,
  /// one Gauss–Markov fitted (fit_gauss_markov).
  double gradient_sigma_m = 0.0, gradient_tau_s = 0.0;
  double gradient_leak_m = 0.0;  ///< RMS leakage of the per-satellite processes removed, m
};

/// The per-satellite residual processes, fitted jointly to the pooled
/// autocovariance products x(t) x(t + k dt) of each satellite (lags 0..4 h):
///   E[x1 x2] = [k = 0] B_L s_dll^2(C/N0(el1))             white DLL noise
///            + s_mp^2 / (sin el1 sin el2) exp(-k dt / tau_mp)   multipath
///            + s_oc^2 exp(-k dt / tau_oc)                  orbit / clock
///            + s_tec^2 m1 m2 exp(-k dt / tau_tec)          iono perturbation
/// with s_dll the DLL jitter at 1 Hz loop bandwidth and m = m/TECU x obliquity;
/// linear least squares in the variances for each tau triple on a log grid
/// (30 s .. 12 h), the triple with the smallest residual sum kept.
struct ProcessFit {
  double dll_bandwidth_hz = 0.0;  ///< B_L that gives the white part, Hz
  double multipath_sigma_m = 0.0, multipath_tau_s = 0.0;      ///< zenith sigma, m; s
  double orbit_clock_sigma_m = 0.0, orbit_clock_tau_s = 0.0;  ///< m; s
  double iono_sigma_tecu = 0.0, iono_tau_s = 0.0;             ///< vertical TEC, TECU; s
  long pairs = 0;                                             ///< products used
};

/// Shortest span of data over which the daily cycle of the gradient is
/// fitted (10 h, 5/12 of the cycle: less cannot separate it from the mean), s.
inline constexpr double kMinDiurnalSpan_s = 36000.0;

/// The common terms of AtmosphereBiasFit (not the gradient process) from
/// residuals ordered by grid (epoch); the daily cycle only with diurnal.
AtmosphereBiasFit fit_atmosphere_bias(const std::vector<Residual>& res, bool diurnal = false);

struct CalibrationResult {
  config::Config config;        ///< the fitted configuration
  int epochs = 0;               ///< epochs with residuals (4+ satellites)
  int residuals = 0;            ///< satellite residuals used
  double residual_rms_m = 0.0;  ///< RMS of the per-satellite residuals (clock removed)
  NoiseFit range_noise;         ///< one GM + white fitted to the pooled autocovariance (summary)
  AtmosphereBiasFit bias;       ///< iono scale and tropo residual
  ProcessFit processes;         ///< the fitted error processes written to the config
  double cn0_rms_db = 0.0;      ///< S1C minus the fitted C/N0 curve, RMS, dB-Hz
  double cn0_zenith_dbhz = 0.0; ///< fitted C/N0 at 90 deg and at the mean range
  double cn0_slope_db = 0.0;    ///< fitted antenna gain change zenith -> horizon, dB
  int cn0_samples = 0;
  std::vector<Residual> residual_rows;  ///< every residual used by the fit
  statistics::PositionErrorStats spp;  ///< the data's own single-point errors (receiver solver)
  int spp_fixes = 0;
};

/// Fit base's receiver model to the data. Throws gnssemu::Error when the data
/// give too few residuals (fewer than 100 epochs with 5+ satellites).
CalibrationResult calibrate(const CalibrationInput& in, const config::Config& base);

/// The fitted config as TOML (config::to_toml, paths relative to out_dir),
/// headed by comments with the fit.
std::string calibration_toml(const CalibrationResult& r, const std::string& out_dir);

/// `tow_s,prn,el_deg,az_deg,residual_m,cn0_dbhz,klobuchar_m,nmf_wet` rows.
void write_residuals_csv(const CalibrationResult& r, std::ostream& out);

/// `parameter,value,unit` rows of the fit and the data's SPP statistics.
void write_calibration_report(const CalibrationResult& r, std::ostream& out);

}  // namespace gnssemu::cli

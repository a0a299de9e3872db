// SPDX-License-Identifier: Apache-2.0
#pragma once
// The fits of `gnssemu calibrate` (docs/cli.md, method steps 2-5) on
// residuals of one or several station-days: the mean common terms, the
// random processes of what is common to an epoch's satellites, the
// per-satellite processes and the C/N0 curve. Everything that does not
// persist from one stretch of data to the next is a random process with a
// fitted variance and time scale, not a constant.
#include <array>
#include <vector>

#include "core/signal/dll_jitter.hpp"
#include "core/signal/link_budget.hpp"
#include "tools/gnssemu/stations/calibration_residuals.hpp"

namespace gnssemu::cli {

/// First-order Gauss–Markov plus white noise fitted to an autocovariance.
struct NoiseFit {
  double gm_sigma_m = 0.0;   ///< Gauss–Markov steady-state sigma, m
  double gm_tau_s = 0.0;     ///< its correlation time, s
  double white_sigma_m = 0.0;///< white part, m
};

/// Fit sigma^2 exp(-lag/tau) to autocovariance lags 1..K (least squares,
/// tau on a log grid 30 s..max_tau_s) and the white part from lag 0.
/// acov[k] at lag k * step_s, m^2 (k = 0..K).
NoiseFit fit_gauss_markov(const std::vector<double>& acov, double step_s, double max_tau_s = 21600.0);

/// Pooled autocovariance of the per-satellite series, lags 0..max_lag steps.
std::vector<double> pooled_autocovariance(const std::vector<Residual>& res, int max_lag);

/// What is common to the satellites of an epoch, fitted with the epoch clock
/// removed: residual = alpha Klobuchar [+ beta Niell_wet] + G_N cos(az) +
/// G_E sin(az) + clock (least squares over all epochs of all days, each epoch
/// demeaned): the means. What varies about them (per-epoch estimates, see
/// fit_common_processes) is a random process. The model leaves beta out:
/// Klobuchar and wet regressors are nearly collinear (correlation 0.7-0.94
/// at the five station-days) and the Klobuchar term alone explains as much
/// of the residual as both on three of them (docs/validation.md); beta is
/// fitted only as a diagnostic.
struct AtmosphereBiasFit {
  double klobuchar_alpha = 0.0;  ///< world ionosphere = (1 + alpha) x Klobuchar
  double zwd_beta_m = 0.0;       ///< with_zwd: world zenith wet delay minus the receiver's, m
  double correlation = 0.0;      ///< correlation of the Klobuchar and wet regressors (conditioning)
  double gradient_north_m = 0.0, gradient_east_m = 0.0;  ///< mean azimuthal pattern, m
  /// The Klobuchar scale per epoch about 1 + alpha, relative to it: one
  /// Gauss–Markov (sigma as a fraction of the world's ionosphere, tau).
  double scale_sigma = 0.0, scale_tau_s = 0.0;
  double scale_leak = 0.0;       ///< RMS leakage of the per-satellite processes removed (fraction)
  /// G_N, G_E per epoch about their means: one Gauss–Markov each (pooled).
  double gradient_sigma_m = 0.0, gradient_tau_s = 0.0;
  double gradient_leak_m = 0.0;  ///< RMS leakage of the per-satellite processes removed, m
};

/// The means of AtmosphereBiasFit from residuals ordered by grid (epoch);
/// beta only with_zwd (else 0).
AtmosphereBiasFit fit_atmosphere_bias(const std::vector<Residual>& res, bool with_zwd = false);

/// One epoch's common terms about the means: a_t (Klobuchar scale error,
/// fraction of the Klobuchar delay), G_N,t, G_E,t (m), with the estimator's
/// weight of each residual (so the leakage of per-satellite processes into
/// them can be computed).
struct CommonEpoch {
  int grid = 0;
  std::array<double, 3> value{};                   ///< a_t, G_N,t (m), G_E,t (m)
  std::size_t first = 0, last = 0;                 ///< residuals [first, last)
  std::vector<std::array<double, 3>> weights;      ///< estimator row per residual
};

/// Remove alpha, beta, the mean gradient and each epoch's own common terms
/// (then the epoch mean again, variance re-inflated for the 3 parameters per
/// epoch) from res; returns the per-epoch terms of epochs with 6+ satellites.
std::vector<CommonEpoch> remove_common_terms(std::vector<Residual>& res, const AtmosphereBiasFit& b);

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

/// res: after remove_common_terms; link gives C/N0(el) (the fitted curve).
ProcessFit fit_processes(const std::vector<Residual>& res, const signal::LinkBudgetConfig& link,
                         const signal::DllParams& dll, double step_s);

/// The Gauss–Markov processes of the per-epoch common terms: their pooled
/// autocovariance (lags to 12 h within a day) less the leakage of the fitted
/// per-satellite processes into the estimator, sum_i w_i(t) w_i(t + k)
/// C_i(k) (same PRN), then fit_gauss_markov (tau up to 2 days: a term that
/// holds for a whole day is a slow process, not a constant). Fills the
/// scale_* and gradient_* fields of out. res: the residuals before
/// remove_common_terms (its epoch indices).
void fit_common_processes(const std::vector<CommonEpoch>& epochs, const std::vector<Residual>& res,
                          const ProcessFit& p, double step_s, AtmosphereBiasFit& out);

/// Antenna pattern of the link budget fitted to S1C.
struct Cn0Fit {
  signal::AntennaPattern antenna;
  double rms_db = 0.0;       ///< S1C about the fitted curve, dB-Hz
  double zenith_dbhz = 0.0;  ///< fitted C/N0 at 90 deg and the mean range
  double slope_db = 0.0;     ///< gain change zenith -> horizon, dB
  int n = 0;                 ///< S1C samples (fewer than 10: no fit)
};

/// S1C + FSPL(range) = const + slope (1 - sin el), least squares; the
/// constant through link's EIRP and noise terms gives the zenith gain.
Cn0Fit fit_cn0(const std::vector<Residual>& res, const signal::LinkBudgetConfig& link);

}  // namespace gnssemu::cli

// SPDX-License-Identifier: Apache-2.0
#pragma once
// WorldConfig: what happens to the signals between the satellites and the
// antenna (DESIGN.md §1, steps 1-5): error processes, the receiver
// oscillator's truth, the atmosphere and the signal model. The receiver does
// not know any of it. All values SI.
#include <cstdint>
#include <optional>

#include "core/atmosphere/clouds_rain.hpp"
#include "core/atmosphere/ionosphere.hpp"
#include "core/atmosphere/shells.hpp"
#include "core/atmosphere/term_cache.hpp"
#include "core/atmosphere/troposphere.hpp"
#include "core/common/range.hpp"
#include "core/common/sat_id.hpp"
#include "core/signal/dll_jitter.hpp"
#include "core/signal/link_budget.hpp"
#include "core/world/measurement/carrier.hpp"

namespace gnssemu::world {

/// First-order Gauss–Markov process: steady-state sigma and correlation time.
struct GaussMarkovConfig {
  double sigma_m = 0.0;     ///< steady-state 1-sigma, m (>= 0; 0 disables)
  double tau_s = 1800.0;    ///< correlation time, s (> 0)
};

/// Valid values of a GaussMarkovConfig of the error model.
struct GaussMarkovRanges {
  static constexpr Range sigma_m{0.0, 100.0, "m"};
  static constexpr Range tau_s{0.0, 1.0e6, "s", true};
};

/// Where the white pseudorange noise sigma comes from.
enum class ThermalModel {
  kFixed,  ///< errors.thermal_sigma_m for every satellite
  kDll,    ///< DLL thermal jitter at the satellite's C/N0 (signal.dll)
};

struct ErrorModelConfig {
  ThermalModel thermal_model = ThermalModel::kDll;
  double thermal_sigma_m = 0.3;                  ///< kFixed: white pseudorange noise, m
  GaussMarkovConfig orbit_clock{1.2, 1800.0};    ///< broadcast orbit/clock residual per satellite
  double doppler_sigma_m_s = 0.03;               ///< white range-rate noise, m/s
  /// Multipath-like residual per satellite: a unit Gauss–Markov process (tau_s)
  /// times sigma_m / sin(el) (el held at >= 5 deg), so sigma_m is the zenith
  /// 1-sigma, m; sigma_m 0 disables (the default).
  GaussMarkovConfig multipath{0.0, 60.0};
  /// Azimuthal delay pattern common to all satellites (an unmodelled
  /// horizontal gradient): delay += G_N cos(az) + G_E sin(az), m, with
  /// G_N = north_m + north_diurnal_m cos(2 pi (LT - north_peak_h) / 24 h) + g_N(t)
  /// (E alike), LT the local mean solar time at the receiver from GPS time and
  /// longitude (IS-GPS-200 20.3.3.5.2.5 convention), and g_N, g_E two
  /// independent Gauss–Markov processes (sigma_m, tau_s). Fitted by
  /// `gnssemu calibrate`; all zero (the default) disables it.
  struct Gradient {
    double north_m = 0.0;          ///< mean north component, m
    double east_m = 0.0;           ///< mean east component, m
    double north_diurnal_m = 0.0;  ///< amplitude of the daily cycle of G_N, m (>= 0)
    double north_peak_h = 0.0;     ///< local time of its maximum, h [0, 24)
    double east_diurnal_m = 0.0;   ///< amplitude of the daily cycle of G_E, m (>= 0)
    double east_peak_h = 0.0;      ///< local time of its maximum, h [0, 24)
    GaussMarkovConfig process{0.0, 3600.0};
  } gradient;
  /// What the broadcast ionosphere gets wrong for the whole sky at once: the
  /// world's ionospheric delay of every line of sight is multiplied by
  /// 1 + sigma x(t), x a unit Gauss–Markov process (tau_s). Fitted by
  /// `gnssemu calibrate` from the per-epoch Klobuchar scale; sigma 0 (the
  /// default) disables it.
  struct IonoScale {
    double sigma = 0.0;     ///< steady-state 1-sigma of the relative error (>= 0; 0.2 = 20 %)
    double tau_s = 3600.0;  ///< correlation time, s (> 0)
  } iono_scale;
};

/// Valid values of ErrorModelConfig's own numbers and of its gradient's
/// (orbit_clock, multipath and gradient.process: GaussMarkovRanges).
struct ErrorModelRanges {
  static constexpr Range thermal_sigma_m{0.0, 100.0, "m"};
  static constexpr Range doppler_sigma_m_s{0.0, 10.0, "m/s"};
  static constexpr Range gradient_north_m{-100.0, 100.0, "m"};
  static constexpr Range gradient_east_m{-100.0, 100.0, "m"};
  static constexpr Range gradient_north_diurnal_m{0.0, 100.0, "m"};
  static constexpr Range gradient_north_peak_h{0.0, 24.0, "h", false, true};
  static constexpr Range gradient_east_diurnal_m{0.0, 100.0, "m"};
  static constexpr Range gradient_east_peak_h{0.0, 24.0, "h", false, true};
  static constexpr Range iono_scale_sigma{0.0, 2.0, ""};
  static constexpr Range iono_scale_tau_s{0.0, 1.0e7, "s", true};
};

/// The receiver's oscillator as it really runs (the receiver estimates it).
struct ClockConfig {
  double bias_s = 1.0e-4;            ///< initial receiver clock bias, s
  double drift_s_s = 5.0e-8;         ///< initial clock drift, s/s (TCXO-like)
  double drift_noise_s_s_sqrt_s = 1.0e-10;  ///< drift random walk density, s/s/sqrt(s)
  /// |bias| above this makes the receiver step its clock by a whole multiple of
  /// it (millisecond jumps of unsteered receivers), s; 0 disables.
  double jump_threshold_s = 1.0e-3;
};

/// Valid values of ClockConfig's fields: u-blox receivers steer their clock
/// to within 1 ms; TCXO drift stays within 10 ppm.
struct ClockRanges {
  static constexpr Range bias_s{-1.0e-2, 1.0e-2, "s"};
  static constexpr Range drift_s_s{-1.0e-5, 1.0e-5, "s/s"};
  static constexpr Range drift_noise_s_s_sqrt_s{0.0, 1.0e-6, "s/s/sqrt(s)"};
  static constexpr Range jump_threshold_s{0.0, 1.0e-2, "s"};
};

/// The atmosphere the world applies to the signal (the receiver does not know
/// it). A stage whose switch is off costs nothing per epoch.
struct AtmosphereConfig {
  atmosphere::IonosphereConfig ionosphere;    ///< enabled; Klobuchar shape x 1 + GM 1 TECU / 1800 s
  atmosphere::TroposphereConfig troposphere;  ///< enabled; 2.31 exp(-1.2e-4 h) + 0.10 m wet, Niell
  /// Slow Gauss–Markov variation of the zenith wet delay (one process for the
  /// site, mapped with the Niell wet function), m; sigma 0 disables.
  GaussMarkovConfig zwd_perturbation{0.02, 3600.0};
  bool gases = true;                          ///< oxygen + water vapour over the shells
  atmosphere::ShellsConfig shells;
  atmosphere::CloudsRainConfig clouds_rain;   ///< no clouds, no rain
  /// Per-satellite refresh interval of the slow terms (iono and tropo delay
  /// without their perturbations, attenuation), s; 0 = every epoch.
  double cache_refresh_s = 5.0;
  atmosphere::CacheMode cache_mode = atmosphere::CacheMode::kLinear;
};

/// Valid values of AtmosphereConfig's own numbers (its models have theirs:
/// IonosphereRanges, TroposphereRanges, ShellRanges, GasRanges,
/// CloudLayerRanges, RainRanges).
struct AtmosphereRanges {
  static constexpr Range zwd_perturbation_sigma_m{0.0, 1.0, "m"};
  static constexpr Range zwd_perturbation_tau_s{0.0, 1.0e6, "s", true};
  static constexpr Range cache_refresh_s{0.0, 3600.0, "s"};
};

/// Signal stage: link budget -> C/N0, code noise.
struct SignalConfig {
  /// false: no link budget; C/N0 = nominal_cn0_dbhz - 10 (1 - sin el)^2 and
  /// every received satellite is strong enough to track.
  bool enabled = true;
  signal::LinkBudgetConfig link;         ///< EIRP, antenna, noise figure, environment noise rise
  signal::DllParams dll;                 ///< thermal jitter when errors.thermal_model = kDll
};

struct WorldConfig {
  /// Seed of the receiver's own random processes (multipath, noise,
  /// carrier, clock); deterministic.
  uint64_t seed = 1;
  /// Seed of the processes of the sky it is under (SkyErrors: orbit/clock
  /// residuals, atmosphere), shared by every receiver there; none: seed.
  std::optional<uint64_t> sky_seed;
  ErrorModelConfig errors;
  ClockConfig clock;
  double nominal_cn0_dbhz = 45.0;  ///< zenith C/N0 when signal.enabled is false, dB-Hz
  AtmosphereConfig atmosphere;
  SignalConfig signal;
  CarrierConfig carrier;           ///< carrier phase, Doppler noise, cycle slips
  /// Systems whose signals are modelled (the receiver's configured
  /// constellations, `[receiver] constellations`); the others' satellites are
  /// not in the sky this world computes, whatever the nav data hold.
  SystemSet systems = SystemSet::only(GnssSystem::kGps);
  /// Bands modelled per satellite: 1 the L1-band signal; 2 also each
  /// system's second signal (SatObservable::band1), for a receiver that
  /// tracks it (its `[receiver] bands`).
  int bands = 1;
  /// The receiver's code delay on the second signal over the first (its
  /// inter-frequency bias), m; the phase's lies in the ambiguity.
  double receiver_ifb_m = 0.3;
};

/// The sky seed of c (its own, else its seed).
inline uint64_t sky_seed(const WorldConfig& c) noexcept { return c.sky_seed.value_or(c.seed); }

/// Valid values of WorldConfig's own numbers (seed: any).
struct WorldRanges {
  static constexpr Range nominal_cn0_dbhz{10.0, 60.0, "dB-Hz"};
  static constexpr Range bands{1.0, 2.0, ""};  ///< integer
  static constexpr Range receiver_ifb_m{-100.0, 100.0, "m"};
};

/// Throws gnssemu::Error for a value out of its range anywhere in c (its
/// models' validators included).
void validate(const WorldConfig& c);

/// The world's ionosphere as fitted error models have it: the broadcast
/// Klobuchar shape x scale (>= 0) with the broadcast obliquity (what the
/// receiver removes is 1 x the same), plus the per-line-of-sight TEC process
/// (sigma_tecu, tau_s).
void use_klobuchar_ionosphere(AtmosphereConfig& a, double scale, double sigma_tecu, double tau_s) noexcept;

/// The world's troposphere equal to what the receiver corrects with
/// (Saastamoinen ZHD and ZWD of the standard atmosphere at RH 0.7, no ZWD
/// process): no tropospheric error.
void use_receiver_troposphere(AtmosphereConfig& a) noexcept;

}  // namespace gnssemu::world

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Carrier phase and Doppler of one satellite signal as a receiver's loops
// measure them: PLL phase jitter and Costas half-cycle slips from C/N0, FLL
// frequency jitter in the Doppler, and the loss of continuity when the path
// switches between LOS and NLOS or the range jumps by more than a code loop
// follows. Pure functions and one small per-satellite state; no allocation.
#include <cmath>
#include <cstdint>

#include "core/common/constants.hpp"
#include "core/common/range.hpp"

namespace gnssemu::world {

/// Half a C/A chip, m: the code loop's pull-in with 1 chip early-late spacing.
inline constexpr double kHalfChip_m = kCaChip_m / 2.0;

/// Where the Doppler noise comes from.
enum class DopplerModel {
  kFixed,  ///< white range-rate noise of errors.doppler_sigma_m_s at every C/N0
  kFll,    ///< frequency-loop jitter at the satellite's C/N0 (fll_range_rate_sigma_m_s)
};

/// The carrier loops of the receiver's front end, as the world applies them
/// to the signal (the receiver's own processing sees only the results).
struct CarrierConfig {
  /// false: no carrier phase (the receiver cannot smooth code with it).
  bool enabled = true;
  DopplerModel doppler_model = DopplerModel::kFll;
  double pll_bandwidth_hz = 10.0;   ///< carrier (Costas PLL) noise bandwidth B_n, Hz (> 0)
  double fll_bandwidth_hz = 2.0;    ///< frequency-loop noise bandwidth for the Doppler, Hz (> 0)
  double integration_s = 0.02;      ///< predetection integration T of both loops, s (> 0; one data bit)
  /// Phase jitter besides thermal noise (oscillator phase noise, vibration),
  /// rad (>= 0); it sets the slip rate of strong signals.
  double oscillator_sigma_rad = 0.1;
  /// Unexplained jump of the range between epochs beyond which the code loop
  /// loses lock, m (> 0).
  double lock_break_m = kHalfChip_m;
};

/// Valid values of CarrierConfig's numbers.
struct CarrierRanges {
  static constexpr Range pll_bandwidth_hz{0.0, 100.0, "Hz", true};
  static constexpr Range fll_bandwidth_hz{0.0, 100.0, "Hz", true};
  static constexpr Range integration_s{0.0, 0.02, "s", true};
  static constexpr Range oscillator_sigma_rad{0.0, 1.0, "rad"};
  static constexpr Range lock_break_m{0.0, 1.0e6, "m", true};
};

/// Throws gnssemu::Error for a value out of its range.
void validate(const CarrierConfig& c);

/// Thermal phase jitter of a Costas PLL, rad, at C/N0 cn0_dbhz (clamped to
/// [0, 70]): sigma^2 = B_n / (C/N0) (1 + 1 / (2 T C/N0)) (Kaplan &
/// Hegarty, Understanding GPS/GNSS, PLL thermal jitter).
double pll_jitter_rad(double cn0_dbhz, double bandwidth_hz, double integration_s) noexcept;

/// 1-sigma range-rate noise of an FLL Doppler, m/s, at C/N0 cn0_dbhz (clamped
/// to [0, 70]): lambda / (2 pi T) sqrt(4 F B_n / (C/N0) (1 + 1 / (T C/N0))),
/// F = 1 at high C/N0 (Kaplan & Hegarty, FLL thermal jitter); lambda the
/// signal's carrier wavelength, m (> 0).
double fll_range_rate_sigma_m_s(double cn0_dbhz, const CarrierConfig& c,
                                double wavelength_m = kL1Wavelength_m) noexcept;

/// Probability of a half-cycle slip of a Costas loop within dt_s (s) at total
/// phase jitter sigma_rad: 1 - exp(-dt / T), T Viterbi's mean time to the first
/// slip of a first-order loop, T = pi^2 rho I0(rho)^2 / (2 B_n) with the
/// Costas loop's rho = 1 / (4 sigma^2) (A. J. Viterbi, Principles of Coherent
/// Communication, 1966; the factor 4 because the discriminator is pi-periodic).
double cycle_slip_probability(double sigma_rad, double bandwidth_hz, double dt_s) noexcept;

/// Amplitude of the reflection the carrier multipath assumes, relative to the
/// direct signal (a single specular reflection).
inline constexpr double kCarrierReflectionAmplitude = 0.2;

/// Carrier-phase multipath of a signal of wavelength_m (m, > 0) whose code
/// sees code_multipath_m (m) from the same reflection: one reflection of
/// relative amplitude a delayed by d = code_multipath_m / a (the code error
/// of a narrow correlator is about a d) shifts the phase by
/// atan2(a sin phi, 1 + a cos phi), phi = 2 pi d / lambda (Braasch, in
/// Parkinson & Spilker, GPS: Theory and Applications I, ch. 14): bounded by
/// asin(a) lambda / (2 pi), so it scales with the wavelength, m.
inline double carrier_multipath_m(double code_multipath_m, double wavelength_m) noexcept {
  constexpr double a = kCarrierReflectionAmplitude;
  const double phi = 2.0 * kPi * code_multipath_m / (a * wavelength_m);
  return std::atan2(a * std::sin(phi), 1.0 + a * std::cos(phi)) * wavelength_m / (2.0 * kPi);
}

/// Continuity of one satellite's carrier as the world keeps it between epochs.
struct CarrierTrack {
  bool continuous = false;      ///< received at the previous epoch
  bool nlos = false;            ///< reflections only at the previous epoch
  double offset_cycles = 0.0;   ///< ambiguity of the current lock plus its slips, cycles
  /// A Costas loop holds the inverted data sign: offset_cycles is half a
  /// cycle off a whole number (new locks and half-cycle slips toggle it).
  bool half_cycle = false;
  std::uint32_t discontinuities = 0;  ///< new locks and slips so far
  double range_m = 0.0;         ///< geometric range at the previous epoch, m
  double range_rate_m_s = 0.0;  ///< its rate, m/s
};

}  // namespace gnssemu::world

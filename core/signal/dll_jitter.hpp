// SPDX-License-Identifier: Apache-2.0
#pragma once
// Code-tracking thermal noise of a delay lock loop.
#include "core/common/constants.hpp"
#include "core/common/range.hpp"

namespace gnssemu::signal {

enum class DllDiscriminator {
  kEarlyMinusLatePower,  ///< noncoherent early-minus-late power
  kDotProduct,           ///< noncoherent dot product
};

struct DllParams {
  double loop_bandwidth_hz = 0.5;   ///< B_L, Hz (> 0); carrier-aided code loops 0.1-2 Hz
  double integration_s = 0.02;      ///< predetection integration T, s (> 0; 1 ms...20 ms)
  double spacing_chips = 0.5;       ///< early-late spacing d, chips (0 < d <= 1)
  double chip_m = kCaChip_m;        ///< chip length, m
  DllDiscriminator discriminator = DllDiscriminator::kEarlyMinusLatePower;
};

/// Valid values of DllParams' fields.
struct DllRanges {
  static constexpr Range loop_bandwidth_hz{0.0, 50.0, "Hz", true};
  static constexpr Range integration_s{0.0, 1.0, "s", true};
  static constexpr Range spacing_chips{0.0, 1.0, "chips", true};
  static constexpr Range chip_m{0.0, 1.0e4, "m", true};  ///< any GNSS code (C/A 293 m, GLONASS 587 m)
};

/// Throws gnssemu::Error for out-of-range parameters.
void validate(const DllParams& p);

/// 1-sigma thermal code jitter, m, for C/N0 in dB-Hz (wide front end; Kaplan &
/// Hegarty, Understanding GPS/GNSS, 3rd ed., §8.8; Van Dierendonck, Fenton,
/// Ford 1992):
///   EMLP: sigma^2 = B_L d / (2 C/N0) [1 + 2 / (T C/N0 (2 - d))] chips^2
///   DP:   sigma^2 = B_L d / (2 C/N0) [1 + 1 / (T C/N0)]           chips^2
/// cn0_dbhz is clamped to [0, 70] (NaN -> 0) so the result is finite.
double dll_thermal_sigma_m(double cn0_dbhz, const DllParams& p) noexcept;

/// C/N0 as a ratio, Hz: 10^(C/N0 / 10) with cn0_dbhz held in [0, 70] dB-Hz
/// (NaN -> 0 dB-Hz), so loop models stay finite.
double cn0_ratio_hz(double cn0_dbhz) noexcept;

}  // namespace gnssemu::signal

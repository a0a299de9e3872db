#pragma once
// Code-tracking thermal noise of a delay lock loop, and the pseudorange
// weight a receiver derives from C/N0 and elevation.
#include "core/common/constants.hpp"
#include "core/common/range.hpp"

namespace gnssemu::signal {

/// GPS L1 C/A chip length c / 1.023 MHz, m.
inline constexpr double kCaChip_m = kSpeedOfLight_m_s / 1.023e6;

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

/// Receiver pseudorange error model used to weight the solution:
///   sigma^2 = a^2 + b^2 / sin^2(el) + c^2 10^(-C/N0 / 10)
/// (elevation term as RTKLIB's; C/N0 term as Kuusniemi et al., GPS
/// Solutions 2004, "sigma^2 = a + b 10^(-C/N0/10)").
struct WeightModel {
  double a_m = 0.3;            ///< constant part, m
  double b_m = 0.3;            ///< elevation part, m
  double c_m_sqrt_hz = 150.0;  ///< C/N0 part, m sqrt(Hz)
  double min_el_rad = 0.0175;  ///< elevation floor for 1 / sin(el), rad (> 0; 1 deg)
};

/// Throws gnssemu::Error for negative or non-finite coefficients.
void validate(const WeightModel& w);

/// Modelled pseudorange 1-sigma, m (> 0 unless all coefficients are 0).
double pseudorange_sigma_m(double cn0_dbhz, double el_rad, const WeightModel& w) noexcept;
/// Least-squares weight 1 / sigma^2, 1/m^2 (0 if sigma is 0).
double pseudorange_weight(double cn0_dbhz, double el_rad, const WeightModel& w) noexcept;

}  // namespace gnssemu::signal

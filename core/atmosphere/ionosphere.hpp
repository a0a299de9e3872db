// SPDX-License-Identifier: Apache-2.0
#pragma once
// World ionosphere: the delay the signal really suffers (the receiver only
// knows its broadcast Klobuchar model). Vertical TEC from a configured value
// or the Klobuchar daily shape scaled by a factor, an obliquity factor, the
// first-order 40.3 TEC / f^2 group delay, and a slow Gauss–Markov perturbation.
#include "core/common/range.hpp"
#include "core/orbit/nav_data.hpp"

namespace gnssemu::atmosphere {

/// Group delay per TEC unit (1 TECU = 1e16 electrons/m^2), m/TECU, at freq_hz:
/// 40.3e16 / f^2 (RTKLIB ionex.c; reference atmosphere.md §1.2). 0.16237 at L1.
double iono_m_per_tecu(double freq_hz) noexcept;

/// Obliquity (slant) factor 1 + 16 (pivot - e)^3 / 180^3 with e and pivot in
/// degrees (Klobuchar's F rewritten in degrees; 16/180^3 = 2.7435e-6).
/// pivot_deg = 95.4 reproduces Klobuchar exactly (0.53 semicircles); the seed's
/// 96 is a rounding of it (reference atmosphere.md §1.3). el_rad clamped to [0, pi/2].
double iono_obliquity_factor(double el_rad, double pivot_deg = 95.4) noexcept;

/// Thin-shell mapping 1 / cos(asin(R / (R + H) cos(el))) (RTKLIB ionmapf),
/// R = earth_radius_m, H = shell_height_m (> 0). el_rad clamped to [0, pi/2].
double iono_thin_shell_mapping(double el_rad, double shell_height_m = 350.0e3,
                               double earth_radius_m = 6371.0e3) noexcept;

enum class VtecSource {
  kFixed,            ///< vtec_tecu everywhere, all day
  kKlobucharShape,   ///< Klobuchar vertical delay (daily cosine) times klobuchar_scale
};

enum class IonoMapping {
  kObliquityFactor,  ///< iono_obliquity_factor(el, obliquity_pivot_deg)
  kThinShell,        ///< iono_thin_shell_mapping(el, shell_height_m)
};

/// First-order Gauss–Markov process parameters.
struct GaussMarkovParams {
  double sigma = 0.0;     ///< steady-state 1-sigma, in the unit of the process (>= 0; 0 disables)
  double tau_s = 1800.0;  ///< correlation time, s (> 0)
};

struct IonosphereConfig {
  bool enabled = true;
  VtecSource source = VtecSource::kKlobucharShape;
  double vtec_tecu = 10.0;          ///< kFixed: vertical TEC, TECU (>= 0)
  double klobuchar_scale = 1.0;     ///< kKlobucharShape: multiplies the Klobuchar VTEC (>= 0)
  orbit::KlobucharParams shape;     ///< kKlobucharShape coefficients; invalid -> RTKLIB defaults
  IonoMapping mapping = IonoMapping::kObliquityFactor;
  double obliquity_pivot_deg = 95.4;  ///< see iono_obliquity_factor; [90, 100]
  double shell_height_m = 350.0e3;    ///< kThinShell: shell height, m (> 0)
  double freq_hz = 1575.42e6;         ///< carrier, Hz (> 0)
  /// Perturbation of the vertical TEC, TECU; per satellite (one process per
  /// line of sight), so the receiver's Klobuchar model misses it.
  GaussMarkovParams perturbation{1.0, 1800.0};
};

/// Valid values of IonosphereConfig's fields (300 TECU is beyond the largest
/// storm-time values observed, ~250).
struct IonosphereRanges {
  static constexpr Range vtec_tecu{0.0, 1000.0, "TECU"};
  static constexpr Range klobuchar_scale{0.0, 20.0, ""};
  static constexpr Range obliquity_pivot_deg{90.0, 100.0, "deg"};
  static constexpr Range shell_height_m{50.0e3, 2000.0e3, "m"};
  static constexpr Range freq_hz{0.0, 1.0e12, "Hz", true};
  static constexpr Range perturbation_sigma_tecu{0.0, 100.0, "TECU"};
  static constexpr Range perturbation_tau_s{0.0, 1.0e6, "s", true};
};

/// Throws gnssemu::Error for a value out of its range or a non-finite
/// Klobuchar coefficient.
void validate(const IonosphereConfig& cfg);

/// Validated world ionosphere. Construction throws gnssemu::Error on bad
/// values (validate);
/// evaluation is noexcept and allocation-free.
class Ionosphere {
public:
  explicit Ionosphere(const IonosphereConfig& cfg);

  const IonosphereConfig& config() const noexcept { return cfg_; }

  /// Vertical TEC without perturbation, TECU (>= 0), at the pierce point of
  /// (az_rad, el_rad) seen from (lat_rad, lon_rad) at GPS time of week tow_s.
  double vtec_tecu(double lat_rad, double lon_rad, double az_rad, double el_rad, double tow_s) const noexcept;

  /// Slant mapping factor used (dimensionless, >= 1).
  double mapping(double el_rad) const noexcept;

  /// Slant code group delay, m (>= 0; 0 when disabled). perturbation_tecu is
  /// added to the vertical TEC (the sum is floored at 0).
  double slant_delay_m(double lat_rad, double lon_rad, double az_rad, double el_rad, double tow_s,
                       double perturbation_tecu = 0.0) const noexcept;

private:
  IonosphereConfig cfg_;
  double m_per_tecu_ = 0.0;
};

/// A first-order Gauss–Markov state, x' = -x / tau + w. The caller supplies
/// the standard-normal draws (e.g. the receiver's counter-based generator),
/// so the process is deterministic for a given sample sequence; no globals.
class GaussMarkov {
public:
  /// Throws gnssemu::Error if sigma < 0, tau_s <= 0 or either is not finite.
  explicit GaussMarkov(const GaussMarkovParams& p);

  /// Stationary start: x = sigma * w0.
  void reset(double w0) noexcept;
  /// Exact discretisation over dt_s: x = phi x + sigma sqrt(1 - phi^2) w,
  /// phi = exp(-dt / tau) (Brown & Hwang, 4th ed., §2.9). dt_s <= 0 holds.
  void step(double dt_s, double w) noexcept;
  double value() const noexcept { return x_; }

private:
  GaussMarkovParams p_;
  double x_ = 0.0;
};

}  // namespace gnssemu::atmosphere

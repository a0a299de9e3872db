// SPDX-License-Identifier: Apache-2.0
#pragma once
// Propagation stage of the world (DESIGN.md §1, step 3): what happens to one
// satellite's signal between the satellite and the antenna. The atmosphere
// fills it; a scene (buildings) adds its own delay / loss / blockage to
// the same PathEffects. Construction validates and may throw; evaluation
// never throws and never allocates.
#include <array>

#include "core/atmosphere/clouds_rain.hpp"
#include "core/atmosphere/ionosphere.hpp"
#include "core/atmosphere/shells.hpp"
#include "core/atmosphere/troposphere.hpp"
#include "core/common/vec3.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/world/measurement/gas_table.hpp"
#include "core/world/world_config.hpp"

namespace gnssemu::world {

/// Effect of the path on one satellite's signal at one epoch.
struct PathEffects {
  double delay_m = 0.0;   ///< extra group delay over the geometric range (iono + tropo + scene), m
  double loss_db = 0.0;   ///< attenuation (gases, clouds, rain, obstruction), dB (>= 0)
  bool received = true;   ///< false: no signal reaches the antenna (blocked)
  double iono_m = 0.0;    ///< ionospheric part of delay_m, m
  double tropo_m = 0.0;   ///< tropospheric part of delay_m, m
};

/// Slowly varying atmospheric terms of one line of sight (what the per-
/// satellite cache stores): index with SlowTerm.
enum SlowTerm : int {
  kIonoM = 0,       ///< slant iono delay without perturbation, m
  kIonoMPerTecu,    ///< slant mapping x m/TECU: delay per TECU of vertical perturbation, m/TECU
  kTropoM,          ///< slant tropo delay without the ZWD perturbation, m
  kNmfWet,          ///< Niell wet mapping factor (for the ZWD perturbation)
  kAttenDb,         ///< gases + clouds + rain, dB
  kSlowTermCount,
};
using SlowTerms = std::array<double, kSlowTermCount>;

/// The world's atmosphere (ionosphere, troposphere, gases over the shells,
/// clouds and rain) built from AtmosphereConfig.
class AtmospherePropagation {
public:
  /// Throws gnssemu::Error on invalid values (via the atmosphere classes).
  explicit AtmospherePropagation(const AtmosphereConfig& cfg);

  /// Klobuchar coefficients for the world's VTEC shape when the ionosphere's
  /// shape was not configured (the broadcast set of the day); invalid -> kept.
  void set_klobuchar_shape(const orbit::KlobucharParams& p);

  bool iono_on() const noexcept { return iono_on_; }
  bool tropo_on() const noexcept { return tropo_on_; }
  bool atten_on() const noexcept { return gases_on_ || clouds_rain_on_; }
  bool any_on() const noexcept { return iono_on_ || tropo_on_ || atten_on(); }

  /// Slow terms seen from rx (geodetic, height above the ellipsoid) along
  /// (az_rad, el_rad) at GPS time of week tow_s and day of year doy. The
  /// gases come from a table over elevation kept for the receiver's height
  /// (GasAttenuationTable); clouds and rain are evaluated every call.
  SlowTerms slow_terms(const Lla& rx, double az_rad, double el_rad, double tow_s, double doy) noexcept;
  /// Quadrature evaluations of the gases so far (benchmarks).
  long gas_evaluations() const noexcept { return gas_table_.evaluations(); }

  const atmosphere::Ionosphere& ionosphere() const noexcept { return iono_; }
  const atmosphere::Troposphere& troposphere() const noexcept { return tropo_; }

private:
  AtmosphereConfig cfg_;
  atmosphere::Ionosphere iono_;
  atmosphere::Troposphere tropo_;
  atmosphere::AtmosphereShells shells_;
  atmosphere::CloudsRain clouds_rain_;
  GasAttenuationTable gas_table_;
  bool iono_on_, tropo_on_, gases_on_, clouds_rain_on_;
};

}  // namespace gnssemu::world

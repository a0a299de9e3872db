// SPDX-License-Identifier: Apache-2.0
#pragma once
// Atmosphere as concentric spherical shells on a spherical Earth: slant path
// length through each shell and the gaseous (oxygen + water vapour)
// attenuation integrated along the slant path.
#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

#include "core/common/range.hpp"
#include "core/common/violation.hpp"

namespace gnssemu::atmosphere {

/// Mean Earth radius R1 (IUGG), m; the spherical Earth of the shell model.
inline constexpr double kMeanEarthRadius_m = 6371008.8;

enum class ShellKind : std::size_t {
  kTroposphere = 0,
  kStratosphere,
  kMesosphere,
  kThermosphere,
  kIonosphere,
};
inline constexpr std::size_t kShellCount = 5;
/// Names of the shells in ShellKind order (config [atmosphere.shells.<name>]).
inline constexpr std::array<std::string_view, kShellCount> kShellNames{"troposphere", "stratosphere", "mesosphere",
                                                                       "thermosphere", "ionosphere"};

/// One shell. Heights above the spherical surface, m.
struct Shell {
  bool enabled = true;
  double bottom_m = 0.0;
  double top_m = 0.0;
  /// Mean temperature of the shell, K (> 0): sets the dry-air scale height
  /// R T / (g M) of the concentration factor exp(-g M (h - bottom) / (R T)).
  double temperature_k = 288.15;
  bool gas_absorption = true;  ///< whether oxygen/water vapour attenuate in this shell
};

/// Surface state driving the gaseous attenuation.
struct GasConfig {
  double freq_hz = 1575.42e6;              ///< carrier, Hz (> 0, < 350 GHz)
  double water_vapour_density_g_m3 = 7.5;  ///< at h = 0 (P.676 reference atmosphere), g/m^3 (>= 0)
  double water_vapour_scale_height_m = 2000.0;  ///< m (> 0); reference §3.1
};

/// Shells in ShellKind order plus the gas state. Defaults (heights above the
/// surface): troposphere 0-12 km, stratosphere 12-50 km, mesosphere 50-85 km,
/// thermosphere 85-600 km (US Standard Atmosphere 1976 layer boundaries,
/// rounded; mid-latitude tropopause 11-12 km), ionosphere 60-1000 km
/// (D region base to the topside; delay purposes only, no gas absorption).
struct ShellsConfig {
  std::array<Shell, kShellCount> shells{{
      {true, 0.0, 12.0e3, 288.15, true},
      {true, 12.0e3, 50.0e3, 240.0, true},
      {true, 50.0e3, 85.0e3, 230.0, true},
      {true, 85.0e3, 600.0e3, 800.0, true},
      {true, 60.0e3, 1000.0e3, 800.0, false},
  }};
  GasConfig gas;
};

/// Path length through the shell [bottom_m, top_m] of a ray leaving a
/// receiver at rx_height_m (above the sphere) with elevation el_rad, m.
/// Closed form on a sphere of radius earth_radius_m; robust at 0 and 90 deg,
/// inside the shell, and above it (0). Negative elevations are followed down
/// to the tangent point and back up; a ray that would meet the surface is
/// treated as grazing it. A shell with bottom <= 0 also contains a receiver
/// below the surface (e.g. -400 m). Never NaN for finite inputs; NaN inputs give 0.
double slant_path_in_shell_m(double rx_height_m, double el_rad, double bottom_m, double top_m,
                             double earth_radius_m = kMeanEarthRadius_m) noexcept;

/// Oxygen specific attenuation at sea level, dB/km, f in GHz (ITU-R P.676
/// old Annex 2 "Mason" form, reference §3.1; 0.227 not the seed's 0.277).
double oxygen_specific_attenuation_db_km(double freq_ghz) noexcept;
/// Water-vapour specific attenuation, dB/km, f in GHz, rho in g/m^3.
double water_vapour_specific_attenuation_db_km(double freq_ghz, double rho_g_m3) noexcept;

/// Per-shell results.
struct ShellAttenuation {
  std::array<double, kShellCount> path_m{};     ///< slant path in each shell, m
  std::array<double, kShellCount> gas_db{};     ///< oxygen + water vapour, dB
  double total_db = 0.0;
};

/// Valid values of Shell's and GasConfig's fields (and top >= bottom).
struct ShellRanges {
  static constexpr Range bottom_m{-1000.0, 5.0e6, "m"};
  static constexpr Range top_m{-1000.0, 5.0e6, "m"};
  static constexpr Range temperature_k{0.0, 5000.0, "K", true};
};
struct GasRanges {
  static constexpr Range freq_hz{0.0, 350.0e9, "Hz", true, true};
  static constexpr Range water_vapour_density_g_m3{0.0, 50.0, "g/m^3"};
  static constexpr Range water_vapour_scale_height_m{0.0, 20000.0, "m", true};
};

/// A shell is not upside down: top_m >= bottom_m.
std::optional<Violation> check_thickness(const Shell& s);
/// The enabled neutral shells stack without overlap (the ionosphere overlaps
/// them by design): an overlap would count the gases of the common heights
/// twice. Names the first overlapping pair, the higher-starting shell first.
std::optional<Violation> check_overlap(const ShellsConfig& cfg);

/// Throws gnssemu::Error for a value out of its range, a shell with negative
/// thickness or overlapping shells.
void validate(const ShellsConfig& cfg);

/// Validated shell model. Construction throws gnssemu::Error on bad values (validate).
class AtmosphereShells {
public:
  explicit AtmosphereShells(const ShellsConfig& cfg);

  const ShellsConfig& config() const noexcept { return cfg_; }

  /// Concentration factor of dry air at height_m relative to the surface
  /// (piecewise isothermal chain of exp(-g M dh / (R T)) through the shells).
  double dry_density_ratio(double height_m) const noexcept;

  /// Gaseous attenuation along the slant path, per shell, dB (>= 0).
  /// rx_height_m: receiver height above the sphere, m; el_rad: elevation.
  /// Composite Gauss–Legendre quadrature over each shell's path; no allocation.
  ShellAttenuation gas_attenuation(double rx_height_m, double el_rad) const noexcept;

private:
  ShellsConfig cfg_;
  double gamma_o_db_m_ = 0.0;   // sea-level oxygen, dB/m
  double gamma_w_db_m_ = 0.0;   // surface water vapour, dB/m
  // Dry shells sorted by bottom for the density chain (troposphere..thermosphere).
  std::array<double, kShellCount> chain_bottom_m_{};
  std::array<double, kShellCount> chain_scale_m_{};
  std::array<double, kShellCount> chain_ratio_{};
  std::size_t chain_n_ = 0;
};

}  // namespace gnssemu::atmosphere

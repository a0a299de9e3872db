// SPDX-License-Identifier: Apache-2.0
#pragma once
// L1 C/A link budget: satellite EIRP, free-space loss, atmospheric losses,
// receive antenna gain versus elevation, thermal noise density, receiver
// noise figure and an environment noise-floor rise -> C/N0 in dB-Hz.
// Reference: shared/reference/atmosphere.md §4.
#include <optional>
#include <string_view>
#include <vector>

#include "core/common/constants.hpp"
#include "core/common/range.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/violation.hpp"

namespace gnssemu::signal {

/// Boltzmann constant, J/K (SI 2019 exact).
inline constexpr double kBoltzmann_j_k = 1.380649e-23;

/// Free-space path loss 20 log10(4 pi d / lambda), dB. range_m > 0, freq_hz > 0.
double free_space_path_loss_db(double range_m, double freq_hz = kL1Freq_hz) noexcept;

/// Thermal noise density 10 log10(k T), dBW/Hz. -203.98 at 290 K.
double thermal_noise_density_dbw_hz(double temperature_k = 290.0) noexcept;

/// Receive antenna pattern: gain in dBic, linear in (1 - sin el) between the
/// zenith and horizon values, then a roll-off below the horizon. A simple
/// stand-in for a ceramic patch (about +3...+5 dBic at zenith, -3...-6 dBic
/// at 5-10 deg on typical datasheets ⚠).
struct AntennaPattern {
  double zenith_gain_dbi = 3.0;    ///< gain at el = 90 deg, dBic
  double horizon_gain_dbi = -5.0;  ///< gain at el = 0, dBic (<= zenith)
  double below_horizon_slope_db_per_deg = 1.0;  ///< extra loss per degree below 0, dB/deg (>= 0)
};

/// Antenna gain at elevation el_rad (clamped to [-pi/2, pi/2]), dBic.
double antenna_gain_dbi(const AntennaPattern& p, double el_rad) noexcept;

/// Environment noise-floor rise presets, dB (see docs/models.md for
/// the mapping from a "countryside 1 dB ... industrial 40 dB" scale).
/// "countryside" 1, "suburban" 3, "urban" 6, "industrial" 20, "jamming" 40.
/// Throws gnssemu::Error naming the known presets for an unknown name.
double environment_noise_rise_db(std::string_view preset);
/// The names environment_noise_rise_db knows, in its order.
std::vector<std::string_view> environment_preset_names();

struct LinkBudgetConfig {
  double eirp_dbw = 26.8;              ///< satellite EIRP, dBW (CBNU 26.25, TN 27)
  double freq_hz = kL1Freq_hz;         ///< carrier of the 3-argument evaluate(), Hz
  double noise_temperature_k = 290.0;  ///< reference noise temperature, K (> 0)
  double noise_figure_db = 2.0;        ///< receiver noise figure, dB (>= 0)
  double environment_noise_rise_db = 1.0;  ///< noise-floor rise from the surroundings, dB (>= 0, <= 60)
  double implementation_loss_db = 0.0;     ///< correlation / quantisation losses, dB (>= 0)
  AntennaPattern antenna;
};

/// Terms of one evaluation, for logging and tests.
struct LinkBudget {
  double fspl_db = 0.0;
  double antenna_gain_dbi = 0.0;
  double received_power_dbw = 0.0;  ///< at the antenna output (before the receiver)
  double noise_density_dbw_hz = 0.0;  ///< thermal + noise figure + environment rise
  double cn0_dbhz = 0.0;
};

/// Valid values of AntennaPattern's fields (and horizon <= zenith).
struct AntennaRanges {
  static constexpr Range zenith_gain_dbi{-30.0, 30.0, "dBic"};
  static constexpr Range horizon_gain_dbi{-40.0, 30.0, "dBic"};
  static constexpr Range below_horizon_slope_db_per_deg{0.0, 10.0, "dB/deg"};
};

/// Valid values of LinkBudgetConfig's fields.
struct LinkBudgetRanges {
  static constexpr Range eirp_dbw{0.0, 60.0, "dBW", true, true};
  static constexpr Range freq_hz{0.0, 1.0e12, "Hz", true};
  static constexpr Range noise_temperature_k{0.0, 5000.0, "K", true};
  static constexpr Range noise_figure_db{0.0, 30.0, "dB"};
  static constexpr Range environment_noise_rise_db{0.0, 60.0, "dB"};
  static constexpr Range implementation_loss_db{0.0, 30.0, "dB"};
};

/// The pattern falls from the zenith: horizon_gain_dbi <= zenith_gain_dbi.
std::optional<Violation> check_gains(const AntennaPattern& a);

/// Throws gnssemu::Error for a value out of its range or horizon gain above
/// zenith gain (check_gains).
void validate(const LinkBudgetConfig& cfg);

/// Validated link budget. Construction throws gnssemu::Error on bad values.
class LinkBudgetModel {
public:
  explicit LinkBudgetModel(const LinkBudgetConfig& cfg);

  const LinkBudgetConfig& config() const noexcept { return cfg_; }

  /// P_rec = EIRP - FSPL(range_m) - losses_db + G(el);
  /// C/N0 = P_rec - (10 log10 kT + NF + rise) - implementation loss, dB-Hz.
  /// range_m: geometric range, m (> 0; clamped to >= 1 m); losses_db: sum of
  /// atmospheric, cloud, rain and obstruction losses along the path, dB (>= 0).
  LinkBudget evaluate(double range_m, double el_rad, double losses_db) const noexcept;

  double cn0_dbhz(double range_m, double el_rad, double losses_db) const noexcept {
    return evaluate(range_m, el_rad, losses_db).cn0_dbhz;
  }

  /// The same for a satellite of system sys on carrier carrier_hz (Hz, > 0):
  /// free-space loss at that carrier, and the system's power and slope
  /// offsets of kSystemSignals added to the received power (GPS: none).
  LinkBudget evaluate(double range_m, double el_rad, double losses_db, GnssSystem sys,
                      double carrier_hz) const noexcept;
  double cn0_dbhz(double range_m, double el_rad, double losses_db, GnssSystem sys, double carrier_hz) const noexcept {
    return evaluate(range_m, el_rad, losses_db, sys, carrier_hz).cn0_dbhz;
  }

private:
  LinkBudgetConfig cfg_;
  double noise_density_dbw_hz_ = 0.0;
};

}  // namespace gnssemu::signal

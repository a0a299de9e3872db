#include "core/signal/link_budget.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"

namespace gnssemu::signal {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("link budget config", 0, what);
}

struct NoisePreset {
  std::string_view name;
  double rise_db;
};
// Engineering defaults ⚠ (no measured climatology at L1); "jamming" keeps the
// literal 40 dB of that scale's industrial end (docs/models.md).
constexpr NoisePreset kNoisePresets[] = {
    {"countryside", 1.0}, {"suburban", 3.0}, {"urban", 6.0}, {"industrial", 20.0}, {"jamming", 40.0},
};

}  // namespace

double free_space_path_loss_db(double range_m, double freq_hz) noexcept {
  const double d = std::isfinite(range_m) ? std::max(range_m, 1.0) : 1.0;
  const double lambda = kSpeedOfLight_m_s / (freq_hz > 0.0 ? freq_hz : kL1Freq_hz);
  return 20.0 * std::log10(4.0 * kPi * d / lambda);
}

double thermal_noise_density_dbw_hz(double temperature_k) noexcept {
  return 10.0 * std::log10(kBoltzmann_j_k * (temperature_k > 0.0 ? temperature_k : 290.0));
}

double antenna_gain_dbi(const AntennaPattern& p, double el_rad) noexcept {
  const double el = std::isfinite(el_rad) ? std::clamp(el_rad, -0.5 * kPi, 0.5 * kPi) : 0.0;
  if (el >= 0.0) return p.zenith_gain_dbi - (p.zenith_gain_dbi - p.horizon_gain_dbi) * (1.0 - std::sin(el));
  return p.horizon_gain_dbi + p.below_horizon_slope_db_per_deg * el * kRadToDeg;
}

double environment_noise_rise_db(std::string_view preset) {
  for (const NoisePreset& p : kNoisePresets)
    if (p.name == preset) return p.rise_db;
  std::string known;
  for (const NoisePreset& p : kNoisePresets) known += (known.empty() ? "" : ", ") + std::string(p.name);
  throw Error("link budget config", 0, "unknown environment noise preset '" + std::string(preset) +
                                           "' (known: " + known + ")");
}

LinkBudgetModel::LinkBudgetModel(const LinkBudgetConfig& cfg) : cfg_(cfg) {
  require(std::isfinite(cfg.eirp_dbw) && cfg.eirp_dbw > 0.0 && cfg.eirp_dbw < 60.0,
          "eirp_dbw must be in (0, 60) dBW, got " + std::to_string(cfg.eirp_dbw));
  require(std::isfinite(cfg.freq_hz) && cfg.freq_hz > 0.0, "freq_hz must be > 0 Hz");
  require(std::isfinite(cfg.noise_temperature_k) && cfg.noise_temperature_k > 0.0,
          "noise_temperature_k must be > 0 K, got " + std::to_string(cfg.noise_temperature_k));
  require(std::isfinite(cfg.noise_figure_db) && cfg.noise_figure_db >= 0.0 && cfg.noise_figure_db <= 30.0,
          "noise_figure_db must be in [0, 30] dB");
  require(std::isfinite(cfg.environment_noise_rise_db) && cfg.environment_noise_rise_db >= 0.0 &&
              cfg.environment_noise_rise_db <= 60.0,
          "environment_noise_rise_db must be in [0, 60] dB, got " + std::to_string(cfg.environment_noise_rise_db));
  require(std::isfinite(cfg.implementation_loss_db) && cfg.implementation_loss_db >= 0.0,
          "implementation_loss_db must be >= 0 dB");
  const AntennaPattern& a = cfg.antenna;
  require(std::isfinite(a.zenith_gain_dbi) && std::isfinite(a.horizon_gain_dbi) &&
              a.horizon_gain_dbi <= a.zenith_gain_dbi,
          "antenna: horizon gain must be finite and <= zenith gain");
  require(std::isfinite(a.below_horizon_slope_db_per_deg) && a.below_horizon_slope_db_per_deg >= 0.0,
          "antenna: below_horizon_slope_db_per_deg must be >= 0");
  noise_density_dbw_hz_ =
      thermal_noise_density_dbw_hz(cfg.noise_temperature_k) + cfg.noise_figure_db + cfg.environment_noise_rise_db;
}

LinkBudget LinkBudgetModel::evaluate(double range_m, double el_rad, double losses_db) const noexcept {
  LinkBudget b;
  b.fspl_db = free_space_path_loss_db(range_m, cfg_.freq_hz);
  b.antenna_gain_dbi = antenna_gain_dbi(cfg_.antenna, el_rad);
  const double loss = std::isnan(losses_db) ? 0.0 : std::clamp(losses_db, 0.0, 300.0);  // +inf = blocked
  b.received_power_dbw = cfg_.eirp_dbw - b.fspl_db - loss + b.antenna_gain_dbi;
  b.noise_density_dbw_hz = noise_density_dbw_hz_;
  b.cn0_dbhz = b.received_power_dbw - noise_density_dbw_hz_ - cfg_.implementation_loss_db;
  return b;
}

}  // namespace gnssemu::signal

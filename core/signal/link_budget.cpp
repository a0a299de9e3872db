// SPDX-License-Identifier: Apache-2.0
#include "core/signal/link_budget.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/signal/system_signal.hpp"

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

std::optional<Violation> check_gains(const AntennaPattern& a) {
  if (!(a.horizon_gain_dbi > a.zenith_gain_dbi)) return std::nullopt;
  return Violation{"horizon_gain_dbi", "zenith_gain_dbi",
                   "horizon_gain_dbi " + format_number(a.horizon_gain_dbi) + " exceeds zenith_gain_dbi " +
                       format_number(a.zenith_gain_dbi)};
}

std::vector<std::string_view> environment_preset_names() {
  std::vector<std::string_view> out;
  for (const NoisePreset& p : kNoisePresets) out.push_back(p.name);
  return out;
}

void validate(const LinkBudgetConfig& cfg) {
  using L = LinkBudgetRanges;
  using A = AntennaRanges;
  const AntennaPattern& a = cfg.antenna;
  check_ranges("link budget config",
               {{cfg.eirp_dbw, L::eirp_dbw, "eirp_dbw"}, {cfg.freq_hz, L::freq_hz, "freq_hz"},
                {cfg.noise_temperature_k, L::noise_temperature_k, "noise_temperature_k"},
                {cfg.noise_figure_db, L::noise_figure_db, "noise_figure_db"},
                {cfg.environment_noise_rise_db, L::environment_noise_rise_db, "environment_noise_rise_db"},
                {cfg.implementation_loss_db, L::implementation_loss_db, "implementation_loss_db"},
                {a.zenith_gain_dbi, A::zenith_gain_dbi, "antenna.zenith_gain_dbi"},
                {a.horizon_gain_dbi, A::horizon_gain_dbi, "antenna.horizon_gain_dbi"},
                {a.below_horizon_slope_db_per_deg, A::below_horizon_slope_db_per_deg,
                 "antenna.below_horizon_slope_db_per_deg"}});
  require(!check_gains(a), "antenna: horizon gain must be <= zenith gain");
}

LinkBudgetModel::LinkBudgetModel(const LinkBudgetConfig& cfg) : cfg_(cfg) {
  validate(cfg);
  noise_density_dbw_hz_ =
      thermal_noise_density_dbw_hz(cfg.noise_temperature_k) + cfg.noise_figure_db + cfg.environment_noise_rise_db;
}

LinkBudget LinkBudgetModel::evaluate(double range_m, double el_rad, double losses_db) const noexcept {
  return evaluate(range_m, el_rad, losses_db, GnssSystem::kGps, cfg_.freq_hz);
}

LinkBudget LinkBudgetModel::evaluate(double range_m, double el_rad, double losses_db, GnssSystem sys,
                                     double carrier_hz) const noexcept {
  LinkBudget b;
  b.fspl_db = free_space_path_loss_db(range_m, carrier_hz);
  b.antenna_gain_dbi = antenna_gain_dbi(cfg_.antenna, el_rad);
  const double loss = std::isnan(losses_db) ? 0.0 : std::clamp(losses_db, 0.0, 300.0);  // +inf = blocked
  b.received_power_dbw = cfg_.eirp_dbw - b.fspl_db - loss + b.antenna_gain_dbi;
  const SystemSignal& ss = system_signal(sys);
  if (ss.power_offset_db != 0.0 || ss.slope_offset_db != 0.0) {
    const double el = std::isfinite(el_rad) ? std::clamp(el_rad, 0.0, 0.5 * kPi) : 0.0;
    b.received_power_dbw += ss.power_offset_db + ss.slope_offset_db * (1.0 - std::sin(el));
  }
  b.noise_density_dbw_hz = noise_density_dbw_hz_;
  b.cn0_dbhz = b.received_power_dbw - noise_density_dbw_hz_ - cfg_.implementation_loss_db;
  return b;
}

}  // namespace gnssemu::signal

// SPDX-License-Identifier: Apache-2.0
// [signal] and its sub-tables: link budget, C/N0, tracking thresholds, the
// DLL. Ranges and cross-field rules: the core signal models'.
#include "config/keys/config_keys.hpp"

namespace gnssemu::config::detail {

namespace {

using signal::AntennaPattern;
using signal::DllParams;
using signal::LinkBudgetConfig;
using signal::TrackingThresholds;
using world::SignalConfig;
using world::WorldConfig;

constexpr Choice<signal::DllDiscriminator> kDiscriminators[] = {
    {"early_minus_late_power", signal::DllDiscriminator::kEarlyMinusLatePower},
    {"dot_product", signal::DllDiscriminator::kDotProduct}};

using Ar = signal::AntennaRanges;
constexpr Field<AntennaPattern> kAntennaFields[] = {
    number<&AntennaPattern::zenith_gain_dbi>("zenith_gain_dbi", Ar::zenith_gain_dbi, "gain at the zenith"),
    number<&AntennaPattern::horizon_gain_dbi>("horizon_gain_dbi", Ar::horizon_gain_dbi,
                                              "gain at the horizon, ≤ `zenith_gain_dbi`; linear in (1 − sin el) "
                                              "between the two"),
    rule<AntennaPattern, signal::check_gains>(),
    number<&AntennaPattern::below_horizon_slope_db_per_deg>("below_horizon_slope_db_per_deg",
                                                            Ar::below_horizon_slope_db_per_deg,
                                                            "extra loss per degree below the horizon"),
};
constexpr Section<AntennaPattern> kAntenna{kAntennaFields};

using Dr = signal::DllRanges;
constexpr Field<DllParams> kDllFields[] = {
    number<&DllParams::loop_bandwidth_hz>("loop_bandwidth_hz", Dr::loop_bandwidth_hz, "code loop bandwidth B_L"),
    number<&DllParams::integration_s>("integration_s", Dr::integration_s, "coherent integration time"),
    number<&DllParams::spacing_chips>("spacing_chips", Dr::spacing_chips, "early-late correlator spacing"),
    choice<kDiscriminators, &DllParams::discriminator>("discriminator", "noncoherent discriminator"),
};
constexpr Section<DllParams> kDll{kDllFields};

constexpr Choice<world::DopplerModel> kDopplerModels[] = {{"fll", world::DopplerModel::kFll},
                                                          {"fixed", world::DopplerModel::kFixed}};
using Cr = world::CarrierRanges;
constexpr Field<world::CarrierConfig> kCarrierFields[] = {
    boolean<&world::CarrierConfig::enabled>("enabled", "false: no carrier phase (nothing to smooth code with)"),
    either<kDopplerModels, &world::CarrierConfig::doppler_model>(
        "doppler_model", "Doppler noise: the FLL's jitter at each satellite's C/N0, or the white "
                         "`receiver.errors.doppler_sigma_m_s`"),
    number<&world::CarrierConfig::pll_bandwidth_hz>("pll_bandwidth_hz", Cr::pll_bandwidth_hz,
                                                    "Costas PLL noise bandwidth: phase jitter and cycle slips"),
    number<&world::CarrierConfig::fll_bandwidth_hz>("fll_bandwidth_hz", Cr::fll_bandwidth_hz,
                                                    "frequency loop noise bandwidth: Doppler jitter"),
    number<&world::CarrierConfig::integration_s>("integration_s", Cr::integration_s,
                                                 "predetection integration of both loops (one data bit at most)"),
    number<&world::CarrierConfig::oscillator_sigma_rad>(
        "oscillator_sigma_rad", Cr::oscillator_sigma_rad,
        "phase jitter besides thermal noise (oscillator, vibration): the slip rate of strong signals"),
    number<&world::CarrierConfig::lock_break_m>(
        "lock_break_m", Cr::lock_break_m,
        "a range jump between epochs beyond what its rate explains breaks lock (half a C/A chip)"),
};
constexpr Section<world::CarrierConfig> kCarrier{kCarrierFields};

// A preset for noise_rise_db, which may not be given as well.
void read_environment(TableReader& t, const Field<Config>& f, Config& c) {
  const toml::node* env = t.find(f.key);
  const toml::node* rise = t.find("noise_rise_db");
  if (env != nullptr && rise != nullptr) {
    t.fail(*rise, t.full_name("noise_rise_db") + ": give either environment or noise_rise_db, not both");
  }
  if (env == nullptr) return;
  const std::string name = t.string(f.key, std::nullopt);
  try {
    c.world.signal.link.environment_noise_rise_db = signal::environment_noise_rise_db(name);
  } catch (const Error& e) {
    t.fail(*env, t.full_name(f.key) + ": " + reason_of(e));
  }
}

// The presets with their rise: `"urban"` 6 dB.
std::string environment_names() {
  std::string names;
  for (const std::string_view n : signal::environment_preset_names()) {
    names += (names.empty() ? "`\"" : ", `\"") + std::string(n) + "\"` " +
             format_number(signal::environment_noise_rise_db(n)) + " dB";
  }
  return names;
}

using Lr = signal::LinkBudgetRanges;
using Tr = signal::TrackingRanges;
constexpr Field<Config> kSignalFields[] = {
    boolean<&Config::world, &WorldConfig::signal, &SignalConfig::enabled>(
        "enabled", "false: no link budget; C/N0 from `receiver.nominal_cn0_dbhz`, every satellite above the mask "
                   "tracked"),
    custom<Config>("environment", "", environment_names,
                   "noise-floor rise preset for `noise_rise_db` (not together with it); written as `noise_rise_db`",
                   read_environment, nullptr)
        .default_doc("none"),
    number<&Config::world, &WorldConfig::signal, &SignalConfig::link, &LinkBudgetConfig::environment_noise_rise_db>(
        "noise_rise_db", Lr::environment_noise_rise_db, "environment noise-floor rise ΔN (C/N0 falls 1:1)")
        .with_note("environment noise floor rise"),
    number<&Config::world, &WorldConfig::signal, &SignalConfig::link, &LinkBudgetConfig::eirp_dbw>(
        "eirp_dbw", Lr::eirp_dbw, "satellite EIRP"),
    number<&Config::world, &WorldConfig::signal, &SignalConfig::link, &LinkBudgetConfig::noise_figure_db>(
        "noise_figure_db", Lr::noise_figure_db, "receiver noise figure"),
    number<&Config::world, &WorldConfig::signal, &SignalConfig::link, &LinkBudgetConfig::noise_temperature_k>(
        "noise_temperature_k", Lr::noise_temperature_k, "reference noise temperature"),
    number<&Config::world, &WorldConfig::signal, &SignalConfig::link, &LinkBudgetConfig::implementation_loss_db>(
        "implementation_loss_db", Lr::implementation_loss_db, "correlation / quantisation losses"),
    number<&Config::receiver, &receiver::ReceiverConfig::tracking, &TrackingThresholds::acquire_dbhz>(
        "acquire_dbhz", Tr::acquire_dbhz, "C/N0 to acquire"),
    number<&Config::receiver, &receiver::ReceiverConfig::tracking, &TrackingThresholds::lose_dbhz>(
        "lose_dbhz", Tr::lose_dbhz, "below this, lock is lost (hysteresis), ≤ `acquire_dbhz`"),
    rule<Config, signal::check_hysteresis, RuleScope::kTable, &Config::receiver, &receiver::ReceiverConfig::tracking>(),
    table<kAntenna, &Config::world, &WorldConfig::signal, &SignalConfig::link, &LinkBudgetConfig::antenna>("antenna"),
    table<kDll, &Config::world, &WorldConfig::signal, &SignalConfig::dll>(
        "dll", "code tracking loop (thermal noise when receiver.errors.thermal_model = \"dll\")"),
    table<kCarrier, &Config::world, &WorldConfig::carrier>("carrier", "carrier loops: phase, Doppler, slips"),
};

}  // namespace

constexpr Section<Config> kSignalKeys{kSignalFields};

}  // namespace gnssemu::config::detail

// [atmosphere], [signal], [receiver.corrections]. Schema: docs/configuration.md.
#include "config/config_atmosphere.hpp"

#include <array>
#include <limits>
#include <string_view>
#include <utility>

#include "core/atmosphere/clouds_rain.hpp"
#include "core/common/error.hpp"
#include "core/world/propagation.hpp"
#include "core/signal/link_budget.hpp"

namespace gnssemu::config::detail {

namespace {

using atmosphere::CacheMode;
using atmosphere::IonoCorrection;
using atmosphere::IonoMapping;
using atmosphere::TropoCorrection;
using atmosphere::VtecSource;
using atmosphere::ZhdModel;
using atmosphere::ZwdModel;

template <class E>
struct Choice {
  std::string_view name;
  E value;
};

constexpr std::array<Choice<IonoCorrection>, 2> kIonoCorrections{{{"klobuchar", IonoCorrection::kKlobuchar},
                                                                   {"none", IonoCorrection::kNone}}};
constexpr std::array<Choice<TropoCorrection>, 4> kTropoCorrections{
    {{"saastamoinen", TropoCorrection::kSaastamoinenNiell},
     {"zhd_niell", TropoCorrection::kZhdNiell},
     {"saastamoinen_cosz", TropoCorrection::kSaastamoinenCosZ},
     {"none", TropoCorrection::kNone}}};
constexpr std::array<Choice<CacheMode>, 2> kCacheModes{{{"hold", CacheMode::kHold}, {"linear", CacheMode::kLinear}}};
constexpr std::array<Choice<VtecSource>, 2> kVtecSources{
    {{"klobuchar", VtecSource::kKlobucharShape}, {"fixed", VtecSource::kFixed}}};
constexpr std::array<Choice<IonoMapping>, 2> kIonoMappings{
    {{"obliquity", IonoMapping::kObliquityFactor}, {"thin_shell", IonoMapping::kThinShell}}};
constexpr std::array<Choice<ZhdModel>, 2> kZhdModels{
    {{"exponential", ZhdModel::kExponential}, {"saastamoinen", ZhdModel::kSaastamoinen}}};
constexpr std::array<Choice<ZwdModel>, 2> kZwdModels{
    {{"fixed", ZwdModel::kFixed}, {"saastamoinen", ZwdModel::kSaastamoinen}}};
constexpr std::array<Choice<world::ThermalModel>, 2> kThermalModels{
    {{"dll", world::ThermalModel::kDll}, {"fixed", world::ThermalModel::kFixed}}};
constexpr std::array<Choice<signal::DllDiscriminator>, 2> kDiscriminators{
    {{"early_minus_late_power", signal::DllDiscriminator::kEarlyMinusLatePower},
     {"dot_product", signal::DllDiscriminator::kDotProduct}}};
constexpr std::array<std::string_view, atmosphere::kShellCount> kShellNames{
    "troposphere", "stratosphere", "mesosphere", "thermosphere", "ionosphere"};

template <class E, std::size_t N>
E choice(TableReader& t, std::string_view key, const std::array<Choice<E>, N>& choices, E def) {
  const toml::node* n = t.find(key);
  if (n == nullptr) return def;
  const std::string v = t.string(key, std::nullopt);
  std::string known;
  for (const Choice<E>& c : choices) {
    if (c.name == v) return c.value;
    known += (known.empty() ? "\"" : ", \"") + std::string(c.name) + "\"";
  }
  t.fail(*n, t.full_name(key) + ": '" + v + "' is not one of " + known);
}

template <class E, std::size_t N>
std::string name_of(E value, const std::array<Choice<E>, N>& choices) {
  for (const Choice<E>& c : choices)
    if (c.value == value) return std::string(c.name);
  return std::string(choices[0].name);
}

std::string quoted(std::string_view s) { return "\"" + std::string(s) + "\""; }

void read_ionosphere(TableReader& t, atmosphere::IonosphereConfig& c) {
  using R = atmosphere::IonosphereRanges;
  c.enabled = t.boolean("enabled", c.enabled);
  c.source = choice(t, "vtec_source", kVtecSources, c.source);
  c.vtec_tecu = t.number("vtec_tecu", c.vtec_tecu, R::vtec_tecu);
  c.klobuchar_scale = t.number("klobuchar_scale", c.klobuchar_scale, R::klobuchar_scale);
  c.mapping = choice(t, "mapping", kIonoMappings, c.mapping);
  c.obliquity_pivot_deg = t.number("obliquity_pivot_deg", c.obliquity_pivot_deg, R::obliquity_pivot_deg);
  c.shell_height_m = t.number("shell_height_m", c.shell_height_m, R::shell_height_m);
  if (auto p = t.table("perturbation", false)) {
    world::GaussMarkovConfig gm{c.perturbation.sigma, c.perturbation.tau_s};
    read_gauss_markov(*p, gm, "sigma_tecu", R::perturbation_sigma_tecu, R::perturbation_tau_s);
    c.perturbation = {gm.sigma_m, gm.tau_s};
  }
  t.finish();
}

void read_troposphere(TableReader& t, world::AtmosphereConfig& a) {
  using R = atmosphere::TroposphereRanges;
  atmosphere::TroposphereConfig& c = a.troposphere;
  c.enabled = t.boolean("enabled", c.enabled);
  c.zhd_model = choice(t, "zhd_model", kZhdModels, c.zhd_model);
  c.zhd_a_m = t.number("zhd_a_m", c.zhd_a_m, R::zhd_a_m);
  c.zhd_b_per_m = t.number("zhd_b_per_m", c.zhd_b_per_m, R::zhd_b_per_m);
  c.zwd_model = choice(t, "zwd_model", kZwdModels, c.zwd_model);
  c.zwd_m = t.number("zwd_m", c.zwd_m, R::zwd_m);
  c.zwd_scale_height_m = t.number("zwd_scale_height_m", c.zwd_scale_height_m, R::zwd_scale_height_m);
  c.rel_humidity = t.number("rel_humidity", c.rel_humidity, R::rel_humidity);
  if (auto p = t.table("zwd_perturbation", false)) {
    read_gauss_markov(*p, a.zwd_perturbation, "sigma_m", world::AtmosphereRanges::zwd_perturbation_sigma_m,
                      world::AtmosphereRanges::zwd_perturbation_tau_s);
  }
  t.finish();
}

void read_shells(TableReader& t, atmosphere::ShellsConfig& c) {
  for (std::size_t i = 0; i < atmosphere::kShellCount; ++i) {
    auto s = t.table(kShellNames[i], false);
    if (!s) continue;
    atmosphere::Shell& sh = c.shells[i];
    sh.enabled = s->boolean("enabled", sh.enabled);
    sh.bottom_m = s->number("bottom_m", sh.bottom_m, atmosphere::ShellRanges::bottom_m);
    sh.top_m = s->number("top_m", sh.top_m, atmosphere::ShellRanges::top_m);
    if (sh.top_m < sh.bottom_m) {
      const toml::node* n = s->find("top_m");
      if (n == nullptr) n = s->find("bottom_m");
      s->fail(*n, s->path() + ": negative thickness (top_m " + format_number(sh.top_m) + " m < bottom_m " +
                      format_number(sh.bottom_m) + " m)");
    }
    sh.temperature_k = s->number("temperature_k", sh.temperature_k, atmosphere::ShellRanges::temperature_k);
    sh.gas_absorption = s->boolean("gas_absorption", sh.gas_absorption);
    s->finish();
  }
  // The neutral shells stack (the ionosphere overlaps them by design): an
  // overlap would count the gases of the common heights twice.
  const auto neutral = [](std::size_t i) { return static_cast<atmosphere::ShellKind>(i) != atmosphere::ShellKind::kIonosphere; };
  for (std::size_t i = 0; i < atmosphere::kShellCount; ++i) {
    for (std::size_t j = 0; j < atmosphere::kShellCount; ++j) {
      const atmosphere::Shell& a = c.shells[i];
      const atmosphere::Shell& b = c.shells[j];
      if (i == j || !neutral(i) || !neutral(j) || !a.enabled || !b.enabled) continue;
      if (!(a.bottom_m <= b.bottom_m && b.bottom_m < a.top_m && b.top_m > b.bottom_m)) continue;
      const toml::node* n = t.find(kShellNames[j]);
      if (n == nullptr) n = t.find(kShellNames[i]);
      if (n == nullptr) continue;  // the defaults do not overlap
      t.fail(*n, t.path() + ": " + std::string(kShellNames[i]) + " (" + format_number(a.bottom_m) + "-" +
                     format_number(a.top_m) + " m) and " + std::string(kShellNames[j]) + " (" +
                     format_number(b.bottom_m) + "-" + format_number(b.top_m) + " m) overlap");
    }
  }
  t.finish();
}

atmosphere::CloudLayer read_cloud(TableReader& t) {
  atmosphere::CloudLayer l;
  if (const toml::node* n = t.find("preset")) {
    const std::string name = t.string("preset", std::nullopt);
    try {
      l = atmosphere::cloud_preset(name);
    } catch (const Error& e) {
      t.fail(*n, t.full_name("preset") + ": " + reason_of(e));
    }
  } else if (t.find("thickness_m") == nullptr || t.find("liquid_water_g_m3") == nullptr) {
    t.fail_missing(t.find("thickness_m") == nullptr ? "thickness_m" : "liquid_water_g_m3",
                   "key (or a preset)");
  }
  using R = atmosphere::CloudLayerRanges;
  l.base_m = t.number("base_m", l.base_m, R::base_m);
  if (const toml::node* n = t.find("thickness_m")) {
    // A negative thickness gets its own message before the range's.
    constexpr double kBig = std::numeric_limits<double>::max();
    const double v = t.number("thickness_m", std::nullopt, Range{-kBig, kBig, R::thickness_m.unit});
    if (v < 0.0) t.fail(*n, t.full_name("thickness_m") + ": negative thickness " + format_number(v) + " m");
    l.thickness_m = t.number("thickness_m", std::nullopt, R::thickness_m);
  }
  l.liquid_water_g_m3 = t.number("liquid_water_g_m3", l.liquid_water_g_m3, R::liquid_water_g_m3);
  l.temperature_k = t.number("temperature_k", l.temperature_k, R::temperature_k);
  t.finish();
  return l;
}

}  // namespace

void read_thermal_model(TableReader& errors, world::ErrorModelConfig& e) {
  e.thermal_model = choice(errors, "thermal_model", kThermalModels, e.thermal_model);
}

void read_gauss_markov(TableReader& t, world::GaussMarkovConfig& gm, std::string_view sigma_key,
                       const gnssemu::Range& sigma, const gnssemu::Range& tau) {
  gm.sigma_m = t.number(sigma_key, gm.sigma_m, sigma);
  gm.tau_s = t.number("tau_s", gm.tau_s, tau);
  t.finish();
}

std::string reason_of(const Error& e) {
  const std::string w = e.what();
  if (e.file().empty()) return w;
  const std::size_t p = w.find(": ", e.file().size());
  return p == std::string::npos ? w : w.substr(p + 2);
}

void read_corrections(TableReader& t, receiver::SolverConfig& s) {
  s.iono = choice(t, "ionosphere", kIonoCorrections, s.iono);
  s.tropo = choice(t, "troposphere", kTropoCorrections, s.tropo);
  t.finish();
}

void read_atmosphere(TableReader& t, world::WorldConfig& w) {
  world::AtmosphereConfig& a = w.atmosphere;
  a.cache_refresh_s = t.number("cache_refresh_s", a.cache_refresh_s, world::AtmosphereRanges::cache_refresh_s);
  a.cache_mode = choice(t, "cache_mode", kCacheModes, a.cache_mode);
  a.gases = t.boolean("gases", a.gases);
  atmosphere::GasConfig& gas = a.shells.gas;
  gas.water_vapour_density_g_m3 = t.number("water_vapour_density_g_m3", gas.water_vapour_density_g_m3,
                                           atmosphere::GasRanges::water_vapour_density_g_m3);
  gas.water_vapour_scale_height_m = t.number("water_vapour_scale_height_m", gas.water_vapour_scale_height_m,
                                             atmosphere::GasRanges::water_vapour_scale_height_m);
  if (auto s = t.table("ionosphere", false)) read_ionosphere(*s, a.ionosphere);
  if (auto s = t.table("troposphere", false)) read_troposphere(*s, a);
  if (auto s = t.table("shells", false)) read_shells(*s, a.shells);
  std::vector<TableReader> clouds = t.table_array("clouds");
  if (clouds.size() > atmosphere::kMaxCloudLayers) {
    clouds[atmosphere::kMaxCloudLayers].fail(*t.find("clouds"),
                                             "atmosphere.clouds: at most " +
                                                 std::to_string(atmosphere::kMaxCloudLayers) + " layers, got " +
                                                 std::to_string(clouds.size()));
  }
  a.clouds_rain.layer_count = clouds.size();
  for (std::size_t i = 0; i < clouds.size(); ++i) a.clouds_rain.layers[i] = read_cloud(clouds[i]);
  if (auto s = t.table("rain", false)) {
    using R = atmosphere::RainRanges;
    atmosphere::RainConfig& rain = a.clouds_rain.rain;
    rain.rate_mm_h = s->number("rate_mm_h", rain.rate_mm_h, R::rate_mm_h);
    rain.rain_height_m = s->number("rain_height_m", rain.rain_height_m, R::rain_height_m);
    rain.k = s->number("k", rain.k, R::k);
    rain.alpha = s->number("alpha", rain.alpha, R::alpha);
    s->finish();
  }
  t.finish();
}

void read_signal(TableReader& t, world::WorldConfig& w, receiver::ReceiverConfig& r) {
  world::SignalConfig& s = w.signal;
  signal::TrackingThresholds& tracking = r.tracking;
  signal::LinkBudgetConfig& l = s.link;
  s.enabled = t.boolean("enabled", s.enabled);
  const toml::node* env = t.find("environment");
  const toml::node* rise = t.find("noise_rise_db");
  if (env != nullptr && rise != nullptr) {
    t.fail(*rise, t.full_name("noise_rise_db") + ": give either environment or noise_rise_db, not both");
  }
  if (env != nullptr) {
    const std::string name = t.string("environment", std::nullopt);
    try {
      l.environment_noise_rise_db = signal::environment_noise_rise_db(name);
    } catch (const Error& e) {
      t.fail(*env, t.full_name("environment") + ": " + reason_of(e));
    }
  }
  using L = signal::LinkBudgetRanges;
  l.environment_noise_rise_db = t.number("noise_rise_db", l.environment_noise_rise_db, L::environment_noise_rise_db);
  l.eirp_dbw = t.number("eirp_dbw", l.eirp_dbw, L::eirp_dbw);
  l.noise_figure_db = t.number("noise_figure_db", l.noise_figure_db, L::noise_figure_db);
  l.noise_temperature_k = t.number("noise_temperature_k", l.noise_temperature_k, L::noise_temperature_k);
  l.implementation_loss_db = t.number("implementation_loss_db", l.implementation_loss_db, L::implementation_loss_db);
  tracking.acquire_dbhz = t.number("acquire_dbhz", tracking.acquire_dbhz, signal::TrackingRanges::acquire_dbhz);
  tracking.lose_dbhz = t.number("lose_dbhz", tracking.lose_dbhz, signal::TrackingRanges::lose_dbhz);
  if (tracking.lose_dbhz > tracking.acquire_dbhz) {
    const toml::node* n = t.find("lose_dbhz");
    if (n == nullptr) n = t.find("acquire_dbhz");
    t.fail(*n, t.path() + ": lose_dbhz " + format_number(tracking.lose_dbhz) + " exceeds acquire_dbhz " +
                   format_number(tracking.acquire_dbhz) + " (hysteresis needs lose <= acquire)");
  }
  if (auto a = t.table("antenna", false)) {
    using A = signal::AntennaRanges;
    signal::AntennaPattern& p = l.antenna;
    p.zenith_gain_dbi = a->number("zenith_gain_dbi", p.zenith_gain_dbi, A::zenith_gain_dbi);
    p.horizon_gain_dbi = a->number("horizon_gain_dbi", p.horizon_gain_dbi, A::horizon_gain_dbi);
    if (p.horizon_gain_dbi > p.zenith_gain_dbi) {
      const toml::node* n = a->find("horizon_gain_dbi");
      if (n == nullptr) n = a->find("zenith_gain_dbi");
      a->fail(*n, a->path() + ": horizon_gain_dbi " + format_number(p.horizon_gain_dbi) +
                      " exceeds zenith_gain_dbi " + format_number(p.zenith_gain_dbi));
    }
    p.below_horizon_slope_db_per_deg =
        a->number("below_horizon_slope_db_per_deg", p.below_horizon_slope_db_per_deg, A::below_horizon_slope_db_per_deg);
    a->finish();
  }
  if (auto d = t.table("dll", false)) {
    using D = signal::DllRanges;
    signal::DllParams& p = s.dll;
    p.loop_bandwidth_hz = d->number("loop_bandwidth_hz", p.loop_bandwidth_hz, D::loop_bandwidth_hz);
    p.integration_s = d->number("integration_s", p.integration_s, D::integration_s);
    p.spacing_chips = d->number("spacing_chips", p.spacing_chips, D::spacing_chips);
    p.discriminator = choice(*d, "discriminator", kDiscriminators, p.discriminator);
    d->finish();
  }
  t.finish();
}

void check_models(const TableReader& at, const world::WorldConfig& w, const receiver::ReceiverConfig& r) {
  validate_at(at, [&] {
    world::validate(w);
    receiver::validate(r);
  });
}

std::string thermal_model_name(world::ThermalModel m) { return name_of(m, kThermalModels); }

std::string corrections_toml(const receiver::SolverConfig& s, std::string (*)(double)) {
  std::string o = "\n[receiver.corrections]  # what the receiver subtracts (broadcast models)\n";
  o += "ionosphere = " + quoted(name_of(s.iono, kIonoCorrections)) + "\n";
  o += "troposphere = " + quoted(name_of(s.tropo, kTropoCorrections)) + "\n";
  return o;
}

std::string atmosphere_toml(const world::WorldConfig& w, std::string (*number)(double)) {
  const world::AtmosphereConfig& a = w.atmosphere;
  const auto b = [](bool v) { return std::string(v ? "true" : "false"); };
  std::string o = "\n[atmosphere]  # what the world does to the signal\n";
  o += "cache_refresh_s = " + number(a.cache_refresh_s) + "\n";
  o += "cache_mode = " + quoted(name_of(a.cache_mode, kCacheModes)) + "\n";
  o += "gases = " + b(a.gases) + "\n";
  o += "water_vapour_density_g_m3 = " + number(a.shells.gas.water_vapour_density_g_m3) + "\n";
  o += "water_vapour_scale_height_m = " + number(a.shells.gas.water_vapour_scale_height_m) + "\n";
  const atmosphere::IonosphereConfig& i = a.ionosphere;
  o += "\n[atmosphere.ionosphere]\n";
  o += "enabled = " + b(i.enabled) + "\n";
  o += "vtec_source = " + quoted(name_of(i.source, kVtecSources)) + "\n";
  o += "vtec_tecu = " + number(i.vtec_tecu) + "\n";
  o += "klobuchar_scale = " + number(i.klobuchar_scale) + "\n";
  o += "mapping = " + quoted(name_of(i.mapping, kIonoMappings)) + "\n";
  o += "obliquity_pivot_deg = " + number(i.obliquity_pivot_deg) + "\n";
  o += "shell_height_m = " + number(i.shell_height_m) + "\n";
  o += "\n[atmosphere.ionosphere.perturbation]  # first-order Gauss-Markov on the vertical TEC\n";
  o += "sigma_tecu = " + number(i.perturbation.sigma) + "\n";
  o += "tau_s = " + number(i.perturbation.tau_s) + "\n";
  const atmosphere::TroposphereConfig& tr = a.troposphere;
  o += "\n[atmosphere.troposphere]\n";
  o += "enabled = " + b(tr.enabled) + "\n";
  o += "zhd_model = " + quoted(name_of(tr.zhd_model, kZhdModels)) + "\n";
  o += "zhd_a_m = " + number(tr.zhd_a_m) + "\n";
  o += "zhd_b_per_m = " + number(tr.zhd_b_per_m) + "\n";
  o += "zwd_model = " + quoted(name_of(tr.zwd_model, kZwdModels)) + "\n";
  o += "zwd_m = " + number(tr.zwd_m) + "\n";
  o += "zwd_scale_height_m = " + number(tr.zwd_scale_height_m) + "\n";
  o += "rel_humidity = " + number(tr.rel_humidity) + "\n";
  o += "\n[atmosphere.troposphere.zwd_perturbation]  # first-order Gauss-Markov\n";
  o += "sigma_m = " + number(a.zwd_perturbation.sigma_m) + "\n";
  o += "tau_s = " + number(a.zwd_perturbation.tau_s) + "\n";
  for (std::size_t k = 0; k < atmosphere::kShellCount; ++k) {
    const atmosphere::Shell& s = a.shells.shells[k];
    o += "\n[atmosphere.shells." + std::string(kShellNames[k]) + "]\n";
    o += "enabled = " + b(s.enabled) + "\n";
    o += "bottom_m = " + number(s.bottom_m) + "\n";
    o += "top_m = " + number(s.top_m) + "\n";
    o += "temperature_k = " + number(s.temperature_k) + "\n";
    o += "gas_absorption = " + b(s.gas_absorption) + "\n";
  }
  for (std::size_t k = 0; k < a.clouds_rain.layer_count; ++k) {
    const atmosphere::CloudLayer& l = a.clouds_rain.layers[k];
    o += "\n[[atmosphere.clouds]]\n";
    o += "base_m = " + number(l.base_m) + "\n";
    o += "thickness_m = " + number(l.thickness_m) + "\n";
    o += "liquid_water_g_m3 = " + number(l.liquid_water_g_m3) + "\n";
    o += "temperature_k = " + number(l.temperature_k) + "\n";
  }
  const atmosphere::RainConfig& rain = a.clouds_rain.rain;
  o += "\n[atmosphere.rain]\n";
  o += "rate_mm_h = " + number(rain.rate_mm_h) + "\n";
  o += "rain_height_m = " + number(rain.rain_height_m) + "\n";
  o += "k = " + number(rain.k) + "\n";
  o += "alpha = " + number(rain.alpha) + "\n";
  return o;
}

std::string signal_toml(const world::WorldConfig& w, const receiver::ReceiverConfig& r, std::string (*number)(double)) {
  const world::SignalConfig& s = w.signal;
  const signal::LinkBudgetConfig& l = s.link;
  std::string o = "\n[signal]  # link budget -> C/N0, tracking\n";
  o += std::string("enabled = ") + (s.enabled ? "true" : "false") + "\n";
  o += "noise_rise_db = " + number(l.environment_noise_rise_db) + "  # environment noise floor rise\n";
  o += "eirp_dbw = " + number(l.eirp_dbw) + "\n";
  o += "noise_figure_db = " + number(l.noise_figure_db) + "\n";
  o += "noise_temperature_k = " + number(l.noise_temperature_k) + "\n";
  o += "implementation_loss_db = " + number(l.implementation_loss_db) + "\n";
  o += "acquire_dbhz = " + number(r.tracking.acquire_dbhz) + "\n";
  o += "lose_dbhz = " + number(r.tracking.lose_dbhz) + "\n";
  o += "\n[signal.antenna]\n";
  o += "zenith_gain_dbi = " + number(l.antenna.zenith_gain_dbi) + "\n";
  o += "horizon_gain_dbi = " + number(l.antenna.horizon_gain_dbi) + "\n";
  o += "below_horizon_slope_db_per_deg = " + number(l.antenna.below_horizon_slope_db_per_deg) + "\n";
  o += "\n[signal.dll]  # code tracking loop (thermal noise when receiver.errors.thermal_model = \"dll\")\n";
  o += "loop_bandwidth_hz = " + number(s.dll.loop_bandwidth_hz) + "\n";
  o += "integration_s = " + number(s.dll.integration_s) + "\n";
  o += "spacing_chips = " + number(s.dll.spacing_chips) + "\n";
  o += "discriminator = " + quoted(name_of(s.dll.discriminator, kDiscriminators)) + "\n";
  return o;
}

}  // namespace gnssemu::config::detail

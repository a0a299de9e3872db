// SPDX-License-Identifier: Apache-2.0
// [atmosphere] and its sub-tables: what the world does to the signal.
// Ranges and cross-field rules: the core atmosphere models'.
#include <limits>

#include "config/keys/config_keys.hpp"
#include "core/atmosphere/clouds_rain.hpp"

namespace gnssemu::config::detail {

namespace {

using atmosphere::CloudLayer;
using atmosphere::IonosphereConfig;
using atmosphere::RainConfig;
using atmosphere::Shell;
using atmosphere::ShellsConfig;
using atmosphere::TroposphereConfig;
using world::AtmosphereConfig;
using world::GaussMarkovConfig;
using Perturbation = atmosphere::GaussMarkovParams;

constexpr Choice<atmosphere::CacheMode> kCacheModes[] = {{"hold", atmosphere::CacheMode::kHold},
                                                         {"linear", atmosphere::CacheMode::kLinear}};
constexpr Choice<atmosphere::VtecSource> kVtecSources[] = {{"klobuchar", atmosphere::VtecSource::kKlobucharShape},
                                                           {"fixed", atmosphere::VtecSource::kFixed}};
constexpr Choice<atmosphere::IonoMapping> kIonoMappings[] = {
    {"obliquity", atmosphere::IonoMapping::kObliquityFactor}, {"thin_shell", atmosphere::IonoMapping::kThinShell}};
constexpr Choice<atmosphere::ZhdModel> kZhdModels[] = {{"exponential", atmosphere::ZhdModel::kExponential},
                                                       {"saastamoinen", atmosphere::ZhdModel::kSaastamoinen}};
constexpr Choice<atmosphere::ZwdModel> kZwdModels[] = {{"fixed", atmosphere::ZwdModel::kFixed},
                                                       {"saastamoinen", atmosphere::ZwdModel::kSaastamoinen}};

// --- [atmosphere.ionosphere] -----------------------------------------------

using Ir = atmosphere::IonosphereRanges;
constexpr Field<Perturbation> kPerturbationFields[] = {
    number<&Perturbation::sigma>("sigma_tecu", Ir::perturbation_sigma_tecu,
                                 "1 sigma of a first-order Gauss–Markov process on the vertical TEC, one per line of "
                                 "sight; 0 disables"),
    number<&Perturbation::tau_s>("tau_s", Ir::perturbation_tau_s, "correlation time"),
};
constexpr Section<Perturbation> kPerturbation{kPerturbationFields};

constexpr Field<IonosphereConfig> kIonosphereFields[] = {
    boolean<&IonosphereConfig::enabled>("enabled", "world ionosphere on"),
    choice<kVtecSources, &IonosphereConfig::source>(
        "vtec_source", "VTEC = Klobuchar daily shape (nav header coefficients) × `klobuchar_scale`, or `vtec_tecu`"),
    number<&IonosphereConfig::vtec_tecu>("vtec_tecu", Ir::vtec_tecu, "fixed VTEC"),
    number<&IonosphereConfig::klobuchar_scale>(
        "klobuchar_scale", Ir::klobuchar_scale,
        "activity relative to the broadcast model (1: the receiver's Klobuchar removes the mean exactly)"),
    choice<kIonoMappings, &IonosphereConfig::mapping>("mapping",
                                                      "slant factor 1 + 16(pivot − e)³/180³, or thin shell"),
    number<&IonosphereConfig::obliquity_pivot_deg>("obliquity_pivot_deg", Ir::obliquity_pivot_deg,
                                                   "95.4 = Klobuchar's F; 96 = the seed's rounding"),
    number<&IonosphereConfig::shell_height_m>("shell_height_m", Ir::shell_height_m, "thin-shell height"),
    table<kPerturbation, &IonosphereConfig::perturbation>("perturbation",
                                                          "first-order Gauss-Markov on the vertical TEC"),
};
constexpr Section<IonosphereConfig> kIonosphere{kIonosphereFields};

// --- [atmosphere.troposphere] ----------------------------------------------

constexpr Field<GaussMarkovConfig> kZwdPerturbationFields[] = {
    number<&GaussMarkovConfig::sigma_m>("sigma_m", world::AtmosphereRanges::zwd_perturbation_sigma_m,
                                        "1 sigma of a Gauss–Markov process on the site's zenith wet delay (mapped "
                                        "with Niell wet); 0 disables"),
    number<&GaussMarkovConfig::tau_s>("tau_s", world::AtmosphereRanges::zwd_perturbation_tau_s, "correlation time"),
};
constexpr Section<GaussMarkovConfig> kZwdPerturbation{kZwdPerturbationFields};

using Tr = atmosphere::TroposphereRanges;
constexpr Field<AtmosphereConfig> kTroposphereFields[] = {
    boolean<&AtmosphereConfig::troposphere, &TroposphereConfig::enabled>("enabled", "world troposphere on"),
    choice<kZhdModels, &AtmosphereConfig::troposphere, &TroposphereConfig::zhd_model>(
        "zhd_model", "ZHD a·e^(−b·h), or Saastamoinen with the standard pressure"),
    number<&AtmosphereConfig::troposphere, &TroposphereConfig::zhd_a_m>("zhd_a_m", Tr::zhd_a_m, "a"),
    number<&AtmosphereConfig::troposphere, &TroposphereConfig::zhd_b_per_m>("zhd_b_per_m", Tr::zhd_b_per_m, "b"),
    choice<kZwdModels, &AtmosphereConfig::troposphere, &TroposphereConfig::zwd_model>(
        "zwd_model", "ZWD `zwd_m`·e^(−h/`zwd_scale_height_m`), or Saastamoinen with `rel_humidity`"),
    number<&AtmosphereConfig::troposphere, &TroposphereConfig::zwd_m>("zwd_m", Tr::zwd_m,
                                                                      "sea-level zenith wet delay"),
    number<&AtmosphereConfig::troposphere, &TroposphereConfig::zwd_scale_height_m>(
        "zwd_scale_height_m", Tr::zwd_scale_height_m, "scale height of the fixed ZWD"),
    number<&AtmosphereConfig::troposphere, &TroposphereConfig::rel_humidity>(
        "rel_humidity", Tr::rel_humidity, "relative humidity of the Saastamoinen ZWD"),
    table<kZwdPerturbation, &AtmosphereConfig::zwd_perturbation>("zwd_perturbation", "first-order Gauss-Markov"),
};
constexpr Section<AtmosphereConfig> kTroposphere{kTroposphereFields};

// --- [atmosphere.shells.<name>] --------------------------------------------

using Sh = atmosphere::ShellRanges;
constexpr Field<Shell> kShellFields[] = {
    boolean<&Shell::enabled>("enabled", "shell present in the gaseous attenuation (the iono and tropo delays have "
                                        "their own switches and heights: `[atmosphere.ionosphere]`, "
                                        "`[atmosphere.troposphere]`)"),
    number<&Shell::bottom_m>("bottom_m", Sh::bottom_m, "bottom above the ellipsoid"),
    number<&Shell::top_m>("top_m", Sh::top_m,
                          "top above the ellipsoid, ≥ `bottom_m`; enabled neutral shells must not overlap (the "
                          "ionosphere may)"),
    rule<Shell, atmosphere::check_thickness>(),
    number<&Shell::temperature_k>("temperature_k", Sh::temperature_k, "mean temperature (dry-air scale height)"),
    boolean<&Shell::gas_absorption>("gas_absorption", "gases attenuate in this shell"),
};
constexpr Section<Shell> kShell{kShellFields};

// The five shells, each an optional table named after it.
void read_shells(TableReader& t, const Field<ShellsConfig>&, ShellsConfig& c) {
  for (std::size_t i = 0; i < atmosphere::kShellCount; ++i) {
    std::optional<TableReader> s = t.table(atmosphere::kShellNames[i], false);
    if (s) read_section(*s, kShell, c.shells[i]);
  }
}

void write_shells(TomlWriter& w, const Field<ShellsConfig>&, const ShellsConfig& c) {
  const std::string shells = w.table();
  for (std::size_t i = 0; i < atmosphere::kShellCount; ++i) {
    write_table(w, kShell, shells + "." + std::string(atmosphere::kShellNames[i]), {}, c.shells[i]);
  }
}

void describe_shells(KeyDocs& d, const Field<ShellsConfig>&, const ShellsConfig& c) {
  for (std::size_t i = 0; i < atmosphere::kShellCount; ++i) {
    d.enter(atmosphere::kShellNames[i], "atmosphere.shells.<name>");
    describe_section(d, kShell, c.shells[i]);
    d.leave();
  }
}

constexpr Field<ShellsConfig> kShellsFields[] = {
    custom_table<ShellsConfig>("", read_shells, write_shells, describe_shells),
    rule<ShellsConfig, atmosphere::check_overlap>(),
};
constexpr Section<ShellsConfig> kShells{kShellsFields};

// --- [[atmosphere.clouds]] -------------------------------------------------

using Cr = atmosphere::CloudLayerRanges;

// A preset fills every value; without one, thickness and liquid water are needed.
void read_preset(TableReader& t, const Field<CloudLayer>&, CloudLayer& l) {
  if (const toml::node* n = t.find("preset")) {
    const std::string name = t.string("preset", std::nullopt);
    try {
      l = atmosphere::cloud_preset(name);
    } catch (const Error& e) {
      t.fail(*n, t.full_name("preset") + ": " + reason_of(e));
    }
  } else if (t.find("thickness_m") == nullptr || t.find("liquid_water_g_m3") == nullptr) {
    t.fail_missing(t.find("thickness_m") == nullptr ? "thickness_m" : "liquid_water_g_m3", "key (or a preset)");
  }
}

void read_thickness(TableReader& t, const Field<CloudLayer>&, CloudLayer& l) {
  if (const toml::node* n = t.find("thickness_m")) {
    // A negative thickness gets its own message before the range's.
    constexpr double kBig = std::numeric_limits<double>::max();
    const double v = t.number("thickness_m", std::nullopt, Range{-kBig, kBig, Cr::thickness_m.unit});
    if (v < 0.0) t.fail(*n, t.full_name("thickness_m") + ": negative thickness " + format_number(v) + " m");
    l.thickness_m = t.number("thickness_m", std::nullopt, Cr::thickness_m);
  }
}

std::string preset_names() { return names_doc(atmosphere::cloud_preset_names()); }

constexpr Field<CloudLayer> thickness_field() {
  Field<CloudLayer> row = number<&CloudLayer::thickness_m>(
      "thickness_m", Cr::thickness_m, "thickness (required without a preset; a negative one: \"negative thickness\")");
  row.read = read_thickness;
  return row;
}

constexpr Field<CloudLayer> kCloudFields[] = {
    custom<CloudLayer>("preset", "", preset_names,
                       "every value of a preset (docs/models.md); the keys below override it; written as those keys",
                       read_preset, nullptr)
        .default_doc("none"),
    number<&CloudLayer::base_m>("base_m", Cr::base_m, "cloud base above the ellipsoid"),
    thickness_field(),
    number<&CloudLayer::liquid_water_g_m3>("liquid_water_g_m3", Cr::liquid_water_g_m3,
                                           "liquid water density (required without a preset)"),
    number<&CloudLayer::temperature_k>("temperature_k", Cr::temperature_k, "droplet temperature"),
};
constexpr Section<CloudLayer> kCloud{kCloudFields};

void read_clouds(TableReader& t, const Field<AtmosphereConfig>& f, AtmosphereConfig& a) {
  std::vector<TableReader> clouds = t.table_array(f.key);
  if (clouds.size() > atmosphere::kMaxCloudLayers) {
    clouds[atmosphere::kMaxCloudLayers].fail(*t.find(f.key), t.full_name(f.key) + ": at most " +
                                                                 std::to_string(atmosphere::kMaxCloudLayers) +
                                                                 " layers, got " + std::to_string(clouds.size()));
  }
  a.clouds_rain.layer_count = clouds.size();
  for (std::size_t i = 0; i < clouds.size(); ++i) {
    a.clouds_rain.layers[i] = CloudLayer{};
    read_section(clouds[i], kCloud, a.clouds_rain.layers[i]);
  }
}

void write_clouds(TomlWriter& w, const Field<AtmosphereConfig>& f, const AtmosphereConfig& a) {
  const std::string path = sub_table(w, f.key);
  for (std::size_t i = 0; i < a.clouds_rain.layer_count; ++i) {
    write_table(w, kCloud, path, {}, a.clouds_rain.layers[i], true);
  }
}

void describe_clouds(KeyDocs& d, const Field<AtmosphereConfig>& f, const AtmosphereConfig&) {
  describe_table<kCloud>(d, f.key, CloudLayer{});
}

// --- [atmosphere.rain] -----------------------------------------------------

using Rn = atmosphere::RainRanges;
constexpr Field<RainConfig> kRainFields[] = {
    number<&RainConfig::rate_mm_h>("rate_mm_h", Rn::rate_mm_h, "rain rate; 0 = no rain"),
    number<&RainConfig::rain_height_m>("rain_height_m", Rn::rain_height_m, "rain height"),
    number<&RainConfig::k>("k", Rn::k, "ITU-R P.838-3 k at L1, circular polarisation"),
    number<&RainConfig::alpha>("alpha", Rn::alpha, "ITU-R P.838-3 α at L1, circular polarisation"),
};
constexpr Section<RainConfig> kRain{kRainFields};

// --- [atmosphere] ----------------------------------------------------------

using Gs = atmosphere::GasRanges;
constexpr Field<AtmosphereConfig> kAtmosphereFields[] = {
    number<&AtmosphereConfig::cache_refresh_s>("cache_refresh_s", world::AtmosphereRanges::cache_refresh_s,
                                               "per-satellite refresh of the slow terms; 0 = every epoch"),
    choice<kCacheModes, &AtmosphereConfig::cache_mode>("cache_mode",
                                                       "between refreshes: hold, or extrapolate from the last two"),
    boolean<&AtmosphereConfig::gases>("gases", "oxygen + water vapour attenuation over the shells"),
    number<&AtmosphereConfig::shells, &ShellsConfig::gas, &atmosphere::GasConfig::water_vapour_density_g_m3>(
        "water_vapour_density_g_m3", Gs::water_vapour_density_g_m3, "surface water vapour density"),
    number<&AtmosphereConfig::shells, &ShellsConfig::gas, &atmosphere::GasConfig::water_vapour_scale_height_m>(
        "water_vapour_scale_height_m", Gs::water_vapour_scale_height_m, "its scale height"),
    table<kIonosphere, &AtmosphereConfig::ionosphere>("ionosphere"),
    table<kTroposphere>("troposphere"),
    table<kShells, &AtmosphereConfig::shells>("shells"),
    custom_table<AtmosphereConfig>("clouds", read_clouds, write_clouds, describe_clouds),
    table<kRain, &AtmosphereConfig::clouds_rain, &atmosphere::CloudsRainConfig::rain>("rain"),
};

}  // namespace

constexpr Section<world::AtmosphereConfig> kAtmosphereKeys{kAtmosphereFields};

}  // namespace gnssemu::config::detail

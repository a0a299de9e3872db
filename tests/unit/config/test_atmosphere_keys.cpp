// SPDX-License-Identifier: Apache-2.0
// [atmosphere] and its sub-tables (config/atmosphere_keys): every key
// parsed, exact round trip through to_toml, default.toml equal to the struct
// defaults, and every bad value an error naming file:line.
#include <string>

#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

// Every key, each different from its default; kBase is lines 1-6.
const std::string kAtmosphere = kBase + R"(
[atmosphere]
cache_refresh_s = 30
cache_mode = "hold"
gases = false
water_vapour_density_g_m3 = 12.5
water_vapour_scale_height_m = 1800

[atmosphere.ionosphere]
enabled = false
vtec_source = "fixed"
vtec_tecu = 42.5
klobuchar_scale = 1.7
mapping = "thin_shell"
obliquity_pivot_deg = 96
shell_height_m = 450000
[atmosphere.ionosphere.perturbation]
sigma_tecu = 2.5
tau_s = 900

[atmosphere.troposphere]
enabled = false
zhd_model = "saastamoinen"
zhd_a_m = 2.25
zhd_b_per_m = 1.3e-4
zwd_model = "saastamoinen"
zwd_m = 0.21
zwd_scale_height_m = 1500
rel_humidity = 0.55
[atmosphere.troposphere.zwd_perturbation]
sigma_m = 0.035
tau_s = 7200

[atmosphere.shells.stratosphere]
enabled = false
bottom_m = 11000
top_m = 48000
temperature_k = 230.5
gas_absorption = false

[[atmosphere.clouds]]
preset = "cumulus"
temperature_k = 270.5

[[atmosphere.clouds]]
base_m = 200
thickness_m = 350.5
liquid_water_g_m3 = 0.42
temperature_k = 280

[atmosphere.rain]
rate_mm_h = 100
rain_height_m = 4200
k = 6.0e-5
alpha = 0.95

)";

void expect_same_atmosphere(const Config& a, const Config& b) {
  const world::AtmosphereConfig &x = a.world.atmosphere, &y = b.world.atmosphere;
  EXPECT_EQ(x.cache_refresh_s, y.cache_refresh_s);
  EXPECT_EQ(x.cache_mode, y.cache_mode);
  EXPECT_EQ(x.gases, y.gases);
  EXPECT_EQ(x.shells.gas.water_vapour_density_g_m3, y.shells.gas.water_vapour_density_g_m3);
  EXPECT_EQ(x.shells.gas.water_vapour_scale_height_m, y.shells.gas.water_vapour_scale_height_m);
  EXPECT_EQ(x.ionosphere.enabled, y.ionosphere.enabled);
  EXPECT_EQ(x.ionosphere.source, y.ionosphere.source);
  EXPECT_EQ(x.ionosphere.vtec_tecu, y.ionosphere.vtec_tecu);
  EXPECT_EQ(x.ionosphere.klobuchar_scale, y.ionosphere.klobuchar_scale);
  EXPECT_EQ(x.ionosphere.mapping, y.ionosphere.mapping);
  EXPECT_EQ(x.ionosphere.obliquity_pivot_deg, y.ionosphere.obliquity_pivot_deg);
  EXPECT_EQ(x.ionosphere.shell_height_m, y.ionosphere.shell_height_m);
  EXPECT_EQ(x.ionosphere.perturbation.sigma, y.ionosphere.perturbation.sigma);
  EXPECT_EQ(x.ionosphere.perturbation.tau_s, y.ionosphere.perturbation.tau_s);
  EXPECT_EQ(x.troposphere.enabled, y.troposphere.enabled);
  EXPECT_EQ(x.troposphere.zhd_model, y.troposphere.zhd_model);
  EXPECT_EQ(x.troposphere.zhd_a_m, y.troposphere.zhd_a_m);
  EXPECT_EQ(x.troposphere.zhd_b_per_m, y.troposphere.zhd_b_per_m);
  EXPECT_EQ(x.troposphere.zwd_model, y.troposphere.zwd_model);
  EXPECT_EQ(x.troposphere.zwd_m, y.troposphere.zwd_m);
  EXPECT_EQ(x.troposphere.zwd_scale_height_m, y.troposphere.zwd_scale_height_m);
  EXPECT_EQ(x.troposphere.rel_humidity, y.troposphere.rel_humidity);
  EXPECT_EQ(x.zwd_perturbation.sigma_m, y.zwd_perturbation.sigma_m);
  EXPECT_EQ(x.zwd_perturbation.tau_s, y.zwd_perturbation.tau_s);
  for (std::size_t i = 0; i < atmosphere::kShellCount; ++i) {
    const atmosphere::Shell &s = x.shells.shells[i], &t = y.shells.shells[i];
    EXPECT_EQ(s.enabled, t.enabled) << i;
    EXPECT_EQ(s.bottom_m, t.bottom_m) << i;
    EXPECT_EQ(s.top_m, t.top_m) << i;
    EXPECT_EQ(s.temperature_k, t.temperature_k) << i;
    EXPECT_EQ(s.gas_absorption, t.gas_absorption) << i;
  }
  ASSERT_EQ(x.clouds_rain.layer_count, y.clouds_rain.layer_count);
  for (std::size_t i = 0; i < x.clouds_rain.layer_count; ++i) {
    const atmosphere::CloudLayer &l = x.clouds_rain.layers[i], &m = y.clouds_rain.layers[i];
    EXPECT_EQ(l.base_m, m.base_m);
    EXPECT_EQ(l.thickness_m, m.thickness_m);
    EXPECT_EQ(l.liquid_water_g_m3, m.liquid_water_g_m3);
    EXPECT_EQ(l.temperature_k, m.temperature_k);
  }
  EXPECT_EQ(x.clouds_rain.rain.rate_mm_h, y.clouds_rain.rain.rate_mm_h);
  EXPECT_EQ(x.clouds_rain.rain.rain_height_m, y.clouds_rain.rain.rain_height_m);
  EXPECT_EQ(x.clouds_rain.rain.k, y.clouds_rain.rain.k);
  EXPECT_EQ(x.clouds_rain.rain.alpha, y.clouds_rain.rain.alpha);
}

TEST(AtmosphereConfig, EveryKeyParsed) {
  const Config c = parse(kAtmosphere);
  const world::WorldConfig& w = c.world;
  EXPECT_EQ(w.atmosphere.cache_mode, atmosphere::CacheMode::kHold);
  EXPECT_EQ(w.atmosphere.ionosphere.mapping, atmosphere::IonoMapping::kThinShell);
  EXPECT_EQ(w.atmosphere.ionosphere.perturbation.sigma, 2.5);
  EXPECT_EQ(w.atmosphere.zwd_perturbation.tau_s, 7200.0);
  EXPECT_EQ(w.atmosphere.shells.shells[1].top_m, 48000.0);
  EXPECT_EQ(w.atmosphere.shells.shells[0].top_m, 12000.0);  // untouched shell keeps its default
  ASSERT_EQ(w.atmosphere.clouds_rain.layer_count, 2u);
  // The cumulus preset (1 km + 1.5 km, 1 g/m^3) with its temperature overridden.
  EXPECT_EQ(w.atmosphere.clouds_rain.layers[0].base_m, 1000.0);
  EXPECT_EQ(w.atmosphere.clouds_rain.layers[0].thickness_m, 1500.0);
  EXPECT_EQ(w.atmosphere.clouds_rain.layers[0].liquid_water_g_m3, 1.0);
  EXPECT_EQ(w.atmosphere.clouds_rain.layers[0].temperature_k, 270.5);
  EXPECT_EQ(w.atmosphere.clouds_rain.layers[1].thickness_m, 350.5);
  EXPECT_EQ(w.atmosphere.clouds_rain.rain.rate_mm_h, 100.0);
}

TEST(AtmosphereConfig, RoundTripIsExact) {
  const Config c = parse(kAtmosphere);
  const std::string text = to_toml(c, kData);
  const Config back = parse_config(text, "written.toml", kData);
  expect_same_atmosphere(c, back);
  EXPECT_EQ(to_toml(back, kData), text);
  // The struct defaults too.
  const Config d = parse(kBase);
  expect_same_atmosphere(d, parse(to_toml(d, kData)));
}

TEST(AtmosphereConfig, DefaultTomlIsTheStructDefaults) {
  const Config shipped = load_config(kSource + "/config/default.toml");
  expect_same_atmosphere(shipped, struct_defaults_as_shipped(shipped));
}

TEST(AtmosphereConfig, ShellsMovedTogetherDoNotOverlap) {
  // Checked after every shell is read: a boundary moved in both shells is fine.
  const Config c = parse(kBase + "[atmosphere.shells.stratosphere]\ntop_m = 60000\n"
                                 "[atmosphere.shells.mesosphere]\nbottom_m = 60000\n");
  EXPECT_EQ(c.world.atmosphere.shells.shells[1].top_m, 60000.0);
  EXPECT_EQ(c.world.atmosphere.shells.shells[2].bottom_m, 60000.0);
  // A disabled shell overlaps nothing.
  EXPECT_NO_THROW(parse(kBase + "[atmosphere.shells.stratosphere]\ntop_m = 60000\n"
                                "[atmosphere.shells.mesosphere]\nenabled = false\n"));
}

struct Bad {
  std::string text;
  std::string message;  // expected substring, starting with "t.toml:LINE:"
};

TEST(AtmosphereConfig, BadValuesNameFileAndLine) {
  const Bad cases[] = {
      {"[[atmosphere.clouds]]\nbase_m = 100\nthickness_m = -5\nliquid_water_g_m3 = 0.3\n",
       "t.toml:9: atmosphere.clouds[0].thickness_m: negative thickness -5 m"},
      {"[atmosphere.shells.mesosphere]\nbottom_m = 50000\ntop_m = 40000\n",
       "t.toml:9: atmosphere.shells.mesosphere: negative thickness (top_m 40000 m < bottom_m 50000 m)"},
      {"[atmosphere.shells.stratosphere]\ntop_m = 60000\n",
       "t.toml:7: atmosphere.shells: stratosphere (12000-60000 m) and mesosphere (50000-85000 m) overlap"},
      {"[atmosphere.shells.troposphere]\ntemperature_k = 0\n",
       "t.toml:8: atmosphere.shells.troposphere.temperature_k: 0 is out of range (0, 5000] K"},
      {"[[atmosphere.clouds]]\npreset = \"fog\"\ntemperature_k = -3\n",
       "t.toml:9: atmosphere.clouds[0].temperature_k: -3 is out of range (0, 5000] K"},
      {"[[atmosphere.clouds]]\npreset = \"nimbus\"\n",
       "t.toml:8: atmosphere.clouds[0].preset: unknown cloud preset 'nimbus' (known: fog, thick_fog, stratus, "
       "cumulus, cumulonimbus, thunderstorm)"},
      {"[atmosphere.ionosphere]\nmapping = \"flat\"\n",
       "t.toml:8: atmosphere.ionosphere.mapping: 'flat' is not one of \"obliquity\", \"thin_shell\""},
      {"[atmosphere.ionosphere]\nvtec_tecu = -1\n", "t.toml:8: atmosphere.ionosphere.vtec_tecu: -1 is out of range"},
      {"[atmosphere.rain]\nrate_mm_h = 600\n", "t.toml:8: atmosphere.rain.rate_mm_h: 600 is out of range [0, 500] mm/h"},
      {"[atmosphere]\ncache_refresh_s = -1\n", "t.toml:8: atmosphere.cache_refresh_s: -1 is out of range"},
      {"[atmosphere.troposphere.zwd_perturbation]\ntau_s = 0\n",
       "t.toml:8: atmosphere.troposphere.zwd_perturbation.tau_s: 0 is out of range"},
      {"[[atmosphere.clouds]]\nbase_m = 100\n",
       "t.toml:7: missing required key (or a preset) 'atmosphere.clouds[0].thickness_m'"},
      {"[atmosphere.ionosphere]\nenabeld = true\n",
       "t.toml:8: unknown key 'atmosphere.ionosphere.enabeld' (did you mean 'enabled'?)"},

  };
  for (const Bad& b : cases) {
    const std::string err = error_of(kBase + b.text);
    EXPECT_NE(err.find(b.message), std::string::npos) << b.text << "\n got: " << err;
  }
  std::string nine;
  for (int i = 0; i < 9; ++i) nine += "[[atmosphere.clouds]]\npreset = \"fog\"\n";
  EXPECT_NE(error_of(kBase + "\n" + nine).find("at most 8 layers, got 9"), std::string::npos) << error_of(kBase + nine);
}

}  // namespace
}  // namespace gnssemu::config::test

// SPDX-License-Identifier: Apache-2.0
// [signal] and its sub-tables (config/signal_keys): every key parsed, exact
// round trip through to_toml, default.toml equal to the struct defaults,
// and every bad value an error naming file:line.
#include <string>

#include "test_helpers.hpp"

namespace gnssemu::config::test::signal_keys_test {
namespace {

// Every key, each different from its default; kBase is lines 1-6.
const std::string kSignal = kBase + R"(
[signal]
enabled = false
environment = "urban"
eirp_dbw = 27.5
noise_figure_db = 1.5
noise_temperature_k = 300
implementation_loss_db = 1.25
acquire_dbhz = 33
lose_dbhz = 28.5

[signal.antenna]
zenith_gain_dbi = 5.5
horizon_gain_dbi = -8.5
below_horizon_slope_db_per_deg = 0.5

[signal.dll]
loop_bandwidth_hz = 1.0
integration_s = 0.005
spacing_chips = 0.1
discriminator = "dot_product"
)";

void expect_same_signal(const Config& a, const Config& b) {
  const world::SignalConfig &s = a.world.signal, &t = b.world.signal;
  EXPECT_EQ(s.enabled, t.enabled);
  EXPECT_EQ(s.link.environment_noise_rise_db, t.link.environment_noise_rise_db);
  EXPECT_EQ(s.link.eirp_dbw, t.link.eirp_dbw);
  EXPECT_EQ(s.link.noise_figure_db, t.link.noise_figure_db);
  EXPECT_EQ(s.link.noise_temperature_k, t.link.noise_temperature_k);
  EXPECT_EQ(s.link.implementation_loss_db, t.link.implementation_loss_db);
  EXPECT_EQ(a.receiver.tracking.acquire_dbhz, b.receiver.tracking.acquire_dbhz);
  EXPECT_EQ(a.receiver.tracking.lose_dbhz, b.receiver.tracking.lose_dbhz);
  EXPECT_EQ(s.link.antenna.zenith_gain_dbi, t.link.antenna.zenith_gain_dbi);
  EXPECT_EQ(s.link.antenna.horizon_gain_dbi, t.link.antenna.horizon_gain_dbi);
  EXPECT_EQ(s.link.antenna.below_horizon_slope_db_per_deg, t.link.antenna.below_horizon_slope_db_per_deg);
  EXPECT_EQ(s.dll.loop_bandwidth_hz, t.dll.loop_bandwidth_hz);
  EXPECT_EQ(s.dll.integration_s, t.dll.integration_s);
  EXPECT_EQ(s.dll.spacing_chips, t.dll.spacing_chips);
  EXPECT_EQ(s.dll.discriminator, t.dll.discriminator);
}

TEST(SignalConfig, EveryKeyParsed) {
  const Config c = parse(kSignal);
  const world::WorldConfig& w = c.world;
  const receiver::ReceiverConfig& r = c.receiver;
  EXPECT_EQ(w.signal.link.environment_noise_rise_db, 6.0);  // "urban"
  EXPECT_EQ(r.tracking.lose_dbhz, 28.5);
  EXPECT_EQ(w.signal.link.antenna.horizon_gain_dbi, -8.5);
  EXPECT_EQ(w.signal.dll.discriminator, signal::DllDiscriminator::kDotProduct);
  EXPECT_FALSE(w.signal.enabled);
}

TEST(SignalConfig, RoundTripIsExact) {
  const Config c = parse(kSignal);
  const std::string text = to_toml(c, kData);
  const Config back = parse_config(text, "written.toml", kData);
  expect_same_signal(c, back);
  EXPECT_EQ(to_toml(back, kData), text);
  // The struct defaults too.
  const Config d = parse(kBase);
  expect_same_signal(d, parse(to_toml(d, kData)));
}

TEST(SignalConfig, DefaultTomlIsTheStructDefaults) {
  const Config shipped = load_config(kSource + "/config/default.toml");
  expect_same_signal(shipped, struct_defaults_as_shipped(shipped));
}

struct Bad {
  std::string text;
  std::string message;  // expected substring, starting with "t.toml:LINE:"
};

TEST(SignalConfig, BadValuesNameFileAndLine) {
  const Bad cases[] = {
      {"[signal]\nnoise_temperature_k = 0.0\n", "t.toml:8: signal.noise_temperature_k: 0 is out of range (0, 5000] K"},
      {"[signal]\nenvironment = \"desert\"\n",
       "t.toml:8: signal.environment: unknown environment noise preset 'desert' (known: countryside, suburban, "
       "urban, industrial, jamming)"},
      {"[signal]\nenvironment = \"urban\"\nnoise_rise_db = 3\n",
       "t.toml:9: signal.noise_rise_db: give either environment or noise_rise_db, not both"},
      {"[signal]\nacquire_dbhz = 28\nlose_dbhz = 30\n",
       "t.toml:9: signal: lose_dbhz 30 exceeds acquire_dbhz 28 (hysteresis needs lose <= acquire)"},
      {"[signal.antenna]\nzenith_gain_dbi = -2\nhorizon_gain_dbi = 1\n",
       "t.toml:9: signal.antenna: horizon_gain_dbi 1 exceeds zenith_gain_dbi -2"},
      {"[signal.dll]\nspacing_chips = 1.5\n", "t.toml:8: signal.dll.spacing_chips: 1.5 is out of range (0, 1] chips"},
      {"[signal.carrier]\ndoppler_model = \"pll\"\n",
       "t.toml:8: signal.carrier.doppler_model: 'pll' is not \"fll\" or \"fixed\""},
      {"[signal.carrier]\npll_bandwidth_hz = 0\n",
       "t.toml:8: signal.carrier.pll_bandwidth_hz: 0 is out of range (0, 100] Hz"},
      {"[signal.carrier]\nenabled = true\nintegration_s = 0.05\n",
       "t.toml:9: signal.carrier.integration_s: 0.05 is out of range (0, 0.02] s"},
      {"[signal.carrier]\nlock_break_m = -1\n", "t.toml:8: signal.carrier.lock_break_m: -1 is out of range"},
  };
  for (const Bad& b : cases) {
    const std::string err = error_of(kBase + b.text);
    EXPECT_NE(err.find(b.message), std::string::npos) << b.text << "\n got: " << err;
  }
}

}  // namespace
}  // namespace gnssemu::config::test::signal_keys_test

// SPDX-License-Identifier: Apache-2.0
// [receiver] and its sub-tables (config/receiver_keys): ranges from the
// core, the solver's and the receiver's rules, the receiver's own
// corrections and error models; each assertion pins "file:line: reason".
#include <string>
#include <vector>

#include "config/setup/device_setup.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "test_helpers.hpp"

namespace gnssemu::config::test::receiver_keys_test {
namespace {

TEST(ConfigValidation, RateOutsideOneToTenHz) {
  EXPECT_EQ(error_of(kBase + "[receiver]\nrate_hz = 0.5\n"),
            "t.toml:8: receiver.rate_hz: 0.5 is out of range [1, 10] Hz");
  EXPECT_EQ(error_of(kBase + "[receiver]\nrate_hz = 10.5\n"),
            "t.toml:8: receiver.rate_hz: 10.5 is out of range [1, 10] Hz");
  EXPECT_EQ(parse(kBase + "[receiver]\nrate_hz = 10\n").rate_hz, 10.0);
  EXPECT_EQ(parse(kBase + "[receiver]\nrate_hz = 1\n").rate_hz, 1.0);
}

TEST(ConfigValidation, MaskOutsideZeroToNinety) {
  EXPECT_EQ(error_of(kBase + "[receiver]\nelevation_mask_deg = -1\n"),
            "t.toml:8: receiver.elevation_mask_deg: -1 is out of range [0, 90) deg");
  EXPECT_EQ(error_of(kBase + "[receiver]\nelevation_mask_deg = 90\n"),
            "t.toml:8: receiver.elevation_mask_deg: 90 is out of range [0, 90) deg");
  EXPECT_EQ(parse(kBase + "[receiver]\nelevation_mask_deg = 0\n").receiver.elevation_mask_rad, 0.0);
}

TEST(ConfigValidation, NegativeSigmas) {
  EXPECT_EQ(error_of(kBase + "[receiver.errors]\nthermal_sigma_m = -0.1\n"),
            "t.toml:8: receiver.errors.thermal_sigma_m: -0.1 is out of range [0, 100] m");
  EXPECT_EQ(error_of(kBase + "[receiver.errors]\ndoppler_sigma_m_s = -1\n"),
            "t.toml:8: receiver.errors.doppler_sigma_m_s: -1 is out of range [0, 10] m/s");
  EXPECT_EQ(error_of(kBase + "[receiver.errors.orbit_clock]\nsigma_m = -2\n"),
            "t.toml:8: receiver.errors.orbit_clock.sigma_m: -2 is out of range [0, 100] m");
  EXPECT_EQ(error_of(kBase + "[receiver.clock]\ndrift_noise_s_s_sqrt_s = -1e-12\n"),
            "t.toml:8: receiver.clock.drift_noise_s_s_sqrt_s: -1e-12 is out of range [0, 1e-06] s/s/sqrt(s)");
  // Zero disables a process and is allowed.
  EXPECT_EQ(parse(kBase + "[receiver.errors]\nthermal_sigma_m = 0\n").world.errors.thermal_sigma_m, 0.0);
}

TEST(ConfigValidation, TauNotPositive) {
  EXPECT_EQ(error_of(kBase + "[receiver.errors.orbit_clock]\ntau_s = 0\n"),
            "t.toml:8: receiver.errors.orbit_clock.tau_s: 0 is out of range (0, 1000000] s");
  EXPECT_EQ(error_of(kBase + "[receiver.errors.orbit_clock]\nsigma_m = 1\ntau_s = -60\n"),
            "t.toml:9: receiver.errors.orbit_clock.tau_s: -60 is out of range (0, 1000000] s");
}

TEST(ConfigValidation, SolverRanges) {
  EXPECT_EQ(error_of(kBase + "[receiver.solver]\nsigma_b_m = -0.3\n"),
            "t.toml:8: receiver.solver.sigma_b_m: -0.3 is out of range [0, 100] m");
  EXPECT_EQ(error_of(kBase + "[receiver.solver]\nsigma_a_m = 0\nsigma_b_m = 0\n"),
            "t.toml:8: receiver.solver: sigma_a_m and sigma_b_m are both 0 (the solver's weights would be infinite)");
  EXPECT_EQ(error_of(kBase + "[receiver.solver]\nsigma_range_rate_m_s = 0\n"),
            "t.toml:8: receiver.solver.sigma_range_rate_m_s: 0 is out of range (0, 10] m/s");
  EXPECT_EQ(error_of(kBase + "[receiver.solver]\nheight_hold_sigma_m = -1\n"),
            "t.toml:8: receiver.solver.height_hold_sigma_m: -1 is out of range (0, 1000] m");
  EXPECT_EQ(error_of(kBase + "[receiver.solver]\nresidual_test_pfa = 1\n"),
            "t.toml:8: receiver.solver.residual_test_pfa: 1 is out of range [0, 0.5)");
  EXPECT_EQ(error_of(kBase + "[receiver.solver]\nmax_iterations = 0\n"),
            "t.toml:8: receiver.solver.max_iterations: 0 is out of range [1, 100]");
  EXPECT_EQ(parse(kBase + "[receiver.solver]\nsigma_a_m = 0\n").receiver.solver.sigma_a_m, 0.0);
}

TEST(ConfigValidation, ClockOutOfRange) {
  EXPECT_EQ(error_of(kBase + "[receiver.clock]\nbias_s = 0.5\n"),
            "t.toml:8: receiver.clock.bias_s: 0.5 is out of range [-0.01, 0.01] s");
  EXPECT_EQ(error_of(kBase + "[receiver.clock]\njump_threshold_s = -1e-3\n"),
            "t.toml:8: receiver.clock.jump_threshold_s: -0.001 is out of range [0, 0.01] s");
  EXPECT_EQ(error_of(kBase + "[receiver.clock]\ndrift_s_s = 1e-3\n"),
            "t.toml:8: receiver.clock.drift_s_s: 0.001 is out of range [-1e-05, 1e-05] s/s");
}

TEST(ConfigValidation, ReceiverLimits) {
  EXPECT_EQ(error_of(kBase + "[receiver]\nmax_channels = 3\n"),
            "t.toml:8: receiver.max_channels: 3 is out of range [4, 96]");
  EXPECT_EQ(error_of(kBase + "[receiver]\nseed = -1\n"),
            "t.toml:8: receiver.seed: -1 is out of range [0, 9223372036854775807]");
  EXPECT_EQ(error_of(kBase + "[receiver]\nmax_pdop = 0.5\n"),
            "t.toml:8: receiver.max_pdop: 0.5 is out of range [1, 1000]");
  EXPECT_EQ(error_of(kBase + "[receiver]\nnominal_cn0_dbhz = 70\n"),
            "t.toml:8: receiver.nominal_cn0_dbhz: 70 is out of range [10, 60] dB-Hz");
}

TEST(ConfigValidation, TwoBandsOnlyOnTheF9p) {
  // The M8 and M9 families track L1 only; the ZED-F9P two bands by default
  // and one when asked (an L1-only F9P), and always has raw data.
  EXPECT_EQ(error_of(kBase + "[receiver]\nbands = 2\n"),
            "t.toml:8: receiver.bands = 2: the NEO-M8N tracks L1 only; generation = \"f9p\" tracks two bands");
  EXPECT_EQ(error_of(kBase + "[receiver]\ngeneration = \"m9\"\nbands = 2\n"),
            "t.toml:9: receiver.bands = 2: the NEO-M9N tracks L1 only; generation = \"f9p\" tracks two bands");
  EXPECT_EQ(parse(kBase + "[receiver]\nbands = 2\ngeneration = \"f9p\"\n").receiver.bands, 2);
  EXPECT_EQ(parse(kBase + "[receiver]\ngeneration = \"f9p\"\n").receiver.bands, 2);
  EXPECT_EQ(parse(kBase + "[receiver]\ngeneration = \"f9p\"\nbands = 1\n").receiver.bands, 1);
  EXPECT_EQ(error_of(kBase + "[receiver]\ngeneration = \"f9p\"\nraw_data = false\n"),
            "t.toml:9: receiver.raw_data = false: every ZED-F9P firmware (HPG) has RXM-RAWX and RXM-SFRBX; leave it out");
  EXPECT_TRUE(parse(kBase + "[receiver]\ngeneration = \"m9\"\nraw_data = true\n").raw_data);
}

TEST(ConfigValidation, CoreRangesAreTheConfigRanges) {
  // One range per setting, owned by the core: what the file accepts, the
  // receiver accepts; what the receiver rejects is named at its file:line.
  EXPECT_EQ(error_of(kBase + "[receiver]\nmax_channels = 100\n"),
            "t.toml:8: receiver.max_channels: 100 is out of range [4, 96]");
  EXPECT_EQ(parse(kBase + "[receiver]\nmax_channels = 32\n").receiver.max_channels, 32);
  EXPECT_EQ(error_of(kBase + "[receiver.solver]\nresidual_test_pfa = 0.7\n"),
            "t.toml:8: receiver.solver.residual_test_pfa: 0.7 is out of range [0, 0.5)");
}

// [receiver.errors.multipath] and [receiver.errors.gradient]: the terms
// `gnssemu calibrate` fits; bad values name file:line, defaults are off.

TEST(ConfigCalibrationTerms, DefaultsAreOff) {
  const Config c = parse(kBase);
  EXPECT_EQ(c.world.errors.multipath.sigma_m, 0.0);
  EXPECT_EQ(c.world.errors.multipath.tau_s, 60.0);
  EXPECT_EQ(c.world.errors.gradient.north_m, 0.0);
  EXPECT_EQ(c.world.errors.gradient.east_m, 0.0);
  EXPECT_EQ(c.world.errors.gradient.process.sigma_m, 0.0);
  EXPECT_EQ(c.world.errors.gradient.north_diurnal_m, 0.0);
  EXPECT_EQ(c.world.errors.gradient.east_diurnal_m, 0.0);
}

TEST(ConfigCalibrationTerms, BadValuesNameFileAndLine) {
  EXPECT_EQ(error_of(kBase + "[receiver.errors.multipath]\nsigma_m = -0.1\n"),
            "t.toml:8: receiver.errors.multipath.sigma_m: -0.1 is out of range [0, 100] m");
  EXPECT_EQ(error_of(kBase + "[receiver.errors.multipath]\nsigma_m = 0.1\ntau_s = 0\n"),
            "t.toml:9: receiver.errors.multipath.tau_s: 0 is out of range (0, 1000000] s");
  EXPECT_EQ(error_of(kBase + "[receiver.errors.gradient]\nnorth_m = 200\n"),
            "t.toml:8: receiver.errors.gradient.north_m: 200 is out of range [-100, 100] m");
  EXPECT_EQ(error_of(kBase + "[receiver.errors.gradient]\neast_m = nan\n"),
            "t.toml:8: receiver.errors.gradient.east_m: must be a finite number, got nan");
  EXPECT_EQ(error_of(kBase + "[receiver.errors.gradient]\nsigma_m = 0.3\ntau_s = -5\n"),
            "t.toml:9: receiver.errors.gradient.tau_s: -5 is out of range (0, 1000000] s");
  EXPECT_EQ(error_of(kBase + "[receiver.errors.gradient]\nnorth_diurnal_m = -0.2\n"),
            "t.toml:8: receiver.errors.gradient.north_diurnal_m: -0.2 is out of range [0, 100] m");
  EXPECT_EQ(error_of(kBase + "[receiver.errors.gradient]\neast_peak_h = 24\n"),
            "t.toml:8: receiver.errors.gradient.east_peak_h: 24 is out of range [0, 24) h");
  EXPECT_EQ(error_of(kBase + "[receiver.errors.gradient]\nnorth = 1\n"),
            "t.toml:8: unknown key 'receiver.errors.gradient.north' (did you mean 'north_m'?)");
}

// [receiver.errors] thermal_model, [receiver.solver] sigma_c_m_sqrt_hz and
// [receiver.corrections], each different from its default; kBase is lines 1-6.
const std::string kModels = kBase + R"(
[receiver.errors]
thermal_model = "fixed"
[receiver.solver]
sigma_c_m_sqrt_hz = 95.5
[receiver.corrections]
ionosphere = "none"
troposphere = "zhd_niell"

)";

void expect_same_models(const Config& a, const Config& b) {
  EXPECT_EQ(a.world.errors.thermal_model, b.world.errors.thermal_model);
  EXPECT_EQ(a.receiver.solver.sigma_c_m_sqrt_hz, b.receiver.solver.sigma_c_m_sqrt_hz);
  EXPECT_EQ(a.receiver.solver.iono, b.receiver.solver.iono);
  EXPECT_EQ(a.receiver.solver.tropo, b.receiver.solver.tropo);
}

TEST(ReceiverModelsConfig, EveryKeyParsed) {
  const Config c = parse(kModels);
  const world::WorldConfig& w = c.world;
  const receiver::ReceiverConfig& r = c.receiver;
  EXPECT_EQ(w.errors.thermal_model, world::ThermalModel::kFixed);
  EXPECT_EQ(r.solver.tropo, atmosphere::TropoCorrection::kZhdNiell);
}

TEST(ReceiverModelsConfig, RoundTripIsExact) {
  const Config c = parse(kModels);
  const std::string text = to_toml(c, kData);
  const Config back = parse_config(text, "written.toml", kData);
  expect_same_models(c, back);
  EXPECT_EQ(to_toml(back, kData), text);
  // The struct defaults too.
  const Config d = parse(kBase);
  expect_same_models(d, parse(to_toml(d, kData)));
}

TEST(ReceiverModelsConfig, DefaultTomlIsTheStructDefaults) {
  const Config shipped = load_config(kSource + "/config/default.toml");
  expect_same_models(shipped, struct_defaults_as_shipped(shipped));
}

// A profile gives the defaults; keys in the file override them.
TEST(ReceiverModelsConfig, ProfileGivesDefaultsTheFileOverrides) {
  const Config plain = parse(kBase);
  EXPECT_FALSE(plain.profile.has_value());
  const Config g = parse(kBase + "[receiver]\nprofile = \"geodetic\"\n");
  ASSERT_TRUE(g.profile.has_value());
  EXPECT_EQ(*g.profile, pipeline::ReceiverProfile::kGeodetic);
  const pipeline::PipelineConfig want =
      pipeline::apply_profile({plain.world, plain.receiver}, pipeline::ReceiverProfile::kGeodetic, plain.origin.lat_rad);
  EXPECT_DOUBLE_EQ(g.world.errors.iono_scale.sigma, want.world.errors.iono_scale.sigma);
  EXPECT_GT(g.world.errors.iono_scale.sigma, 0.0);
  EXPECT_DOUBLE_EQ(g.world.signal.dll.loop_bandwidth_hz, want.world.signal.dll.loop_bandwidth_hz);
  EXPECT_DOUBLE_EQ(g.world.errors.gradient.north_m, want.world.errors.gradient.north_m);
  const Config m8 = parse(kBase + "[receiver]\nprofile = \"ublox_m8\"\n[receiver.errors.iono_scale]\nsigma = 0.1\n"
                                  "[signal.dll]\nloop_bandwidth_hz = 0.5\n");
  EXPECT_DOUBLE_EQ(m8.world.errors.iono_scale.sigma, 0.1);
  EXPECT_DOUBLE_EQ(m8.world.signal.dll.loop_bandwidth_hz, 0.5);
  EXPECT_DOUBLE_EQ(m8.world.errors.orbit_clock.sigma_m, want.world.errors.orbit_clock.sigma_m);
  // Written with its profile and every value, read back the same.
  const Config back = parse(to_toml(m8, kData));
  EXPECT_EQ(back.profile, m8.profile);
  expect_same_models(m8, back);
}

struct Bad {
  std::string text;
  std::string message;  // expected substring, starting with "t.toml:LINE:"
};

TEST(ReceiverModelsConfig, BadValuesNameFileAndLine) {
  const Bad cases[] = {
      {"[receiver.corrections]\ntroposphere = \"hopfield\"\n",
       "t.toml:8: receiver.corrections.troposphere: 'hopfield' is not one of \"saastamoinen\", \"zhd_niell\", \"saastamoinen_cosz\", \"none\""},
      {"[receiver]\nprofile = \"m9\"\n", "t.toml:8: receiver.profile: 'm9' is not one of \"ublox_m8\", \"geodetic\""},
      {"[receiver.solver]\nweights = \"snr\"\n",
       "t.toml:8: receiver.solver.weights: 'snr' is not \"elevation_cn0\" or \"rtklib\""},
      {"[receiver.solver]\ncode_bias_sigma_m = -1\n", "t.toml:8: receiver.solver.code_bias_sigma_m: -1"},
      {"[receiver.errors.iono_scale]\nsigma = 3\n", "t.toml:8: receiver.errors.iono_scale.sigma: 3"},
      {"[receiver.errors.iono_scale]\ntau_s = 0\n", "t.toml:8: receiver.errors.iono_scale.tau_s: 0"},
  };
  for (const Bad& b : cases) {
    const std::string err = error_of(kBase + b.text);
    EXPECT_NE(err.find(b.message), std::string::npos) << b.text << "\n got: " << err;
  }
}

// [receiver] filter, [receiver.nav], [receiver.acquisition], [receiver.limits].

TEST(ReceiverDynamicsConfig, DefaultsAreAnM8) {
  const Config c = parse(kBase);
  EXPECT_EQ(c.receiver.filter.type, receiver::NavFilterType::kKalman);
  EXPECT_EQ(c.receiver.filter.dynamic_model, receiver::DynamicModel::kPortable);
  EXPECT_EQ(c.receiver.filter.static_hold_speed_m_s, 0.0);
  EXPECT_EQ(c.receiver.acquisition.start, receiver::StartMode::kHot);
  EXPECT_TRUE(c.receiver.acquisition.modelled);
  EXPECT_EQ(c.receiver.limits.max_altitude_m, 50000.0);
  EXPECT_EQ(c.receiver.limits.max_speed_m_s, 500.0);
  EXPECT_EQ(c.world.carrier.doppler_model, world::DopplerModel::kFll);
}

TEST(ReceiverDynamicsConfig, KeysReachTheReceiverAndTheDevice) {
  const Config c = parse(kBase +
                         "[receiver]\nfilter = \"none\"\n"
                         "[receiver.nav]\ndyn_model = \"airborne2g\"\nstatic_hold_thresh_m_s = 0.3\n"
                         "static_hold_max_dist_m = 12\n"
                         "[receiver.acquisition]\nstart = \"warm\"\ncold_acquire_dbhz = 25\n"
                         "[receiver.limits]\nmax_altitude_m = 18000\nmax_speed_m_s = 515\n");
  EXPECT_EQ(c.receiver.filter.type, receiver::NavFilterType::kNone);
  EXPECT_EQ(c.receiver.filter.dynamic_model, receiver::DynamicModel::kAirborne2g);
  EXPECT_EQ(c.receiver.acquisition.start, receiver::StartMode::kWarm);
  EXPECT_EQ(c.receiver.acquisition.cold_acquire_dbhz, 25.0);
  EXPECT_EQ(c.receiver.limits.max_altitude_m, 18000.0);
  EXPECT_EQ(c.receiver.limits.max_speed_m_s, 515.0);
  // What CFG-NAV5 reads back after start-up (dynModel 7, cm/s, m).
  const protocol::ubx::DeviceSetup d = device_setup(c);
  EXPECT_EQ(d.dyn_model, 7);
  EXPECT_EQ(d.static_hold_thresh_cm_s, 30);
  EXPECT_EQ(d.static_hold_max_dist_m, 12);
}

TEST(ReceiverGenerationConfig, M9ReachesTheChipThroughTheDaemonsSetup) {
  // The daemon builds its Device from device_setup(config): MON-VER and the message set follow generation.
  const Config c = parse(kBase + "[receiver]\ngeneration = \"m9\"\n");
  const protocol::ubx::DeviceSetup d = device_setup(c);
  EXPECT_EQ(d.mon_ver.generation, protocol::ubx::Generation::kM9);
  protocol::ubx::Device chip(d);
  std::string out;
  chip.encoder().mon_ver(out);
  const std::string text(out.begin() + 6, out.end() - 2);
  EXPECT_NE(text.find("EXT CORE 4.04 (7f89f7)"), std::string::npos);
  EXPECT_NE(text.find("00190000"), std::string::npos);
  EXPECT_NE(text.find("FWVER=SPG 4.04"), std::string::npos);
  EXPECT_NE(text.find("PROTVER=32.01"), std::string::npos);
  EXPECT_EQ(chip.generation(), protocol::ubx::Generation::kM9);
  EXPECT_EQ(device_setup(parse(kBase)).mon_ver.generation, protocol::ubx::Generation::kM8);
}

TEST(ReceiverGenerationConfig, ChipRateCapsTheM9Solution) {
  // The NEO-M9N above 8 Hz uses at most 16 satellites; the M8 has no cap
  // within the emulator's 10 Hz. apply_chip_settings is what the daemon and batch run.
  const auto cap = [](const std::string& receiver_keys) {
    const Config c = parse(kBase + "[receiver]\n" + receiver_keys);
    protocol::ubx::Device chip(device_setup(c));
    receiver::Receiver rx(c.receiver);
    apply_chip_settings(chip, rx);
    return rx.max_solution_sats();
  };
  EXPECT_EQ(cap("generation = \"m9\"\nrate_hz = 10\n"), 16);
  EXPECT_EQ(cap("generation = \"m9\"\nrate_hz = 8\n"), kMaxSatsInView);
  EXPECT_EQ(cap("generation = \"m8\"\nrate_hz = 10\n"), kMaxSatsInView);
}

TEST(ReceiverSbasConfig, KeyAndHostCfgSbasReachTheReceiver) {
  // [receiver] sbas seeds the chip's CFG-SBAS usage diffCorr; a host's CFG-SBAS
  // (M8) or CFG-SBAS-USE_DIFFCORR (M9) then decides; mode off stops tracking GEOs.
  using protocol::ubx::FrameView;
  using protocol::ubx::Link;
  namespace msg = protocol::ubx::msg;
  const auto state = [](const std::string& keys, protocol::ubx::MsgId id, const std::vector<std::uint8_t>& payload) {
    const Config c = parse(kBase + "[receiver]\n" + keys);
    protocol::ubx::Device chip(device_setup(c));
    std::string out;
    if (!payload.empty()) chip.handle_ubx(Link{}, FrameView{id, payload}, 0.0, out);
    receiver::Receiver rx(c.receiver);
    apply_chip_settings(chip, rx);
    return std::pair{rx.config().sbas, rx.systems().has(GnssSystem::kSbas)};
  };
  const std::vector<std::uint8_t> none;
  EXPECT_EQ(state("", msg::kCfgSbas, none), std::pair(true, true));
  EXPECT_EQ(state("sbas = false\n", msg::kCfgSbas, none), std::pair(false, true));
  EXPECT_EQ(state("", msg::kCfgSbas, {1, 1, 3, 0, 0, 0, 0, 0}), std::pair(false, true));   // ranging only
  EXPECT_EQ(state("", msg::kCfgSbas, {0, 3, 3, 0, 0, 0, 0, 0}), std::pair(false, false));  // SBAS disabled
  EXPECT_EQ(state("sbas = false\n", msg::kCfgSbas, {1, 3, 3, 0, 0, 0, 0, 0}), std::pair(true, true));
  // NEO-M9N: CFG-VALSET (RAM) CFG-SBAS-USE_DIFFCORR = 0, then = 1.
  const std::vector<std::uint8_t> diffcorr_off{0, 1, 0, 0, 0x04, 0x00, 0x36, 0x10, 0};
  const std::vector<std::uint8_t> diffcorr_on{0, 1, 0, 0, 0x04, 0x00, 0x36, 0x10, 1};
  EXPECT_EQ(state("generation = \"m9\"\n", msg::kCfgValset, diffcorr_off), std::pair(false, true));
  EXPECT_EQ(state("generation = \"m9\"\nsbas = false\n", msg::kCfgValset, diffcorr_on), std::pair(true, true));
}

TEST(ReceiverDynamicsConfig, GeodeticProfileSolvesSnapshotsUnlessTheFileSaysOtherwise) {
  EXPECT_EQ(parse(kBase + "[receiver]\nprofile = \"geodetic\"\n").receiver.filter.type,
            receiver::NavFilterType::kNone);
  EXPECT_EQ(parse(kBase + "[receiver]\nprofile = \"geodetic\"\nfilter = \"kalman\"\n").receiver.filter.type,
            receiver::NavFilterType::kKalman);
  EXPECT_EQ(parse(kBase + "[receiver]\nprofile = \"ublox_m8\"\n").receiver.filter.type,
            receiver::NavFilterType::kKalman);
}

TEST(ReceiverDynamicsConfig, BadValuesNameFileAndLine) {
  const Bad cases[] = {
      {"[receiver]\nfilter = \"ekf\"\n", "t.toml:8: receiver.filter: 'ekf' is not \"kalman\" or \"none\""},
      {"[receiver.nav]\ndyn_model = \"car\"\n",
       "t.toml:8: receiver.nav.dyn_model: 'car' is not one of \"portable\", \"stationary\", \"pedestrian\", "
       "\"automotive\", \"sea\", \"airborne1g\", \"airborne2g\", \"airborne4g\", \"wrist\""},
      {"[receiver.nav]\nstatic_hold_thresh_m_s = 3\n",
       "t.toml:8: receiver.nav.static_hold_thresh_m_s: 3 is out of range [0, 2.55] m/s"},
      {"[receiver.nav]\nsmoothing_window_s = 100\ncoast_limit_s = -1\n",
       "t.toml:9: receiver.nav.coast_limit_s: -1 is out of range [0, 600] s"},
      {"[receiver.nav]\ninnovation_gate_sigma = 0\n",
       "t.toml:8: receiver.nav.innovation_gate_sigma: 0 is out of range (0, 100]"},
      {"[receiver.acquisition]\nstart = \"lukewarm\"\n",
       "t.toml:8: receiver.acquisition.start: 'lukewarm' is not one of \"hot\", \"warm\", \"cold\""},
      {"[receiver.acquisition]\nmodelled = 1\n", "t.toml:8: receiver.acquisition.modelled:"},
      {"[receiver.acquisition]\ncold_search_s = 0\n",
       "t.toml:8: receiver.acquisition.cold_search_s: 0 is out of range (0, 600] s"},
      {"[receiver.acquisition]\nsearch_spread = 1\n",
       "t.toml:8: receiver.acquisition.search_spread: 1 is out of range [0, 1)"},
      {"[receiver.limits]\nmax_altitude_m = 0\n",
       "t.toml:8: receiver.limits.max_altitude_m: 0 is out of range (0, 10000000] m"},
      {"[receiver.limits]\nmax_speed_m_s = nan\n",
       "t.toml:8: receiver.limits.max_speed_m_s: must be a finite number, got nan"},
      {"[receiver.limits]\nmax_altitude_km = 50\n", "t.toml:8: unknown key 'receiver.limits.max_altitude_km'"},
  };
  for (const Bad& b : cases) {
    const std::string err = error_of(kBase + b.text);
    EXPECT_NE(err.find(b.message), std::string::npos) << b.text << "\n got: " << err;
  }
}

}  // namespace
}  // namespace gnssemu::config::test::receiver_keys_test

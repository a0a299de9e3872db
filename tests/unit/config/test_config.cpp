// SPDX-License-Identifier: Apache-2.0
// parse_config, load_config, default_config and to_toml (config/config):
// shipped configs load, defaults, every key round-trips through TOML,
// syntax and file errors, and damaged text gives only located errors.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "every_key.hpp"
#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

namespace fs = std::filesystem;

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Exact comparison of every field; angles to 1e-15 rad (deg <-> rad).
void expect_same(const Config& a, const Config& b) {
  EXPECT_NEAR(a.origin.lat_rad, b.origin.lat_rad, 1e-15);
  EXPECT_NEAR(a.origin.lon_rad, b.origin.lon_rad, 1e-15);
  EXPECT_EQ(a.origin.height_m, b.origin.height_m);
  EXPECT_EQ(a.nav_file, b.nav_file);
  EXPECT_EQ(a.rate_hz, b.rate_hz);
  EXPECT_EQ(a.time.mode, b.time.mode);
  EXPECT_EQ(a.time.start, b.time.start);
  EXPECT_EQ(a.time.use_wall_clock_date, b.time.use_wall_clock_date);
  const receiver::ReceiverConfig& ra = a.receiver;
  const receiver::ReceiverConfig& rb = b.receiver;
  const world::WorldConfig& wa = a.world;
  const world::WorldConfig& wb = b.world;
  EXPECT_NEAR(ra.elevation_mask_rad, rb.elevation_mask_rad, 1e-15);
  EXPECT_EQ(wa.seed, wb.seed);
  EXPECT_EQ(wa.errors.thermal_sigma_m, wb.errors.thermal_sigma_m);
  EXPECT_EQ(wa.errors.orbit_clock.sigma_m, wb.errors.orbit_clock.sigma_m);
  EXPECT_EQ(wa.errors.orbit_clock.tau_s, wb.errors.orbit_clock.tau_s);
  EXPECT_EQ(wa.errors.multipath.sigma_m, wb.errors.multipath.sigma_m);
  EXPECT_EQ(wa.errors.multipath.tau_s, wb.errors.multipath.tau_s);
  EXPECT_EQ(wa.errors.gradient.north_m, wb.errors.gradient.north_m);
  EXPECT_EQ(wa.errors.gradient.east_m, wb.errors.gradient.east_m);
  EXPECT_EQ(wa.errors.gradient.north_diurnal_m, wb.errors.gradient.north_diurnal_m);
  EXPECT_EQ(wa.errors.gradient.north_peak_h, wb.errors.gradient.north_peak_h);
  EXPECT_EQ(wa.errors.gradient.east_diurnal_m, wb.errors.gradient.east_diurnal_m);
  EXPECT_EQ(wa.errors.gradient.east_peak_h, wb.errors.gradient.east_peak_h);
  EXPECT_EQ(wa.errors.gradient.process.sigma_m, wb.errors.gradient.process.sigma_m);
  EXPECT_EQ(wa.errors.gradient.process.tau_s, wb.errors.gradient.process.tau_s);
  EXPECT_EQ(wa.errors.doppler_sigma_m_s, wb.errors.doppler_sigma_m_s);
  EXPECT_EQ(wa.clock.bias_s, wb.clock.bias_s);
  EXPECT_EQ(wa.clock.drift_s_s, wb.clock.drift_s_s);
  EXPECT_EQ(wa.clock.drift_noise_s_s_sqrt_s, wb.clock.drift_noise_s_s_sqrt_s);
  EXPECT_EQ(wa.clock.jump_threshold_s, wb.clock.jump_threshold_s);
  EXPECT_EQ(ra.solver.sigma_a_m, rb.solver.sigma_a_m);
  EXPECT_EQ(ra.solver.max_exclusions, rb.solver.max_exclusions);
  EXPECT_EQ(ra.solver.iono_model_fraction, rb.solver.iono_model_fraction);
  EXPECT_EQ(ra.solver.tropo_model_sigma_m, rb.solver.tropo_model_sigma_m);
  EXPECT_EQ(ra.solver.sigma_b_m, rb.solver.sigma_b_m);
  EXPECT_EQ(ra.solver.sigma_range_rate_m_s, rb.solver.sigma_range_rate_m_s);
  EXPECT_EQ(ra.solver.height_hold_sigma_m, rb.solver.height_hold_sigma_m);
  EXPECT_EQ(ra.solver.residual_test_pfa, rb.solver.residual_test_pfa);
  EXPECT_EQ(ra.solver.max_iterations, rb.solver.max_iterations);
  EXPECT_EQ(wa.nominal_cn0_dbhz, wb.nominal_cn0_dbhz);
  EXPECT_EQ(ra.max_pdop, rb.max_pdop);
  EXPECT_EQ(ra.max_channels, rb.max_channels);
  EXPECT_EQ(a.truth.bind_address, b.truth.bind_address);
  EXPECT_EQ(a.truth.port, b.truth.port);
  EXPECT_EQ(a.truth.timeout_s, b.truth.timeout_s);
  EXPECT_EQ(a.truth.max_extrapolation_s, b.truth.max_extrapolation_s);
  EXPECT_EQ(a.demo.enabled, b.demo.enabled);
  EXPECT_EQ(a.demo.radius_m, b.demo.radius_m);
  EXPECT_EQ(a.demo.speed_m_s, b.demo.speed_m_s);
  EXPECT_EQ(a.demo.height_m, b.demo.height_m);
  ASSERT_EQ(a.outputs.size(), b.outputs.size());
  for (std::size_t i = 0; i < a.outputs.size(); ++i) {
    const OutputPortConfig& pa = a.outputs[i];
    const OutputPortConfig& pb = b.outputs[i];
    EXPECT_EQ(pa.name, pb.name);
    EXPECT_EQ(pa.type(), pb.type());
    EXPECT_TRUE(pa.transport == pb.transport);  // path, device, address, port
    EXPECT_EQ(pa.baud, pb.baud);
    EXPECT_EQ(pa.protocols_in, pb.protocols_in);
    EXPECT_EQ(pa.protocols_out, pb.protocols_out);
    EXPECT_EQ(pa.ubx_messages, pb.ubx_messages);
    EXPECT_EQ(pa.nmea_rates, pb.nmea_rates);
    EXPECT_EQ(pa.nmea.version, pb.nmea.version);
    EXPECT_EQ(pa.nmea.course_min_speed_m_s, pb.nmea.course_min_speed_m_s);
    const protocol::nmea::SentenceSet& sa = pa.nmea.sentences;
    const protocol::nmea::SentenceSet& sb = pb.nmea.sentences;
    EXPECT_EQ(sa.has(protocol::nmea::Sentence::kGga), sb.has(protocol::nmea::Sentence::kGga));
    EXPECT_EQ(sa.has(protocol::nmea::Sentence::kRmc), sb.has(protocol::nmea::Sentence::kRmc));
    EXPECT_EQ(sa.has(protocol::nmea::Sentence::kGsa), sb.has(protocol::nmea::Sentence::kGsa));
    EXPECT_EQ(sa.has(protocol::nmea::Sentence::kGsv), sb.has(protocol::nmea::Sentence::kGsv));
    EXPECT_EQ(sa.has(protocol::nmea::Sentence::kVtg), sb.has(protocol::nmea::Sentence::kVtg));
    EXPECT_EQ(sa.has(protocol::nmea::Sentence::kGll), sb.has(protocol::nmea::Sentence::kGll));
    EXPECT_EQ(sa.has(protocol::nmea::Sentence::kGst), sb.has(protocol::nmea::Sentence::kGst));
    EXPECT_EQ(sa.has(protocol::nmea::Sentence::kZda), sb.has(protocol::nmea::Sentence::kZda));
  }
  EXPECT_EQ(a.log.level, b.log.level);
}

// Every key set to a value different from its default.
const std::string kEverything = R"(
[origin]
lat_deg = -33.8568
lon_deg = 151.2153
height_m = 39.5

[nav]
file = "nav/ab422100.18n"

[time]
mode = "lockstep"
start = "2018-07-29T06:30:15.5"
use_wall_clock_date = false

[receiver]
rate_hz = 4
elevation_mask_deg = 12.5
seed = 424242
nominal_cn0_dbhz = 41.5
max_pdop = 8.0
max_channels = 12

[receiver.errors]
thermal_sigma_m = 0.45
doppler_sigma_m_s = 0.07

[receiver.errors.orbit_clock]
sigma_m = 0.8
tau_s = 900

[receiver.errors.multipath]
sigma_m = 0.061145637
tau_s = 1920

[receiver.errors.gradient]
north_m = -0.383278
east_m = -0.134185
north_diurnal_m = 0.471
north_peak_h = 3.8
east_diurnal_m = 0.416
east_peak_h = 6.3
sigma_m = 0.351071
tau_s = 15291.3

[receiver.clock]
bias_s = -2.5e-4
drift_s_s = -1.5e-7
drift_noise_s_s_sqrt_s = 3e-11
jump_threshold_s = 5e-4

[receiver.solver]
sigma_a_m = 0.9
sigma_b_m = 0.45
sigma_range_rate_m_s = 0.08
height_hold_sigma_m = 2.5
residual_test_pfa = 0
max_exclusions = 3
iono_model_fraction = 0.5
tropo_model_sigma_m = 0.3
max_iterations = 8

[truth]
bind = "0.0.0.0"
port = 6001
timeout_s = 1.5
max_extrapolation_s = 0.25

[demo]
enabled = false
radius_m = 120.0
speed_m_s = 13.9
height_m = 2.5

[[output]]
name = "ecu"
type = "pty"
path = "/tmp/gnssemu/ecu"
baud = 115200
nmea_version = "2.3"
sentences = ["GGA", "RMC", "GST", "ZDA"]
course_min_speed_m_s = 0.0

[[output]]
name = "log"
type = "file"
path = "out/run.nmea"
baud = 38400
nmea_version = "4.10"
sentences = ["GSA", "GSV", "VTG", "GLL"]
course_min_speed_m_s = 1.25

[log]
level = "debug"
)";

TEST(ConfigLoad, EveryFieldParsed) {
  const Config c = parse(kEverything);
  EXPECT_NEAR(c.origin.lat_rad, -33.8568 * kDegToRad, 1e-15);
  EXPECT_NEAR(c.origin.lon_rad, 151.2153 * kDegToRad, 1e-15);
  EXPECT_EQ(c.origin.height_m, 39.5);
  EXPECT_EQ(c.nav_file, kData + "/nav/ab422100.18n");
  EXPECT_EQ(c.time.mode, TimeMode::kLockstep);
  ASSERT_TRUE(c.time.start.has_value());
  EXPECT_EQ(*c.time.start, time::GpsTime::from_calendar({2018, 7, 29, 6, 30, 15.5}));
  EXPECT_FALSE(c.time.use_wall_clock_date);
  EXPECT_EQ(c.rate_hz, 4.0);
  const receiver::ReceiverConfig& r = c.receiver;
  const world::WorldConfig& w = c.world;
  EXPECT_NEAR(r.elevation_mask_rad, 12.5 * kDegToRad, 1e-15);
  EXPECT_EQ(w.seed, 424242u);
  EXPECT_EQ(w.nominal_cn0_dbhz, 41.5);
  EXPECT_EQ(r.max_pdop, 8.0);
  EXPECT_EQ(r.max_channels, 12);
  EXPECT_EQ(w.errors.thermal_sigma_m, 0.45);
  EXPECT_EQ(w.errors.doppler_sigma_m_s, 0.07);
  EXPECT_EQ(w.errors.orbit_clock.sigma_m, 0.8);
  EXPECT_EQ(w.errors.orbit_clock.tau_s, 900.0);
  EXPECT_EQ(w.errors.multipath.sigma_m, 0.061145637);
  EXPECT_EQ(w.errors.multipath.tau_s, 1920.0);
  EXPECT_EQ(w.errors.gradient.north_m, -0.383278);
  EXPECT_EQ(w.errors.gradient.east_m, -0.134185);
  EXPECT_EQ(w.errors.gradient.north_diurnal_m, 0.471);
  EXPECT_EQ(w.errors.gradient.north_peak_h, 3.8);
  EXPECT_EQ(w.errors.gradient.east_diurnal_m, 0.416);
  EXPECT_EQ(w.errors.gradient.east_peak_h, 6.3);
  EXPECT_EQ(w.errors.gradient.process.sigma_m, 0.351071);
  EXPECT_EQ(w.errors.gradient.process.tau_s, 15291.3);
  EXPECT_EQ(w.clock.bias_s, -2.5e-4);
  EXPECT_EQ(w.clock.drift_s_s, -1.5e-7);
  EXPECT_EQ(w.clock.drift_noise_s_s_sqrt_s, 3e-11);
  EXPECT_EQ(w.clock.jump_threshold_s, 5e-4);
  EXPECT_EQ(r.solver.sigma_a_m, 0.9);
  EXPECT_EQ(r.solver.sigma_b_m, 0.45);
  EXPECT_EQ(r.solver.sigma_range_rate_m_s, 0.08);
  EXPECT_EQ(r.solver.height_hold_sigma_m, 2.5);
  EXPECT_EQ(r.solver.residual_test_pfa, 0.0);
  EXPECT_EQ(r.solver.max_exclusions, 3);
  EXPECT_EQ(r.solver.iono_model_fraction, 0.5);
  EXPECT_EQ(r.solver.tropo_model_sigma_m, 0.3);
  EXPECT_EQ(r.solver.max_iterations, 8);
  EXPECT_EQ(c.truth.bind_address, "0.0.0.0");
  EXPECT_EQ(c.truth.port, 6001);
  EXPECT_EQ(c.truth.timeout_s, 1.5);
  EXPECT_EQ(c.truth.max_extrapolation_s, 0.25);
  EXPECT_FALSE(c.demo.enabled);
  EXPECT_EQ(c.demo.radius_m, 120.0);
  EXPECT_EQ(c.demo.speed_m_s, 13.9);
  EXPECT_EQ(c.demo.height_m, 2.5);
  ASSERT_EQ(c.outputs.size(), 2u);
  const OutputPortConfig& a = c.outputs[0];
  EXPECT_EQ(a.name, "ecu");
  EXPECT_EQ(a.type(), PortType::kPty);
  EXPECT_EQ(std::get<PtyPortConfig>(a.transport).path, "/tmp/gnssemu/ecu");
  EXPECT_EQ(a.baud, 115200u);
  EXPECT_EQ(a.nmea.version, protocol::nmea::NmeaVersion::k23);
  EXPECT_EQ(a.nmea.course_min_speed_m_s, 0.0);
  EXPECT_TRUE(a.nmea.sentences.has(protocol::nmea::Sentence::kGga) && a.nmea.sentences.has(protocol::nmea::Sentence::kRmc) && a.nmea.sentences.has(protocol::nmea::Sentence::kGst) && a.nmea.sentences.has(protocol::nmea::Sentence::kZda));
  EXPECT_FALSE(a.nmea.sentences.has(protocol::nmea::Sentence::kGsa) || a.nmea.sentences.has(protocol::nmea::Sentence::kGsv) || a.nmea.sentences.has(protocol::nmea::Sentence::kVtg) || a.nmea.sentences.has(protocol::nmea::Sentence::kGll));
  const OutputPortConfig& b = c.outputs[1];
  EXPECT_EQ(b.name, "log");
  EXPECT_EQ(b.type(), PortType::kFile);
  EXPECT_EQ(std::get<FilePortConfig>(b.transport).path, kData + "/out/run.nmea");  // resolved against the config's folder
  EXPECT_EQ(b.baud, 38400u);
  EXPECT_EQ(b.nmea.version, protocol::nmea::NmeaVersion::k410);
  EXPECT_EQ(b.nmea.course_min_speed_m_s, 1.25);
  EXPECT_TRUE(b.nmea.sentences.has(protocol::nmea::Sentence::kGsa) && b.nmea.sentences.has(protocol::nmea::Sentence::kGsv) && b.nmea.sentences.has(protocol::nmea::Sentence::kVtg) && b.nmea.sentences.has(protocol::nmea::Sentence::kGll));
  EXPECT_FALSE(b.nmea.sentences.has(protocol::nmea::Sentence::kGga) || b.nmea.sentences.has(protocol::nmea::Sentence::kRmc) || b.nmea.sentences.has(protocol::nmea::Sentence::kGst) || b.nmea.sentences.has(protocol::nmea::Sentence::kZda));
  EXPECT_EQ(c.log.level, "debug");
}

TEST(ConfigLoad, MinimalConfigTakesStructDefaults) {
  const Config c = parse(kBase);
  Config d;
  d.origin = c.origin;
  d.nav_file = c.nav_file;
  expect_same(c, d);
  EXPECT_FALSE(c.time.start.has_value());
  EXPECT_TRUE(c.outputs.empty());
}

TEST(ConfigLoad, RoundTripEveryField) {
  const Config c = parse(kEverything);
  const std::string text = to_toml(c, kData);
  // Paths under the folder are written relative to it.
  EXPECT_NE(text.find("file = \"nav/ab422100.18n\""), std::string::npos) << text;
  EXPECT_NE(text.find("path = \"out/run.nmea\""), std::string::npos) << text;
  const Config back = parse_config(text, "written.toml", kData);
  expect_same(c, back);
  // Written without a folder: absolute paths, still the same config.
  expect_same(c, parse_config(to_toml(c), "abs.toml", "/"));
  // A second pass is a fixed point of the text.
  EXPECT_EQ(to_toml(back, kData), text);
}

TEST(ConfigLoad, RoundTripAnglesExact) {
  const Config c = parse(kEverything);
  const Config back = parse(to_toml(c, kData));
  EXPECT_EQ(back.origin.lat_rad, c.origin.lat_rad);
  EXPECT_EQ(back.origin.lon_rad, c.origin.lon_rad);
  EXPECT_EQ(back.receiver.elevation_mask_rad, c.receiver.elevation_mask_rad);
}

TEST(ConfigLoad, RoundTripOddValues) {
  Config c = parse(kBase);
  c.time.start = time::GpsTime(2190, 561600.000001);
  c.time.use_wall_clock_date = false;
  c.world.seed = 9223372036854775807ull;
  c.rate_hz = 1.0 / 0.3;
  c.origin.lat_rad = 0.1;
  c.truth.bind_address = "::";
  c.outputs.push_back({});
  c.outputs[0].name = "q\"uote";
  std::get<PtyPortConfig>(c.outputs[0].transport).path = "/tmp/dir with space/\\back";
  const Config back = parse(to_toml(c));
  expect_same(c, back);
  EXPECT_EQ(back.time.start->tow_s(), 561600.000001);
}

TEST(ConfigLoad, SeedBeyondTomlIntegersThrows) {
  Config c = parse(kBase);
  c.world.seed = 9223372036854775808ull;
  EXPECT_THROW(to_toml(c), Error);
}

TEST(ConfigLoad, DefaultTomlLoads) {
  const std::string path = kSource + "/config/default.toml";
  const Config c = load_config(path);
  EXPECT_EQ(c.source, path);
  EXPECT_EQ(c.nav_file, kSource + "/config/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz");
  EXPECT_NEAR(c.origin.lat_rad * kRadToDeg, 48.8738, 1e-12);
  EXPECT_NEAR(c.origin.lon_rad * kRadToDeg, 2.2950, 1e-12);
  EXPECT_EQ(c.rate_hz, 1.0);
  EXPECT_EQ(c.time.mode, TimeMode::kRealtime);
  EXPECT_FALSE(c.time.start.has_value());
  EXPECT_TRUE(c.demo.enabled);
  ASSERT_EQ(c.outputs.size(), 1u);
  EXPECT_EQ(c.outputs[0].type(), PortType::kPty);
  EXPECT_EQ(std::get<PtyPortConfig>(c.outputs[0].transport).path.rfind("/tmp/gnssemu/", 0), 0u);
  // The shipped defaults are the struct defaults and the M8 profile (one source of truth).
  ASSERT_TRUE(c.profile.has_value());
  EXPECT_EQ(*c.profile, pipeline::ReceiverProfile::kUbloxM8);
  Config d = struct_defaults_as_shipped(c);
  d.origin = c.origin;
  d.nav_file = c.nav_file;
  d.outputs = c.outputs;
  expect_same(c, d);
}

TEST(ConfigLoad, EmbeddedDefaultIsTheShippedFile) {
  EXPECT_EQ(std::string(default_config_text()), read_file(kSource + "/config/default.toml"));
  EXPECT_EQ(fs::path(default_config_dir()), fs::path(kSource + "/config"));
  const Config c = default_config();
  EXPECT_EQ(c.source, "");
  expect_same(c, load_config(kSource + "/config/default.toml"));
}

TEST(ConfigLoad, EmbeddedDefaultWithOtherFolder) {
  // The nav path is relative, so the folder decides which file is used.
  const std::string nav = "nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz";
  const fs::path other = fs::temp_directory_path() / ("gnssemu-default-" + std::to_string(::getpid()));
  fs::create_directories(other / "nav");
  fs::copy_file(kSource + "/config/" + nav, other / nav, fs::copy_options::overwrite_existing);
  const Config c = default_config(other.string());
  EXPECT_EQ(c.nav_file, (other / nav).string());
  fs::remove_all(other);
  try {
    default_config("/nonexistent");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "default.toml (built in):11: nav.file: '" + nav + "' not found (tried /nonexistent/" + nav + ")");
  }
}

TEST(ConfigLoad, EveryExampleLoadsAndRoundTrips) {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(kSource + "/config/examples")) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    const Config c = load_config(entry.path().string());
    EXPECT_EQ(c.source, entry.path().string());
    std::size_t ports = 0;  // every example opens a port, in whichever form
    for (const VehicleConfig& v : resolve_vehicles(c)) {
      for (const VehicleReceiverConfig& r : v.receivers) ports += r.outputs.size();
    }
    EXPECT_GT(ports, 0u);
    const std::string dir = entry.path().parent_path().string();
    expect_same(c, parse_config(to_toml(c, dir), "rt.toml", dir));
    EXPECT_EQ(to_toml(parse_config(to_toml(c, dir), "rt.toml", dir), dir), to_toml(c, dir));
    ++n;
  }
  EXPECT_GE(n, 2);
}

TEST(ConfigLoad, RelativePathFromWorkingDirectory) {
  // load_config("x.toml") resolves against "." -> the current directory.
  const fs::path old = fs::current_path();
  fs::current_path(kSource + "/config");
  Config c;
  EXPECT_NO_THROW(c = load_config("default.toml"));
  fs::current_path(old);
  EXPECT_EQ(c.nav_file, kSource + "/config/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz");
}

TEST(ConfigLoad, RoundTripEveryKeyAndTheDefaults) {
  // to_toml writes every key (ConfigKeys.EveryKeyIsReadWrittenAndDocumented)
  // with text that reads back to the same value, so equal texts are equal
  // configurations.
  for (const std::string& text : {kEveryKey, kOtherKeys, kBase}) {
    const Config c = parse(text);
    const std::string written = to_toml(c, kData);
    const Config back = parse_config(written, "written.toml", kData);
    expect_same(c, back);
    EXPECT_EQ(to_toml(back, kData), written);
  }
  const Config d = default_config();
  EXPECT_EQ(to_toml(parse_config(to_toml(d, default_config_dir()), "d.toml", default_config_dir()), default_config_dir()),
            to_toml(d, default_config_dir()));
}

TEST(ConfigValidation, BaseLoads) {
  const Config c = parse(kBase);
  EXPECT_EQ(c.source, "t.toml");
  EXPECT_NEAR(c.origin.lat_rad * kRadToDeg, 48.8738, 1e-12);
  EXPECT_NEAR(c.origin.lon_rad * kRadToDeg, 2.2950, 1e-12);
  EXPECT_EQ(c.origin.height_m, 100.0);
  EXPECT_EQ(c.nav_file, kData + "/nav/brdc0010.22n");
}

TEST(ConfigValidation, SyntaxErrorNamesLine) {
  const std::string msg = error_of(kBase + "[receiver]\nrate_hz = = 1\n");
  EXPECT_TRUE(starts_with(msg, "t.toml:8: TOML syntax error: ")) << msg;
}

TEST(ConfigValidation, DuplicateKeyIsSyntaxError) {
  const std::string msg = error_of(kBase + "[receiver]\nseed = 1\nseed = 2\n");
  EXPECT_TRUE(starts_with(msg, "t.toml:9: TOML syntax error: ")) << msg;
}

TEST(ConfigValidation, UnterminatedStringIsSyntaxError) {
  const std::string msg = error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\n[nav]\nfile = \"nav/x\n");
  EXPECT_TRUE(starts_with(msg, "t.toml:6: TOML syntax error: ")) << msg;
}

TEST(ConfigValidation, EmptyText) {
  EXPECT_EQ(error_of(""), "t.toml: missing required table 'origin' at top level");
}

TEST(ConfigValidation, ByteOrderMarkAccepted) {
  EXPECT_NO_THROW(parse("\xEF\xBB\xBF" + kBase));
}

TEST(ConfigValidation, BadUtf8IsSyntaxError) {
  const std::string msg = error_of(kBase + "[log]\nlevel = \"\xFF\"\n");
  EXPECT_TRUE(starts_with(msg, "t.toml:8: TOML syntax error: ")) << msg;
}

TEST(ConfigValidation, LoadMissingFile) {
  try {
    load_config("/nonexistent/gnssemu.toml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/gnssemu.toml: cannot open config file");
  }
}

TEST(ConfigValidation, LoadFolder) {
  try {
    load_config(kData);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), kData + ": is a folder, not a config file");
  }
}

TEST(ConfigMutations, OnlyLocatedErrors) {
  std::ifstream in(kSource + "/config/default.toml");
  std::ostringstream s;
  s << in.rdbuf();
  const std::string original = s.str();
  // Relative nav path must resolve: parse against the config/ folder.
  const std::string dir = kSource + "/config";
  const std::string alphabet = "=[]\"'.,#\n 0123456789-+eE_abcxyz{}";
  std::mt19937_64 rng(12345);
  int loaded = 0;
  int errors = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    std::string text = original;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int k = 0; k < edits; ++k) {
      const std::size_t pos = rng() % text.size();
      switch (rng() % 3) {
        case 0: text.erase(pos, 1 + rng() % 4); break;
        case 1: text.insert(pos, 1, alphabet[rng() % alphabet.size()]); break;
        default: text[pos] = alphabet[rng() % alphabet.size()]; break;
      }
    }
    const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
    try {
      parse_config(text, "t.toml", dir);
      ++loaded;
    } catch (const Error& e) {
      ++errors;
      ASSERT_EQ(e.file(), "t.toml") << e.what();
      ASSERT_LE(e.line(), lines) << e.what() << "\n" << text;
      ASSERT_EQ(std::string(e.what()).rfind("t.toml", 0), 0u);
    }
  }
  // Most single-character damage is caught; comments and values absorb some.
  EXPECT_GT(errors, 1000);
  EXPECT_GT(loaded, 100);
}

}  // namespace
}  // namespace gnssemu::config::test

// One test per validation rule; each asserts the exact "file:line: reason".
#include <cmath>

#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

TEST(ConfigValidation, BaseLoads) {
  const Config c = parse(kBase);
  EXPECT_EQ(c.source, "t.toml");
  EXPECT_NEAR(c.origin.lat_rad * kRadToDeg, 48.8738, 1e-12);
  EXPECT_NEAR(c.origin.lon_rad * kRadToDeg, 2.2950, 1e-12);
  EXPECT_EQ(c.origin.height_m, 100.0);
  EXPECT_EQ(c.nav_file, kData + "/nav/brdc0010.22n");
}

// --- TOML syntax -----------------------------------------------------------

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

// --- unknown keys ----------------------------------------------------------

TEST(ConfigValidation, UnknownTopLevelTable) {
  EXPECT_EQ(error_of(kBase + "[recevier]\nseed = 1\n"),
            "t.toml:7: unknown key 'recevier' (did you mean 'receiver'?)");
}

TEST(ConfigValidation, UnknownTopLevelKey) {
  EXPECT_EQ(error_of("verbose = true\n" + kBase), "t.toml:1: unknown key 'verbose'");
}

TEST(ConfigValidation, UnknownKeyInTable) {
  EXPECT_EQ(error_of(kBase + "[receiver]\nseed = 3\nrate_hx = 2\n"),
            "t.toml:9: unknown key 'receiver.rate_hx' (did you mean 'rate_hz'?)");
}

TEST(ConfigValidation, UnknownKeyInOrigin) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\nalt_m = 3\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:5: unknown key 'origin.alt_m'");
}

TEST(ConfigValidation, UnknownKeyInNestedTable) {
  EXPECT_EQ(error_of(kBase + "[receiver.errors.orbit_clock]\nsigma_m = 1\ntau = 60\n"),
            "t.toml:9: unknown key 'receiver.errors.orbit_clock.tau' (did you mean 'tau_s'?)");
}

TEST(ConfigValidation, FirstUnknownKeyInFileOrder) {
  // std::map order would report "aaa" first; the file order reports "zzz".
  EXPECT_EQ(error_of(kBase + "[demo]\nzzz = 1\naaa = 2\n"), "t.toml:8: unknown key 'demo.zzz'");
}

TEST(ConfigValidation, TypoInSecondOutput) {
  const std::string text = kBase +
                           "[[output]]\n"                     // 7
                           "name = \"a\"\n"                   // 8
                           "path = \"/tmp/gnssemu/a\"\n"      // 9
                           "[[output]]\n"                     // 10
                           "name = \"b\"\n"                   // 11
                           "path = \"/tmp/gnssemu/b\"\n"      // 12
                           "sentence = [\"GGA\"]\n";          // 13
  EXPECT_EQ(error_of(text), "t.toml:13: unknown key 'output[1].sentence' (did you mean 'sentences'?)");
}

// --- wrong types -----------------------------------------------------------

TEST(ConfigValidation, StringWhereNumberExpected) {
  EXPECT_EQ(error_of(kBase + "[receiver]\nrate_hz = \"5\"\n"),
            "t.toml:8: receiver.rate_hz: expected a number, got a string");
}

TEST(ConfigValidation, FloatWhereIntegerExpected) {
  EXPECT_EQ(error_of(kBase + "[truth]\nport = 5500.0\n"),
            "t.toml:8: truth.port: expected an integer, got a float (5500)");
  EXPECT_EQ(error_of(kBase + "[receiver]\n\nseed = 1.5\n"),
            "t.toml:9: receiver.seed: expected an integer, got a float (1.5)");
  EXPECT_EQ(error_of(kBase + "[receiver]\nmax_channels = 12.0\n"),
            "t.toml:8: receiver.max_channels: expected an integer, got a float (12)");
}

TEST(ConfigValidation, IntegerForFloatKeyIsFine) {
  const Config c = parse(kBase + "[receiver]\nrate_hz = 5\nelevation_mask_deg = 10\n");
  EXPECT_EQ(c.rate_hz, 5.0);
  EXPECT_NEAR(c.receiver.elevation_mask_rad, 10.0 * kDegToRad, 1e-15);
}

TEST(ConfigValidation, StringWhereBooleanExpected) {
  EXPECT_EQ(error_of(kBase + "[demo]\nenabled = \"yes\"\n"),
            "t.toml:8: demo.enabled: expected true or false, got a string");
}

TEST(ConfigValidation, NumberWhereStringExpected) {
  EXPECT_EQ(error_of(kBase + "[log]\nlevel = 3\n"), "t.toml:8: log.level: expected a string, got an integer");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nnmea_version = 4.11\n"),
            "t.toml:10: output[0].nmea_version: expected a string, got a float");
}

TEST(ConfigValidation, ValueWhereTableExpected) {
  EXPECT_EQ(error_of("receiver = 5\n" + kBase),
            "t.toml:1: receiver: expected a table ([receiver]), got an integer");
}

TEST(ConfigValidation, TableWhereArrayOfTablesExpected) {
  EXPECT_EQ(error_of(kBase + "[output]\nname = \"a\"\n"),
            "t.toml:7: output: expected an array of tables ([[output]]), got a table");
}

TEST(ConfigValidation, SentencesNotAnArray) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nsentences = \"GGA\"\n"),
            "t.toml:10: output[0].sentences: expected an array of strings, got a string");
}

// --- non-finite ------------------------------------------------------------

TEST(ConfigValidation, NanRejected) {
  EXPECT_EQ(error_of(kBase + "[receiver]\nrate_hz = nan\n"),
            "t.toml:8: receiver.rate_hz: must be a finite number, got nan");
}

TEST(ConfigValidation, InfRejected) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = -inf\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:4: origin.height_m: must be a finite number, got -inf");
  EXPECT_EQ(error_of(kBase + "[receiver.errors]\nthermal_sigma_m = +inf\n"),
            "t.toml:8: receiver.errors.thermal_sigma_m: must be a finite number, got inf");
}

// --- ranges ----------------------------------------------------------------

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

TEST(ConfigValidation, LatitudeOutsidePlusMinus90) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 90.5\nlon_deg = 2\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:2: origin.lat_deg: 90.5 is out of range [-90, 90] deg");
  EXPECT_EQ(error_of("[origin]\nlat_deg = -91\nlon_deg = 2\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:2: origin.lat_deg: -91 is out of range [-90, 90] deg");
  const Config pole = parse("[origin]\nlat_deg = -90\nlon_deg = 0\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n");
  EXPECT_EQ(pole.origin.lat_rad, -kPi / 2.0);
}

TEST(ConfigValidation, LongitudeOutsidePlusMinus180) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 180.25\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:3: origin.lon_deg: 180.25 is out of range [-180, 180] deg");
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = -181\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:3: origin.lon_deg: -181 is out of range [-180, 180] deg");
  // -180 is the antimeridian; Lla keeps longitude in (-pi, pi].
  const Config c = parse("[origin]\nlat_deg = 1\nlon_deg = -180\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n");
  EXPECT_EQ(c.origin.lon_rad, kPi);
}

TEST(ConfigValidation, HeightOutOfRange) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 6378137\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:4: origin.height_m: 6378137 is out of range [-1000, 50000] m");
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

TEST(ConfigValidation, InlineTablesAreChecked) {
  EXPECT_EQ(error_of(kBase + "[receiver.errors]\norbit_clock = { sigma_m = 1, tau_s = 0 }\n"),
            "t.toml:8: receiver.errors.orbit_clock.tau_s: 0 is out of range (0, 1000000] s");
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
            "t.toml:8: receiver.max_channels: 3 is out of range [4, 32]");
  EXPECT_EQ(error_of(kBase + "[receiver]\nseed = -1\n"),
            "t.toml:8: receiver.seed: -1 is out of range [0, 9223372036854775807]");
  EXPECT_EQ(error_of(kBase + "[receiver]\nmax_pdop = 0.5\n"),
            "t.toml:8: receiver.max_pdop: 0.5 is out of range [1, 1000]");
  EXPECT_EQ(error_of(kBase + "[receiver]\nnominal_cn0_dbhz = 70\n"),
            "t.toml:8: receiver.nominal_cn0_dbhz: 70 is out of range [10, 60] dB-Hz");
}

TEST(ConfigValidation, CoreRangesAreTheConfigRanges) {
  // One range per setting, owned by the core: what the file accepts, the
  // receiver accepts; what the receiver rejects is named at its file:line.
  EXPECT_EQ(error_of(kBase + "[receiver]\nmax_channels = 40\n"),
            "t.toml:8: receiver.max_channels: 40 is out of range [4, 32]");
  EXPECT_EQ(parse(kBase + "[receiver]\nmax_channels = 32\n").receiver.max_channels, 32);
  EXPECT_EQ(error_of(kBase + "[receiver.solver]\nresidual_test_pfa = 0.7\n"),
            "t.toml:8: receiver.solver.residual_test_pfa: 0.7 is out of range [0, 0.5)");
}

TEST(ConfigValidation, PortOutside16Bits) {
  EXPECT_EQ(error_of(kBase + "[truth]\nport = 65536\n"), "t.toml:8: truth.port: 65536 is out of range [0, 65535]");
  EXPECT_EQ(error_of(kBase + "[truth]\nport = -1\n"), "t.toml:8: truth.port: -1 is out of range [0, 65535]");
  EXPECT_EQ(parse(kBase + "[truth]\nport = 0\n").truth.port, 0);
  EXPECT_EQ(parse(kBase + "[truth]\nport = 65535\n").truth.port, 65535);
}

TEST(ConfigValidation, TruthTimes) {
  EXPECT_EQ(error_of(kBase + "[truth]\ntimeout_s = 0\n"), "t.toml:8: truth.timeout_s: 0 is out of range (0, 60] s");
  EXPECT_EQ(error_of(kBase + "[truth]\ntimeout_s = 1\nmax_extrapolation_s = 1.5\n"),
            "t.toml:9: truth.max_extrapolation_s: 1.5 s exceeds truth.timeout_s (1 s)");
}

TEST(ConfigValidation, TimeoutBelowTheDefaultExtrapolation) {
  // Only timeout_s given: the rule points at it (the other key is absent).
  EXPECT_EQ(error_of(kBase + "[truth]\ntimeout_s = 0.25\n"),
            "t.toml:8: truth.max_extrapolation_s: 0.5 s exceeds truth.timeout_s (0.25 s)");
  EXPECT_EQ(error_of(kBase + "[truth]\n\nmax_extrapolation_s = 0.4\ntimeout_s = 0.25\n"),
            "t.toml:9: truth.max_extrapolation_s: 0.4 s exceeds truth.timeout_s (0.25 s)");
  EXPECT_EQ(parse(kBase + "[truth]\ntimeout_s = 0.5\n").truth.timeout_s, 0.5);
}

TEST(ConfigValidation, BindNotAnAddress) {
  EXPECT_EQ(error_of(kBase + "[truth]\nbind = \"localhost\"\n"),
            "t.toml:8: truth.bind: 'localhost' is not an IPv4 or IPv6 address");
  EXPECT_EQ(parse(kBase + "[truth]\nbind = \"::1\"\n").truth.bind_address, "::1");
  EXPECT_EQ(parse(kBase + "[truth]\nbind = \"0.0.0.0\"\n").truth.bind_address, "0.0.0.0");
}

TEST(ConfigValidation, DemoRanges) {
  EXPECT_EQ(error_of(kBase + "[demo]\nradius_m = 0\n"), "t.toml:8: demo.radius_m: 0 is out of range (0, 100000] m");
  EXPECT_EQ(error_of(kBase + "[demo]\nspeed_m_s = -1\n"), "t.toml:8: demo.speed_m_s: -1 is out of range [0, 500] m/s");
}

// --- outputs ---------------------------------------------------------------

TEST(ConfigValidation, BaudNotStandard) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nbaud = 9601\n"),
            "t.toml:10: output[0].baud: 9601 is not a standard rate "
            "(4800 9600 19200 38400 57600 115200 230400 460800 921600)");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nbaud = 0\n"),
            "t.toml:10: output[0].baud: 0 is out of range [1, 4294967295]");
  EXPECT_EQ(parse(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nbaud = 115200\n").outputs.at(0).baud, 115200u);
}

TEST(ConfigValidation, UnknownSentence) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nsentences = [\"GGA\",\n  \"GGX\"]\n"),
            "t.toml:11: output[0].sentences: unknown sentence 'GGX' (known: GGA RMC GSA GSV VTG GLL GST ZDA)");
}

TEST(ConfigValidation, SentenceListedTwiceOrEmpty) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nsentences = [\"GGA\", \"GGA\"]\n"),
            "t.toml:10: output[0].sentences: 'GGA' listed twice");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nsentences = []\n"),
            "t.toml:10: output[0].sentences: must name at least one sentence");
}

TEST(ConfigValidation, UnknownNmeaVersion) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nnmea_version = \"4.0\"\n"),
            "t.toml:10: output[0].nmea_version: '4.0' is not one of \"2.3\", \"4.10\", \"4.11\"");
}

TEST(ConfigValidation, UnknownPortType) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\ntype = \"usb\"\npath = \"/tmp/a\"\n"),
            "t.toml:9: output[0].type: 'usb' is not one of \"pty\", \"serial\", \"tcp\", \"udp\", \"file\"");
}

TEST(ConfigValidation, DuplicateOutputName) {
  const std::string text = kBase +
                           "[[output]]\nname = \"gps0\"\npath = \"/tmp/gnssemu/a\"\n"  // 7-9
                           "[[output]]\nname = \"gps0\"\npath = \"/tmp/gnssemu/b\"\n";  // 10-12
  EXPECT_EQ(error_of(text), "t.toml:11: output[1].name: 'gps0' is used twice");
}

TEST(ConfigValidation, DuplicateOutputPath) {
  const std::string text = kBase +
                           "[[output]]\nname = \"a\"\npath = \"/tmp/gnssemu/gps0\"\n"  // 7-9
                           "[[output]]\nname = \"b\"\npath = \"/tmp/gnssemu/gps0\"\n";  // 10-12
  EXPECT_EQ(error_of(text), "t.toml:12: output[1].path: '/tmp/gnssemu/gps0' is already used by output 'a'");
}

TEST(ConfigValidation, DuplicateFilePathAfterResolution) {
  const std::string text = kBase +
                           "[[output]]\nname = \"a\"\ntype = \"file\"\npath = \"out/x.nmea\"\n"         // 7-10
                           "[[output]]\nname = \"b\"\ntype = \"file\"\npath = \"out/../out/x.nmea\"\n";  // 11-14
  EXPECT_EQ(error_of(text),
            "t.toml:14: output[1].path: '" + kData + "/out/x.nmea' is already used by output 'a'");
}

TEST(ConfigValidation, RelativePtyPathRejected) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"gps0\"\n"),
            "t.toml:9: output[0].path: pty path 'gps0' must be absolute");
}

TEST(ConfigValidation, OutputNameChecks) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"\"\npath = \"/tmp/a\"\n"),
            "t.toml:8: output[0].name: must not be empty");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"gps 0\"\npath = \"/tmp/a\"\n"),
            "t.toml:8: output[0].name: 'gps 0' contains a space or control character");
}

// --- missing keys ----------------------------------------------------------

TEST(ConfigValidation, MissingKeyNamesItsTable) {
  EXPECT_EQ(error_of("[nav]\nfile = \"nav/brdc0010.22n\"\n\n[origin]\nlat_deg = 1\nheight_m = 0\n"),
            "t.toml:4: missing required key 'origin.lon_deg' in [origin]");
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\n[nav]\n"),
            "t.toml:5: missing required key 'nav.file' in [nav]");
}

TEST(ConfigValidation, MissingKeyInOutput) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\n[[output]]\npath = \"/tmp/b\"\n"),
            "t.toml:7: missing required key 'output[0].path' in [output[0]]");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\n[[output]]\npath = \"/tmp/b\"\n"),
            "t.toml:10: missing required key 'output[1].name' in [output[1]]");
}

TEST(ConfigValidation, MissingTable) {
  EXPECT_EQ(error_of("[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml: missing required table 'origin' at top level");
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\n"),
            "t.toml: missing required table 'nav' at top level");
}

// --- dates and time --------------------------------------------------------

TEST(ConfigValidation, BadDateStrings) {
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-13-01T00:00:00\"\n"),
            "t.toml:8: time.start: bad date-time: month 13 is not 1..12");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-02-29T00:00:00\"\n"),
            "t.toml:8: time.start: bad date-time: day 29 does not exist in 2022-02");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-01-01T24:00:00\"\n"),
            "t.toml:8: time.start: bad date-time: hour 24 is not 0..23");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"1979-12-31T00:00:00\"\n"),
            "t.toml:8: time.start: bad date-time: before the GPS epoch 1980-01-06");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"yesterday\"\n"),
            "t.toml:8: time.start: 'yesterday' is not a GPS date-time YYYY-MM-DDTHH:MM:SS[.fff] (no time zone)");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-01-01T12:00:00Z\"\n"),
            "t.toml:8: time.start: '2022-01-01T12:00:00Z' is not a GPS date-time YYYY-MM-DDTHH:MM:SS[.fff] "
            "(no time zone)");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-01-01T12:00:00.\"\n"),
            "t.toml:8: time.start: '2022-01-01T12:00:00.' is not a GPS date-time YYYY-MM-DDTHH:MM:SS[.fff] "
            "(no time zone)");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = 2022-01-01T12:00:00+01:00\n"),
            "t.toml:8: time.start: GPS time has no time zone; drop the offset");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = 2022-01-01\n"),
            "t.toml:8: time.start: expected a date-time string \"YYYY-MM-DDTHH:MM:SS\", got a date");
}

TEST(ConfigValidation, GoodDates) {
  const time::GpsTime noon = time::GpsTime::from_calendar({2022, 1, 1, 12, 0, 0.0});
  EXPECT_EQ(parse(kBase + "[time]\nstart = \"2022-01-01T12:00:00\"\n").time.start, noon);
  EXPECT_EQ(parse(kBase + "[time]\nstart = \"2022-01-01 12:00:00\"\n").time.start, noon);
  EXPECT_EQ(parse(kBase + "[time]\nstart = 2022-01-01T12:00:00\n").time.start, noon);  // TOML local date-time
  const auto frac = parse(kBase + "[time]\nstart = \"2022-01-01T12:00:00.25\"\n").time.start;
  ASSERT_TRUE(frac.has_value());
  EXPECT_EQ(frac->week(), 2190);
  EXPECT_EQ(frac->tow_s(), 6 * 86400.0 + 12 * 3600.0 + 0.25);
  EXPECT_EQ(parse(kBase + "[time]\nstart = \"2024-02-29T00:00:00\"\n").time.start,
            time::GpsTime::from_calendar({2024, 2, 29, 0, 0, 0.0}));
}

TEST(ConfigValidation, BadTimeMode) {
  EXPECT_EQ(error_of(kBase + "[time]\nmode = \"fast\"\n"),
            "t.toml:8: time.mode: 'fast' is not \"realtime\" or \"lockstep\"");
}

TEST(ConfigValidation, StartAndWallClockExclusive) {
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-01-01T12:00:00\"\nuse_wall_clock_date = true\n"),
            "t.toml:9: time.use_wall_clock_date: cannot be true together with time.start");
}

// --- others ----------------------------------------------------------------

TEST(ConfigValidation, UnknownLogLevel) {
  EXPECT_EQ(error_of(kBase + "[log]\nlevel = \"verbose\"\n"),
            "t.toml:8: log.level: 'verbose' is not one of trace, debug, info, warn, error, critical, off");
}

TEST(ConfigValidation, NavFileNotFoundSaysWhereItLooked) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\n[nav]\nfile = \"nav/missing.22n\"\n"),
            "t.toml:6: nav.file: 'nav/missing.22n' not found (tried " + kData + "/nav/missing.22n)");
  // A folder is not a nav file.
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\n[nav]\nfile = \"nav\"\n"),
            "t.toml:6: nav.file: 'nav' not found (tried " + kData + "/nav)");
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

}  // namespace
}  // namespace gnssemu::config::test

// SPDX-License-Identifier: Apache-2.0
// What the table reader (config/toml_reader) reports for any key: unknown
// keys with a hint, strict types, non-finite numbers, missing keys and
// tables; each assertion pins the exact "file:line: reason".
#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

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

TEST(ConfigValidation, InlineTablesAreChecked) {
  EXPECT_EQ(error_of(kBase + "[receiver.errors]\norbit_clock = { sigma_m = 1, tau_s = 0 }\n"),
            "t.toml:8: receiver.errors.orbit_clock.tau_s: 0 is out of range (0, 1000000] s");
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

}  // namespace
}  // namespace gnssemu::config::test

// [receiver.errors.multipath] and [receiver.errors.gradient] (the terms
// `gnssemu calibrate` fits): bad values name file:line, defaults are off.
#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

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

}  // namespace
}  // namespace gnssemu::config::test

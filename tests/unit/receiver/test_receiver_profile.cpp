// SPDX-License-Identifier: Apache-2.0
// Receiver profiles: names, the C/N0 and code noise each claims (its
// evidence in docs/models.md), the mirrored gradient south of the equator.
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/error.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/pipeline/receiver_profile.hpp"
#include "core/signal/dll_jitter.hpp"
#include "core/signal/link_budget.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::pipeline {
namespace {

constexpr double kZenithRange_m = 20.2e6;  // GPS at the zenith
constexpr double kLat = 45.0 * kDegToRad;

TEST(ReceiverProfile, NamesReadBackAndUnknownNamesAreErrors) {
  for (ReceiverProfile p : {ReceiverProfile::kUbloxM8, ReceiverProfile::kGeodetic})
    EXPECT_EQ(receiver_profile(profile_name(p)), p);
  try {
    receiver_profile("zed_f9p");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ublox_m8, geodetic"), std::string::npos) << e.what();
  }
}

TEST(ReceiverProfile, CarrierToNoiseOfEachDevice) {
  // Geodetic: the stations' S1C fit (53.3 dB-Hz at the zenith, 18.5 dB less
  // at the horizon with its longer range); u-blox M8: the NEO-M8N log (43.0, -13.7).
  struct Case {
    ReceiverProfile p;
    double zenith_dbhz, horizon_drop_db;
  };
  for (const Case& c : {Case{ReceiverProfile::kGeodetic, 53.3, -18.5}, Case{ReceiverProfile::kUbloxM8, 43.0, -13.7}}) {
    const PipelineConfig pc = apply_profile(PipelineConfig{}, c.p, kLat);
    const signal::LinkBudgetModel link(pc.world.signal.link);
    const double z = link.cn0_dbhz(kZenithRange_m, kPi / 2.0, 0.0);
    const double h = link.cn0_dbhz(25.8e6, 0.0, 0.0);  // slant range at the horizon
    EXPECT_NEAR(z, c.zenith_dbhz, 0.3) << profile_name(c.p);
    EXPECT_NEAR(h - z, c.horizon_drop_db, 0.5) << profile_name(c.p);
  }
}

TEST(ReceiverProfile, M8CodeNoiseIsWhatTheM8Reports) {
  // NEO-M8T RXM-RAWX prStdev: 0.32 m at 42-51 dB-Hz, 2.3 m at 30 dB-Hz.
  const PipelineConfig pc = apply_profile(PipelineConfig{}, ReceiverProfile::kUbloxM8, kLat);
  EXPECT_NEAR(signal::dll_thermal_sigma_m(45.0, pc.world.signal.dll), 0.32, 0.03);
  EXPECT_NEAR(signal::dll_thermal_sigma_m(30.0, pc.world.signal.dll), 1.9, 0.5);
}

TEST(ReceiverProfile, SignalsInSpaceAreTheSameForBothAndTheGradientPointsToTheEquator) {
  const PipelineConfig m8 = apply_profile(PipelineConfig{}, ReceiverProfile::kUbloxM8, kLat);
  const PipelineConfig geo = apply_profile(PipelineConfig{}, ReceiverProfile::kGeodetic, kLat);
  EXPECT_EQ(m8.world.errors.orbit_clock.sigma_m, geo.world.errors.orbit_clock.sigma_m);
  EXPECT_EQ(m8.world.errors.iono_scale.sigma, geo.world.errors.iono_scale.sigma);
  EXPECT_EQ(m8.world.atmosphere.ionosphere.klobuchar_scale, geo.world.atmosphere.ionosphere.klobuchar_scale);
  EXPECT_LT(m8.world.errors.gradient.north_m, 0.0);  // fitted at 36-79 N: longer ranges to the south
  const PipelineConfig south = apply_profile(PipelineConfig{}, ReceiverProfile::kUbloxM8, -kLat);
  EXPECT_EQ(south.world.errors.gradient.north_m, -m8.world.errors.gradient.north_m);
  EXPECT_EQ(south.world.errors.gradient.east_m, m8.world.errors.gradient.east_m);
  // Both are valid pipelines.
  const orbit::EphemerisStore store(receiver::test::nominal_constellation(time::GpsTime(2190, 200000.0)));
  EXPECT_NO_THROW(Pipeline(store, m8));
  EXPECT_NO_THROW(Pipeline(store, geo));
}

}  // namespace
}  // namespace gnssemu::pipeline

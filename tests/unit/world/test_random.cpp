// SPDX-License-Identifier: Apache-2.0
// core/world/random: the counter-based generator behind every error process.
#include <gtest/gtest.h>

#include <cstdint>
#include <set>

#include "core/world/random.hpp"

namespace gnssemu::world {
namespace {

TEST(CounterRng, StandardNormalMomentsAndKeyIndependence) {
  const CounterRng rng(99);
  double sum = 0.0, sum2 = 0.0, cross = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double a = rng.normal(3, static_cast<uint64_t>(i), Purpose::kThermal);
    const double b = rng.normal(4, static_cast<uint64_t>(i), Purpose::kThermal);
    sum += a;
    sum2 += a * a;
    cross += a * b;
  }
  // Standard errors: mean 1/sqrt(n) = 0.0022, variance sqrt(2/n) = 0.0032.
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum2 / n, 1.0, 0.015);
  EXPECT_NEAR(cross / n, 0.0, 0.01);
  EXPECT_EQ(rng.normal(3, 17, Purpose::kThermal), CounterRng(99).normal(3, 17, Purpose::kThermal));
  EXPECT_NE(rng.normal(3, 17, Purpose::kThermal), rng.normal(3, 17, Purpose::kDoppler));
  EXPECT_NE(rng.normal(3, 17, Purpose::kThermal), CounterRng(100).normal(3, 17, Purpose::kThermal));
}

TEST(CounterRng, SatelliteStreamsKeepGpsAndSeparateEverySatellite) {
  // GPS draws stay those of the PRN-numbered streams: stream = PRN.
  for (int prn = 1; prn <= system_size(GnssSystem::kGps); ++prn) EXPECT_EQ(sat_stream(SatId::gps(prn)), uint64_t(prn));
  std::set<uint64_t> streams{kClockStream, kGradientStream, kGradientStream + 1, kIonoScaleStream};
  for (int i = 0; i < kNumSats; ++i) EXPECT_TRUE(streams.insert(sat_stream(SatId::from_index(i))).second) << i;
  EXPECT_EQ(sat_stream(SatId(GnssSystem::kGalileo, 11)), 2u * 256u + 11u);
}

}  // namespace
}  // namespace gnssemu::world

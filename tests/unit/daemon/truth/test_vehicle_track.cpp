// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "daemon/truth/vehicle_track.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;

namespace vehicle_track_test {

namespace {

const time::GpsTime kT0(2190, 3600.0);
const TrackParams kParams{2.0, 0.5};

// Vehicle moving +x at 10 m/s from (1000, 0, 0); no velocity in the packets.
VehicleTrack moving_track(int n, double dt_s, bool with_vel = false) {
  VehicleTrack tr;
  for (int i = 0; i < n; ++i) {
    const double s = i * dt_s;
    std::optional<Ecef> vel;
    if (with_vel) vel = Ecef(10.0, 0.0, 0.0);
    EXPECT_EQ(tr.add(s, kT0 + s, Ecef(1000.0 + 10.0 * s, 0.0, 0.0), vel, s),
              VehicleTrack::AddResult::kAdded);
  }
  return tr;
}

}  // namespace

TEST(VehicleTrack, EmptyIsInvalid) {
  VehicleTrack tr;
  EXPECT_FALSE(tr.truth_at(kT0, 0.0, kParams).valid);
  EXPECT_FALSE(tr.fresh(0.0, kParams));
}

TEST(VehicleTrack, InterpolatesPositionAndDerivesVelocity) {
  const VehicleTrack tr = moving_track(5, 0.1);
  const world::Truth t = tr.truth_at(kT0 + 0.25, 0.4, kParams);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.pos_m.x, 1002.5, 1e-9);
  EXPECT_NEAR(t.vel_m_s.x, 10.0, 1e-6);
  EXPECT_NEAR(t.vel_m_s.y, 0.0, 1e-12);
  EXPECT_EQ(t.t, kT0 + 0.25);
  // Exactly on a sample.
  EXPECT_NEAR(tr.truth_at(kT0 + 0.1, 0.4, kParams).pos_m.x, 1001.0, 1e-9);
  EXPECT_NEAR(tr.truth_at(kT0, 0.4, kParams).pos_m.x, 1000.0, 1e-9);
}

TEST(VehicleTrack, InterpolatesGivenVelocity) {
  VehicleTrack tr;
  tr.add(0.0, kT0, Ecef(0, 0, 0), Ecef(0, 0, 0), 0.0);
  tr.add(1.0, kT0 + 1.0, Ecef(5, 0, 0), Ecef(10, 0, 0), 1.0);
  const world::Truth t = tr.truth_at(kT0 + 0.75, 1.0, kParams);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.pos_m.x, 3.75, 1e-12);
  EXPECT_NEAR(t.vel_m_s.x, 7.5, 1e-12);
}

TEST(VehicleTrack, ExtrapolatesBrieflyThenHolds) {
  const VehicleTrack tr = moving_track(5, 0.1);  // newest at +0.4 s, x = 1004
  world::Truth t = tr.truth_at(kT0 + 0.7, 0.8, kParams);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.pos_m.x, 1007.0, 1e-6);  // 0.3 s at 10 m/s
  EXPECT_NEAR(t.vel_m_s.x, 10.0, 1e-6);
  t = tr.truth_at(kT0 + 0.9, 0.9, kParams);  // exactly max_extrapolation_s: still moving
  EXPECT_NEAR(t.pos_m.x, 1009.0, 1e-6);
  EXPECT_NEAR(t.vel_m_s.x, 10.0, 1e-6);
  t = tr.truth_at(kT0 + 1.9, 1.9, kParams);  // 1.5 s past: capped at 0.5 s
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.pos_m.x, 1009.0, 1e-6);
  // Held, not moving: zero velocity, not the last one (pos and vel agree).
  EXPECT_EQ(t.vel_m_s.x, 0.0);
  EXPECT_EQ(t.vel_m_s.y, 0.0);
  EXPECT_EQ(t.vel_m_s.z, 0.0);
  // Given velocity is preferred over differences.
  VehicleTrack tv;
  tv.add(0.0, kT0, Ecef(0, 0, 0), Ecef(0, 3, 0), 0.0);
  t = tv.truth_at(kT0 + 0.2, 0.2, kParams);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.pos_m.y, 0.6, 1e-12);
}

TEST(VehicleTrack, BeforeFirstSample) {
  const VehicleTrack tr = moving_track(3, 0.1);
  world::Truth t = tr.truth_at(kT0 - 0.2, 0.3, kParams);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.pos_m.x, 998.0, 1e-6);
  EXPECT_FALSE(tr.truth_at(kT0 - 0.6, 0.3, kParams).valid);
}

TEST(VehicleTrack, TimeoutMeansNoTruthNotAFrozenPosition) {
  const VehicleTrack tr = moving_track(5, 0.1);  // last arrival at 0.4 s
  EXPECT_TRUE(tr.truth_at(kT0 + 2.4, 2.4, kParams).valid);
  EXPECT_TRUE(tr.fresh(2.4, kParams));
  EXPECT_FALSE(tr.truth_at(kT0 + 2.41, 2.41, kParams).valid);
  EXPECT_FALSE(tr.fresh(2.41, kParams));
  // Even for a time inside the history: the antenna is gone now.
  EXPECT_FALSE(tr.truth_at(kT0 + 0.2, 10.0, kParams).valid);
}

TEST(VehicleTrack, SimTimeMustIncrease) {
  VehicleTrack tr;
  EXPECT_EQ(tr.add(5.0, kT0, Ecef(1, 0, 0), std::nullopt, 0.0), VehicleTrack::AddResult::kAdded);
  EXPECT_EQ(tr.add(5.0, kT0 + 1.0, Ecef(2, 0, 0), std::nullopt, 0.1), VehicleTrack::AddResult::kSimTimeBackwards);
  EXPECT_EQ(tr.add(4.0, kT0 + 1.0, Ecef(2, 0, 0), std::nullopt, 0.1), VehicleTrack::AddResult::kSimTimeBackwards);
  EXPECT_EQ(tr.size(), 1u);
  EXPECT_DOUBLE_EQ(tr.last_arrival_s(), 0.0);
  tr.reset();
  EXPECT_EQ(tr.add(0.0, kT0 + 2.0, Ecef(3, 0, 0), std::nullopt, 2.0), VehicleTrack::AddResult::kAdded);
}

TEST(VehicleTrack, StampNotAfterNewestRestartsHistory) {
  VehicleTrack tr = moving_track(4, 0.1);
  EXPECT_EQ(tr.add(10.0, kT0 + 0.2, Ecef(0, 0, 0), std::nullopt, 1.0), VehicleTrack::AddResult::kRestarted);
  EXPECT_EQ(tr.size(), 1u);
  EXPECT_NEAR(tr.truth_at(kT0 + 0.2, 1.0, kParams).pos_m.x, 0.0, 1e-12);
}

// A step is a jump when it is >= 1 km and >= 10 km/s: 1000 km in 0.1 s is
// one, a 2 km/s rocket's 200 m per packet and a 900 m step in 1 ms are not.
TEST(VehicleTrack, StepsAndJumps) {
  VehicleTrack tr = moving_track(3, 0.1);
  EXPECT_NEAR(tr.last_step().distance_m, 1.0, 1e-9);
  EXPECT_NEAR(tr.last_step().dt_s, 0.1, 1e-9);
  EXPECT_FALSE(tr.last_step().jump());
  const double x = 1000.0 + 10.0 * 0.2;
  EXPECT_EQ(tr.add(0.3, kT0 + 0.3, Ecef(x + 1.0e6, 0.0, 0.0), std::nullopt, 0.3), VehicleTrack::AddResult::kAdded);
  EXPECT_NEAR(tr.last_step().distance_m, 1.0e6, 1e-6);
  EXPECT_TRUE(tr.last_step().jump());
  EXPECT_EQ(tr.add(0.4, kT0 + 0.4, Ecef(x + 1.0e6 + 200.0, 0.0, 0.0), std::nullopt, 0.4),
            VehicleTrack::AddResult::kAdded);
  EXPECT_FALSE(tr.last_step().jump());
  EXPECT_EQ(tr.add(0.401, kT0 + 0.401, Ecef(x + 1.0e6 + 1100.0, 0.0, 0.0), std::nullopt, 0.401),
            VehicleTrack::AddResult::kAdded);
  EXPECT_FALSE(tr.last_step().jump());  // 900 m: under the 1 km floor
  EXPECT_EQ(tr.add(0.5, kT0 + 0.5, Ecef(x + 1.0e6 + 2200.0, 0.0, 0.0), std::nullopt, 0.5),
            VehicleTrack::AddResult::kAdded);
  EXPECT_TRUE(tr.last_step().jump());  // 1.1 km in 99 ms
  // A restarted history has no step before its first sample.
  EXPECT_EQ(tr.add(0.6, kT0, Ecef(0.0, 0.0, 0.0), std::nullopt, 0.6), VehicleTrack::AddResult::kRestarted);
  EXPECT_EQ(tr.last_step().distance_m, 0.0);
  EXPECT_FALSE(tr.last_step().jump());
}

TEST(VehicleTrack, RingKeepsNewestSamples) {
  const int n = static_cast<int>(VehicleTrack::kHistory) + 68;
  const VehicleTrack tr = moving_track(n, 0.1);
  EXPECT_EQ(tr.size(), VehicleTrack::kHistory);
  EXPECT_NEAR(tr.newest().pos_m.x, 1000.0 + (n - 1), 1e-6);
  EXPECT_NEAR(tr.sample(0).pos_m.x, 1000.0 + 68.0, 1e-6);
  // Interpolation deep inside the ring.
  const world::Truth t = tr.truth_at(kT0 + 8.05, (n - 1) * 0.1, kParams);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.pos_m.x, 1080.5, 1e-6);
  // Older than the ring (and beyond extrapolation): invalid.
  EXPECT_FALSE(tr.truth_at(kT0 + 5.0, (n - 1) * 0.1, kParams).valid);
}

TEST(VehicleTrack, HoldsOneSecondAtOneKilohertz) {
  const VehicleTrack tr = moving_track(3000, 1e-3);
  ASSERT_EQ(tr.size(), VehicleTrack::kHistory);
  EXPECT_GE(tr.newest().t - tr.sample(0).t, 1.0);
}

TEST(VehicleTrack, KilohertzVelocityFromABaselineNotOneMillisecond) {
  // 1 kHz, 10 m/s along x, positions rounded to 1 mm as a JSON sender with
  // three decimals sends them; no velocity field.
  VehicleTrack tr;
  for (int i = 0; i < 1000; ++i) {
    const double s = i * 1e-3;
    const double x_m = std::round((1000.0 + 10.0 * s + 0.0004 * ((i * 7919) % 3 - 1)) * 1000.0) / 1000.0;
    ASSERT_EQ(tr.add(s, kT0 + s, Ecef(x_m, 0.0, 0.0), std::nullopt, s), VehicleTrack::AddResult::kAdded);
  }
  double worst_m_s = 0.0;
  for (int k = 100; k < 990; k += 7) {
    const world::Truth t = tr.truth_at(kT0 + k * 1e-3 + 3e-4, 0.999, kParams);
    ASSERT_TRUE(t.valid);
    worst_m_s = std::max(worst_m_s, std::abs(t.vel_m_s.x - 10.0));
  }
  // Over one 1 ms segment a 1 mm step would read 1 m/s off; over 50 ms, 0.04 m/s.
  EXPECT_LT(worst_m_s, 0.05);
  // Extrapolated past the newest sample with that velocity.
  const world::Truth ahead = tr.truth_at(kT0 + 1.099, 1.0, kParams);
  EXPECT_NEAR(ahead.vel_m_s.x, 10.0, 0.05);
}

TEST(VehicleTrack, ClearSamplesKeepsOrdering) {
  VehicleTrack tr = moving_track(3, 0.1);
  tr.clear_samples();
  EXPECT_EQ(tr.size(), 0u);
  EXPECT_FALSE(tr.truth_at(kT0, 0.2, kParams).valid);
  EXPECT_EQ(tr.add(0.1, kT0, Ecef(), std::nullopt, 0.3), VehicleTrack::AddResult::kSimTimeBackwards);
}

}  // namespace vehicle_track_test

// SPDX-License-Identifier: Apache-2.0
// TruthTrack: one interpolation, two end rules. The recorded rule (batch's
// CSV) has no truth outside the samples and gaps at no-truth samples; the
// live rule (the daemon's packets) extrapolates briefly and then holds. Both
// agree inside the samples.
#include <gtest/gtest.h>

#include <vector>

#include "core/world/truth_track.hpp"

namespace gnssemu::world {
namespace {

const time::GpsTime kT0(2190, 604790.0);  // ten seconds before a week rollover

TruthSample at_x(double dt_s, double x_m) {
  TruthSample s;
  s.t = kT0 + dt_s;
  s.pos_m = Ecef(x_m, 0.0, 0.0);
  return s;
}

TEST(TruthTrack, BothRulesInterpolateAlikeInside) {
  const std::vector<TruthSample> s{at_x(0.0, 0.0), at_x(10.0, 100.0), at_x(20.0, 100.0)};
  const TruthTrack recorded(s);
  TruthTrack live(4);
  for (const TruthSample& x : s) live.add(x);
  for (const double dt : {0.0, 2.5, 9.75, 10.0, 12.0, 19.5}) {
    const Truth a = recorded.at(kT0 + dt);
    const Truth b = live.extrapolated(kT0 + dt, 0.5);
    ASSERT_TRUE(a.valid && b.valid) << dt;
    EXPECT_EQ(a.pos_m, b.pos_m) << dt;
    EXPECT_EQ(a.vel_m_s, b.vel_m_s) << dt;
  }
  EXPECT_EQ(recorded.at(kT0 + 2.5).pos_m.x, 25.0);
  EXPECT_EQ(recorded.at(kT0 + 2.5).vel_m_s.x, 10.0);  // the segment's mean velocity
  EXPECT_EQ(recorded.at(kT0 + 15.0).vel_m_s.x, 0.0);
}

TEST(TruthTrack, RecordedTruthEndsAndGaps) {
  std::vector<TruthSample> s{at_x(0.0, 0.0), at_x(1.0, 10.0), at_x(2.0, 20.0), at_x(3.0, 30.0)};
  s[2].valid = false;
  const TruthTrack t(s);
  EXPECT_FALSE(t.at(kT0 - 0.001).valid);
  EXPECT_FALSE(t.at(kT0 + 3.001).valid);
  EXPECT_TRUE(t.at(kT0 + 3.0 + 1e-7).valid);  // rounding at the end is allowed
  EXPECT_TRUE(t.at(kT0 + 1.0).valid);          // the valid end of a gap segment
  EXPECT_FALSE(t.at(kT0 + 1.5).valid);         // inside the gap
  EXPECT_FALSE(t.at(kT0 + 2.5).valid);
  EXPECT_TRUE(t.at(kT0 + 3.0).valid);
  EXPECT_EQ(t.at(kT0 + 3.0).pos_m.x, 30.0);
}

TEST(TruthTrack, LiveTruthExtrapolatesThenHoldsAndDropsTheOldest) {
  TruthTrack t(3);
  EXPECT_FALSE(t.extrapolated(kT0, 0.5).valid);  // empty
  for (int k = 0; k < 5; ++k) t.add(at_x(k, 10.0 * k));
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t.sample(0).pos_m.x, 20.0);
  Truth x = t.extrapolated(kT0 + 4.25, 0.5);
  EXPECT_EQ(x.pos_m.x, 42.5);
  EXPECT_EQ(x.vel_m_s.x, 10.0);
  x = t.extrapolated(kT0 + 6.0, 0.5);  // held at +0.5 s, not moving
  EXPECT_EQ(x.pos_m.x, 45.0);
  EXPECT_EQ(x.vel_m_s.x, 0.0);
  EXPECT_EQ(t.extrapolated(kT0 + 1.75, 0.5).pos_m.x, 17.5);  // before the oldest: moved back
  EXPECT_FALSE(t.extrapolated(kT0 + 1.0, 0.5).valid);
}

}  // namespace
}  // namespace gnssemu::world

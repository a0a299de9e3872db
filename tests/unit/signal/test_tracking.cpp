// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/error.hpp"
#include "core/signal/tracking.hpp"

using namespace gnssemu;
using namespace gnssemu::signal;

TEST(Tracking, Hysteresis) {
  const TrackingThresholds t;  // acquire 30, lose 25
  TrackingState s;
  EXPECT_FALSE(s.update(29.9, 1.0, t));
  EXPECT_TRUE(s.update(30.0, 1.0, t));
  EXPECT_EQ(s.lock_time_s(), 0.0);
  EXPECT_TRUE(s.update(27.0, 1.0, t));  // between thresholds: kept
  EXPECT_TRUE(s.update(25.0, 1.0, t));
  EXPECT_EQ(s.lock_time_s(), 2.0);
  EXPECT_FALSE(s.update(24.99, 1.0, t));
  EXPECT_FALSE(s.update(27.0, 1.0, t));  // between thresholds: not reacquired
  EXPECT_TRUE(s.update(31.0, 1.0, t));
  EXPECT_FALSE(s.update(NAN, 1.0, t));  // NaN = no signal
  EXPECT_EQ(s.lock_time_s(), 0.0);
}

TEST(Tracking, Validation) {
  EXPECT_NO_THROW(validate(TrackingThresholds{30.0, 25.0}));
  EXPECT_NO_THROW(validate(TrackingThresholds{15.0, 12.0}));  // high sensitivity
  EXPECT_THROW(validate(TrackingThresholds{25.0, 30.0}), Error);
  EXPECT_THROW(validate(TrackingThresholds{NAN, 25.0}), Error);
}

// SPDX-License-Identifier: Apache-2.0
// InputBudget: a port takes its burst at once, then its rate; a flood waits.
#include <gtest/gtest.h>

#include "daemon/ports/input_budget.hpp"

namespace gnssemu::daemon {
namespace {

TEST(InputBudget, BurstThenRate) {
  InputBudget b(1000.0, 4000.0);
  // The burst: four 1 kB reads at once, the fourth empties the bucket.
  EXPECT_EQ(b.spend(1000, 0.0), 0.0);
  EXPECT_EQ(b.spend(1000, 0.0), 0.0);
  EXPECT_EQ(b.spend(1000, 0.0), 0.0);
  EXPECT_NEAR(b.spend(1000, 0.0), 1.024, 1e-12);  // refill a 1 kB read: 1.024 s at 1000 B/s
  EXPECT_EQ(b.spend(1000, 1.024), 0.0);  // after the wait a read fits (24 B left)
  EXPECT_NEAR(b.spend(1000, 1.024), 2.0, 1e-9);  // -976 B: 2 s to a read.s worth
  // A quiet spell refills it only to the burst.
  EXPECT_EQ(b.spend(1000, 100.0), 0.0);
  EXPECT_EQ(b.spend(2000, 100.0), 0.0);
}

// A flood read as fast as the waits allow takes the rate, not more.
TEST(InputBudget, FloodTakesTheRate) {
  InputBudget b(kInputBytesPerS, kInputBurstBytes);
  double now = 0.0, taken = 0.0;
  while (now < 10.0) {
    taken += 1024.0;
    now += b.spend(1024, now);
  }
  EXPECT_NEAR(taken / now, kInputBytesPerS, 0.01 * kInputBytesPerS + kInputBurstBytes / now);
}

}  // namespace
}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
// Epoch deadlines and skips of the daemon's scheduler.
#include <gtest/gtest.h>

#include "daemon/epoch_schedule.hpp"

using namespace gnssemu::daemon;

TEST(EpochSchedule, AbsoluteDeadlinesDoNotDrift) {
  EXPECT_EQ(epoch_deadline_ns(0, 1.0), 0);
  EXPECT_EQ(epoch_deadline_ns(7, 1.0), 7'000'000'000);
  EXPECT_EQ(epoch_deadline_ns(3, 10.0), 300'000'000);
  // 3 Hz: each deadline rounds on its own, so after a day the error is < 1 ns.
  EXPECT_EQ(epoch_deadline_ns(3 * 86400, 3.0), 86400'000'000'000);
  EXPECT_EQ(epoch_deadline_ns(1, 3.0), 333'333'333);
  EXPECT_EQ(epoch_deadline_ns(2, 3.0), 666'666'667);
  EXPECT_DOUBLE_EQ(epoch_offset_s(25, 5.0), 5.0);
}

TEST(EpochSchedule, OnTimeAndSlightlyLate) {
  ScheduleStep s = next_epoch(0, 1.0, 2'000'000);  // served epoch 0, 2 ms after
  EXPECT_EQ(s.next_index, 1);
  EXPECT_EQ(s.skipped, 0);
  // Late by almost a whole period for epoch 1's successor: still no skip.
  s = next_epoch(4, 10.0, 600'000'000);
  EXPECT_EQ(s.next_index, 5);
  EXPECT_EQ(s.skipped, 0);
}

TEST(EpochSchedule, LateByMoreThanAPeriodSkips) {
  // Served epoch 4 at 10 Hz, but it is already 0.93 s: epochs 5..9 are due.
  ScheduleStep s = next_epoch(4, 10.0, 930'000'000);
  EXPECT_EQ(s.next_index, 9);
  EXPECT_EQ(s.skipped, 4);
  // Exactly on a deadline boundary.
  s = next_epoch(0, 1.0, 5'000'000'000);
  EXPECT_EQ(s.next_index, 5);
  EXPECT_EQ(s.skipped, 4);
  s = next_epoch(0, 1.0, 2'000'000'001);
  EXPECT_EQ(s.next_index, 2);
  EXPECT_EQ(s.skipped, 1);
}

#include <gtest/gtest.h>

#include "daemon/drop_stats.hpp"

using namespace gnssemu::daemon;

TEST(DropStats, OneLinePerReasonPerInterval) {
  DropStats d(5.0);
  EXPECT_EQ(d.record(DropReason::kNonFinite, 0.0), 1u);  // first: log at once
  EXPECT_EQ(d.record(DropReason::kNonFinite, 1.0), 0u);
  EXPECT_EQ(d.record(DropReason::kNonFinite, 4.9), 0u);
  EXPECT_EQ(d.record(DropReason::kMalformedJson, 4.9), 1u);  // other reasons independent
  EXPECT_EQ(d.record(DropReason::kNonFinite, 5.0), 3u);       // reports the two suppressed + this
  EXPECT_EQ(d.record(DropReason::kNonFinite, 6.0), 0u);
  EXPECT_EQ(d.record(DropReason::kNonFinite, 20.0), 2u);
  EXPECT_EQ(d.count(DropReason::kNonFinite), 6u);
  EXPECT_EQ(d.count(DropReason::kMalformedJson), 1u);
  EXPECT_EQ(d.count(DropReason::kHeightRange), 0u);
  EXPECT_EQ(d.total(), 7u);
}

TEST(DropStats, FloodIsBounded) {
  DropStats d(5.0);
  int lines = 0;
  for (int i = 0; i < 100000; ++i) {  // 10 kHz of garbage for 10 s
    if (d.record(DropReason::kMalformedJson, i * 1e-4) > 0) ++lines;
  }
  EXPECT_EQ(lines, 2);
  EXPECT_EQ(d.total(), 100000u);
}

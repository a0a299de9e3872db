// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "daemon/truth/drop_stats.hpp"

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

TEST(DropStats, BurstIsSummarisedWithoutFurtherPackets) {
  DropStats d(5.0);
  for (int i = 0; i < 5000; ++i) d.record(DropReason::kMalformedJson, 1.0 + i * 1e-5);
  d.record(DropReason::kBadMagic, 1.2);
  EXPECT_EQ(drop_counts_sum(d.take_due(3.0)), 0u);  // within the interval of the first lines
  const DropCounts due = d.take_due(6.0);           // no packet since: the timer reports them
  EXPECT_EQ(due[static_cast<std::size_t>(DropReason::kMalformedJson)], 4999u);
  EXPECT_EQ(due[static_cast<std::size_t>(DropReason::kBadMagic)], 0u);  // its line said it all
  EXPECT_EQ(drop_counts_text(due), "malformed_json 4999");
  EXPECT_EQ(drop_counts_sum(d.take_due(20.0)), 0u);  // taken once
  EXPECT_EQ(drop_counts_text(d.totals()), "malformed_json 5000, bad_magic 1");
}

TEST(DropStats, SummaryRestartsTheInterval) {
  DropStats d(5.0);
  d.record(DropReason::kNotAllowed, 0.0);
  d.record(DropReason::kNotAllowed, 1.0);
  EXPECT_EQ(drop_counts_sum(d.take_due(5.0)), 1u);
  EXPECT_EQ(d.record(DropReason::kNotAllowed, 6.0), 0u);  // 1 s after the summary: suppressed
  EXPECT_EQ(drop_counts_text(d.take_due(10.0)), "not_allowed 1");
}

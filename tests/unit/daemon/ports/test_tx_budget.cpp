// SPDX-License-Identifier: Apache-2.0
// TxBudget: the M8's transmit buffer drained at the line rate.
#include <gtest/gtest.h>

#include "daemon/ports/tx_budget.hpp"

using namespace gnssemu::daemon;

TEST(TxBudget, DrainsAtBaudOverTenAndDropsWholeMessages) {
  TxBudget b(9600, 4096);
  EXPECT_DOUBLE_EQ(b.line_bytes_per_s(), 960.0);
  EXPECT_TRUE(b.admit(4000, 0.0));
  EXPECT_FALSE(b.admit(100, 0.0));  // 4100 > 4096: dropped whole
  EXPECT_TRUE(b.admit(96, 0.0));    // a smaller one still fits
  EXPECT_FALSE(b.admit(1, 0.0));
  EXPECT_TRUE(b.admit(960, 1.0));   // one second drained 960 bytes
  EXPECT_FALSE(b.admit(1, 1.0));
  b.advance(100.0);
  EXPECT_EQ(b.level_bytes(), 0.0);
  b.set_baud(115200, 100.0);
  EXPECT_DOUBLE_EQ(b.line_bytes_per_s(), 11520.0);
  TxBudget none(0);
  EXPECT_TRUE(none.admit(1 << 20, 0.0));
}


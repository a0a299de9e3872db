// SPDX-License-Identifier: Apache-2.0
// tests/support/alloc_counter: every allocation form is counted and freed by
// the same allocator (the hot-path allocation tests and ASan rely on both).
#include <gtest/gtest.h>

#include <algorithm>
#include <new>
#include <vector>

#include "tests/support/alloc_counter.hpp"

namespace {

struct alignas(64) Wide {
  double v[8];
};

TEST(AllocCounter, CountsPlainNothrowArrayAndAlignedForms) {
  using gnssemu::support::allocation_count;
  long n = allocation_count();
  int* a = new int(1);
  EXPECT_EQ(allocation_count() - n, 1);
  delete a;
  n = allocation_count();
  int* b = new (std::nothrow) int[4];
  EXPECT_EQ(allocation_count() - n, 1);
  delete[] b;
  n = allocation_count();
  Wide* w = new Wide{};
  EXPECT_EQ(allocation_count() - n, 1);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(w) % 64, 0u);
  delete w;
  n = allocation_count();
  Wide* ws = new (std::nothrow) Wide[3];
  EXPECT_EQ(allocation_count() - n, 1);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(ws) % 64, 0u);
  delete[] ws;
}

TEST(AllocCounter, StableSortTemporaryBufferPairsWithItsDelete) {
  // libstdc++'s stable_sort takes its buffer with nothrow new; under ASan a
  // half-replaced allocator reported an alloc-dealloc mismatch here.
  std::vector<int> v(1000);
  for (int i = 0; i < 1000; ++i) v[static_cast<std::size_t>(i)] = (i * 7919) % 1000;
  const long n = gnssemu::support::allocation_count();
  std::stable_sort(v.begin(), v.end());
  EXPECT_GE(gnssemu::support::allocation_count() - n, 1);
  EXPECT_TRUE(std::is_sorted(v.begin(), v.end()));
}

}  // namespace

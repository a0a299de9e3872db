// SPDX-License-Identifier: Apache-2.0
// Every #include in core/, config/, daemon/, tools/, bench/ and tests/
// points down the layer table (project_layers.cpp, docs/architecture.md).
#include <gtest/gtest.h>

#include "include_rules.hpp"
#include "project_layers.hpp"

using namespace gnssemu::layering;

TEST(ProjectTree, IncludesPointDownTheLayers) {
  const std::vector<Violation> v = LayerChecker(project_rules()).check_tree(GNSSEMU_SOURCE_DIR);
  std::string all;
  for (const Violation& x : v) all += to_string(x) + "\n";
  EXPECT_TRUE(v.empty()) << v.size() << " include(s) break the layer table:\n" << all;
}

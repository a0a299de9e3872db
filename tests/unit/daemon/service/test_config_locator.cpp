// SPDX-License-Identifier: Apache-2.0
// Where gnssemud looks for default.toml.
#include <gtest/gtest.h>

#include <string>

#include "daemon/service/config_locator.hpp"

using namespace gnssemu::daemon;

TEST(ConfigLocator, SearchOrder) {
  const auto c = default_config_candidates("/opt/gnssemu/bin/gnssemud");
  ASSERT_GE(c.size(), 5u);
  EXPECT_EQ(c[0], "/opt/gnssemu/bin/default.toml");
  EXPECT_EQ(c[1], "/opt/gnssemu/bin/config/default.toml");
  EXPECT_EQ(c[2], "/opt/gnssemu/share/gnssemu/default.toml");
  EXPECT_EQ(c.back(), std::string(GNSSEMU_SOURCE_DIR) + "/config/default.toml");
  // The source tree's default is found from anywhere.
  EXPECT_EQ(find_default_config("/nonexistent/bin/gnssemud"), std::string(GNSSEMU_SOURCE_DIR) + "/config/default.toml");
}


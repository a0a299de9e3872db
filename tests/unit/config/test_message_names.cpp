// SPDX-License-Identifier: Apache-2.0
// Names of the periodic messages a port's configuration lists.
#include "config/message_names.hpp"
#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

TEST(ConfigPorts, MessageNames) {
  EXPECT_EQ(message_name(0x01, 0x07), "NAV-PVT");
  EXPECT_EQ(message_name(kNmeaClass, 0x03), "GSV");
  EXPECT_EQ(message_name(0x7F, 0x7F), "");
  ASSERT_TRUE(message_by_name("MON-HW").has_value());
  EXPECT_EQ(message_by_name("MON-HW")->msg_id, 0x09);
  EXPECT_FALSE(message_by_name("nav-pvt").has_value());
}

}  // namespace
}  // namespace gnssemu::config::test

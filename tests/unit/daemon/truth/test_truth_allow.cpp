// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "daemon/truth/truth_allow.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;

namespace {

config::AddressBlock block(const char* text) {
  std::string why;
  return config::parse_address_block(text, why).value();
}

}  // namespace

TEST(TruthAllowList, EmptyAllowsEveryone) {
  const TruthAllowList a;
  EXPECT_TRUE(a.allows(boost::asio::ip::make_address("203.0.113.7")));
  EXPECT_EQ(a.describe(), "any sender");
}

TEST(TruthAllowList, OnlyListedSenders) {
  const TruthAllowList a({block("127.0.0.1"), block("10.0.0.0/8"), block("fd00::/8")});
  EXPECT_TRUE(a.allows(boost::asio::ip::make_address("127.0.0.1")));
  EXPECT_TRUE(a.allows(boost::asio::ip::make_address("10.20.30.40")));
  EXPECT_TRUE(a.allows(boost::asio::ip::make_address("fd00::5")));
  EXPECT_TRUE(a.allows(boost::asio::ip::make_address("::ffff:10.0.0.1")));  // dual-stack socket
  EXPECT_FALSE(a.allows(boost::asio::ip::make_address("127.0.0.2")));
  EXPECT_FALSE(a.allows(boost::asio::ip::make_address("192.168.1.1")));
  EXPECT_FALSE(a.allows(boost::asio::ip::make_address("::1")));
  EXPECT_EQ(a.describe(), "127.0.0.1/32, 10.0.0.0/8, fd00::/8");
}

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <arpa/inet.h>

#include "config/address_block.hpp"

using namespace gnssemu::config;

namespace {

bool allows(const AddressBlock& b, const char* addr) {
  uint8_t buf[16] = {};
  if (inet_pton(AF_INET, addr, buf) == 1) return b.contains(buf, false);
  EXPECT_EQ(inet_pton(AF_INET6, addr, buf), 1) << addr;
  return b.contains(buf, true);
}

AddressBlock parsed(const char* text) {
  std::string why;
  const auto b = parse_address_block(text, why);
  EXPECT_TRUE(b) << text << ": " << why;
  return b.value_or(AddressBlock{});
}

}  // namespace

TEST(AddressBlock, HostsAndBlocks) {
  EXPECT_TRUE(allows(parsed("127.0.0.1"), "127.0.0.1"));
  EXPECT_FALSE(allows(parsed("127.0.0.1"), "127.0.0.2"));
  const AddressBlock ten = parsed("10.0.0.0/8");
  EXPECT_TRUE(allows(ten, "10.255.1.2"));
  EXPECT_FALSE(allows(ten, "11.0.0.1"));
  EXPECT_TRUE(allows(parsed("192.168.1.16/28"), "192.168.1.31"));
  EXPECT_FALSE(allows(parsed("192.168.1.16/28"), "192.168.1.32"));
  EXPECT_TRUE(allows(parsed("0.0.0.0/0"), "8.8.8.8"));
  EXPECT_EQ(ten.text(), "10.0.0.0/8");
}

TEST(AddressBlock, Ipv6AndMappedIpv4) {
  EXPECT_TRUE(allows(parsed("::1"), "::1"));
  EXPECT_FALSE(allows(parsed("::1"), "::2"));
  EXPECT_TRUE(allows(parsed("fd00::/8"), "fd12:3456::1"));
  // A dual-stack socket reports IPv4 senders as ::ffff:a.b.c.d.
  EXPECT_TRUE(allows(parsed("10.0.0.0/8"), "::ffff:10.1.2.3"));
  EXPECT_FALSE(allows(parsed("10.0.0.0/8"), "::ffff:11.1.2.3"));
  EXPECT_FALSE(allows(parsed("::1"), "127.0.0.1"));
}

TEST(AddressBlock, BadEntriesSayWhy) {
  std::string why;
  EXPECT_FALSE(parse_address_block("localhost", why));
  EXPECT_NE(why.find("not an IPv4 or IPv6 address"), std::string::npos);
  EXPECT_FALSE(parse_address_block("10.0.0.0/33", why));
  EXPECT_NE(why.find("[0, 32]"), std::string::npos);
  EXPECT_FALSE(parse_address_block("::/129", why));
  EXPECT_FALSE(parse_address_block("10.0.0.0/", why));
  EXPECT_FALSE(parse_address_block("10.0.0.0/8x", why));
}

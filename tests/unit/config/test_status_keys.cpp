// SPDX-License-Identifier: Apache-2.0
// [status] (config/config_keys): the status page's address and port parsed,
// written back exactly, default.toml equal to the struct defaults, and every
// bad value an error naming file:line.
#include <string>

#include "test_helpers.hpp"

namespace gnssemu::config::test::status_keys_test {
namespace {

TEST(StatusConfig, DefaultsAreLoopbackOnAFixedPort) {
  const Config c = parse(kBase);
  EXPECT_EQ(c.status.bind, "127.0.0.1");
  EXPECT_EQ(c.status.port, 5580);
  EXPECT_FALSE(c.status.free_port);
  const Config shipped = load_config(kSource + "/config/default.toml");
  EXPECT_EQ(shipped.status.bind, c.status.bind);
  EXPECT_EQ(shipped.status.port, c.status.port);
  EXPECT_EQ(shipped.status.free_port, c.status.free_port);
}

TEST(StatusConfig, EveryKeyParsedAndWrittenBack) {
  const Config c = parse(kBase + "[status]\nbind = \"::1\"\nport = 8088\nfree_port = true\n");
  EXPECT_EQ(c.status.bind, "::1");
  EXPECT_EQ(c.status.port, 8088);
  EXPECT_TRUE(c.status.free_port);
  const std::string text = to_toml(c, kData);
  const Config back = parse_config(text, "written.toml", kData);
  EXPECT_EQ(back.status.bind, "::1");
  EXPECT_EQ(back.status.port, 8088);
  EXPECT_TRUE(back.status.free_port);
  EXPECT_EQ(to_toml(back, kData), text);
}

TEST(StatusConfig, PortZeroIsOff) {
  const Config c = parse(kBase + "[status]\nport = 0\n");
  EXPECT_EQ(c.status.port, 0);
  EXPECT_FALSE(c.status.free_port);
}

struct Bad {
  std::string text;
  std::string message;  // expected substring, starting with "t.toml:LINE:"
};

TEST(StatusConfig, BadValuesNameFileAndLine) {
  const Bad cases[] = {
      {"[status]\nbind = \"localhost\"\n", "t.toml:8: status.bind: 'localhost' is not an IPv4 or IPv6 address"},
      {"[status]\nbind = \"127.0.0.256\"\n", "t.toml:8: status.bind: '127.0.0.256' is not an IPv4 or IPv6 address"},
      {"[status]\nbind = 127\n", "t.toml:8: status.bind"},
      {"[status]\nport = 65536\n", "t.toml:8: status.port: 65536 is out of range"},
      {"[status]\nport = -1\n", "t.toml:8: status.port: -1 is out of range"},
      {"[status]\nport = 80.5\n", "t.toml:8: status.port"},
      {"[status]\nport = \"free\"\n", "t.toml:8: status.port"},
      {"[status]\nfree_port = \"yes\"\n", "t.toml:8: status.free_port"},
      {"[status]\nport = 0\nfree_port = true\n",
       "t.toml:9: status.free_port: true needs status.port above 0 (port = 0 turns the page off)"},
      {"[status]\nenabled = true\n", "t.toml:8: "},
      {"[status]\nport = 7000\n[[output]]\nname = \"net\"\ntype = \"tcp\"\nport = 7000\n",
       "t.toml:8: status.port: 7000 is also the tcp port of [[output]] 'net'"},
      {"[[output]]\nname = \"net\"\ntype = \"tcp\"\nport = 5580\n",
       "t.toml:10: status.port: 5580 is also the tcp port of [[output]] 'net'"},
  };
  for (const Bad& b : cases) {
    const std::string err = error_of(kBase + b.text);
    EXPECT_NE(err.find(b.message), std::string::npos) << b.text << "\n got: " << err;
  }
}

TEST(StatusConfig, ATcpOutputBesideAnOffOrFreePortPageIsFine) {
  const std::string net = "[[output]]\nname = \"net\"\ntype = \"tcp\"\nport = 5580\n";
  EXPECT_EQ(error_of(kBase + "[status]\nport = 0\n" + net), "no error");
  EXPECT_EQ(error_of(kBase + "[status]\nfree_port = true\n" + net), "no error");
}

}  // namespace
}  // namespace gnssemu::config::test::status_keys_test

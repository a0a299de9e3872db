// SPDX-License-Identifier: Apache-2.0
// [control] (config/config_keys): the control socket's path parsed, written
// back exactly, off by default, and every bad value an error naming file:line.
#include <string>

#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

TEST(ControlConfig, OffByDefaultAndInTheShippedFile) {
  EXPECT_TRUE(parse(kBase).control.socket.empty());
  EXPECT_TRUE(load_config(kSource + "/config/default.toml").control.socket.empty());
}

TEST(ControlConfig, SocketParsedAndWrittenBack) {
  const Config c = parse(kBase + "[control]\nsocket = \"/run/gnssemu/control.sock\"\n");
  EXPECT_EQ(c.control.socket, "/run/gnssemu/control.sock");
  const std::string text = to_toml(c, kData);
  const Config back = parse_config(text, "written.toml", kData);
  EXPECT_EQ(back.control.socket, c.control.socket);
  EXPECT_EQ(to_toml(back, kData), text);
}

TEST(ControlConfig, BadValuesNameFileAndLine) {
  const std::string long_path = "/" + std::string(107, 'a');
  const struct {
    std::string text, message;
  } cases[] = {
      {"[control]\nsocket = \"\"\n", "t.toml:8: control.socket: must not be empty"},
      {"[control]\nsocket = \"run/c.sock\"\n", "t.toml:8: control.socket: 'run/c.sock' must be an absolute path"},
      {"[control]\nsocket = \"" + long_path + "\"\n", "t.toml:8: control.socket: 108 bytes; a Unix socket path holds at most 107"},
      {"[control]\nsocket = 5\n", "t.toml:8: control.socket"},
      {"[control]\nport = 5\n", "t.toml:8: "},
  };
  for (const auto& b : cases) {
    const std::string err = error_of(kBase + b.text);
    EXPECT_NE(err.find(b.message), std::string::npos) << b.text << "\n got: " << err;
  }
}

}  // namespace
}  // namespace gnssemu::config::test

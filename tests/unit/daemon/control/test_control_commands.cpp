// SPDX-License-Identifier: Apache-2.0
// The control socket's commands against a recording target: every bad
// request gets an error reply and reaches nothing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/error.hpp"
#include "daemon/control/control_commands.hpp"

namespace gnssemu::daemon {
namespace {

using nlohmann::json;

class Recorder final : public ControlTarget {
public:
  void write_status(std::string& out, std::string_view target) override {
    targets.emplace_back(target);
    out += R"({"fix":{"type":3}})";
  }
  std::vector<std::string> inject(std::string_view scenario, const std::string& source,
                                  std::string_view target) override {
    targets.emplace_back(target);
    if (scenario.find("bad") != std::string_view::npos) throw Error(source, 4, "js_db: 500 is out of range");
    injected.emplace_back(scenario);
    sources.push_back(source);
    held += 1;
    return {"jammer js_db=30 (in 0.0 s, to the end)"};
  }
  std::size_t clear(std::string_view target) override {
    targets.emplace_back(target);
    const std::size_t n = held;
    held = 0;
    ++clears;
    return n;
  }
  std::size_t fault_count() const override { return held; }

  std::vector<std::string> injected, sources, targets;
  std::size_t held = 0;
  int clears = 0;
};

json reply(std::string_view request, Recorder& r) { return json::parse(handle_control_request(request, r)); }

TEST(ControlCommands, StatusWrapsTheStatusObject) {
  Recorder r;
  const json j = reply(R"({"cmd":"status"})", r);
  EXPECT_EQ(j["ok"], true);
  EXPECT_EQ(j["status"]["fix"]["type"], 3);
}

TEST(ControlCommands, TargetPicksTheReceivers) {
  Recorder r;
  EXPECT_EQ(reply(R"({"cmd":"status","target":"v3"})", r)["ok"], true);
  EXPECT_EQ(reply(R"({"cmd":"clear","target":"v3/gps2"})", r)["ok"], true);
  EXPECT_EQ(reply(R"({"cmd":"status"})", r)["ok"], true);
  EXPECT_EQ(r.targets, (std::vector<std::string>{"v3", "v3/gps2", ""}));
  EXPECT_EQ(reply(R"({"cmd":"status","target":3})", r)["ok"], false);
  EXPECT_EQ(reply(R"({"cmd":"clear","target":""})", r)["ok"], false);
  EXPECT_EQ(r.targets.size(), 3u);
}

TEST(ControlCommands, InjectPassesTextAndSourceAndCountsFaults) {
  Recorder r;
  const json j = reply(R"({"cmd":"inject","scenario":"[[event]]\ntype = \"outage\"\nstart_s = 0\n","source":"tunnel.toml"})", r);
  ASSERT_EQ(j["ok"], true) << j.dump();
  EXPECT_EQ(j["faults"], 1);
  ASSERT_EQ(j["injected"].size(), 1u);
  ASSERT_EQ(r.injected.size(), 1u);
  EXPECT_EQ(r.injected[0], "[[event]]\ntype = \"outage\"\nstart_s = 0\n");
  EXPECT_EQ(r.sources[0], "tunnel.toml");
  const json c = reply(R"({"cmd":"clear"})", r);
  EXPECT_EQ(c["ok"], true);
  EXPECT_EQ(c["cleared"], 1);
}

TEST(ControlCommands, InjectErrorNamesFileAndLine) {
  Recorder r;
  const json j = reply(R"({"cmd":"inject","scenario":"bad","source":"jam.toml"})", r);
  EXPECT_EQ(j["ok"], false);
  EXPECT_NE(j["error"].get<std::string>().find("jam.toml:4"), std::string::npos) << j.dump();
  EXPECT_TRUE(r.injected.empty());
}

TEST(ControlCommands, BadRequestsChangeNothing) {
  Recorder r;
  r.held = 2;
  for (const char* bad : {"", "garbage", "[1,2]", "{}", R"({"cmd":7})", R"({"cmd":"reboot"})",
                          R"({"cmd":"clear","all":true})", R"({"cmd":"status","x":1})", R"({"cmd":"inject"})",
                          R"({"cmd":"inject","scenario":5})", R"({"cmd":"inject","scenario":"x","source":""})",
                          R"({"cmd":"inject","scenario":"x","when":3})", "{\"cmd\":\"clear\"", "\xff\xfe"}) {
    const json j = reply(bad, r);
    EXPECT_EQ(j["ok"], false) << bad;
    EXPECT_TRUE(j["error"].is_string()) << bad;
  }
  EXPECT_EQ(r.clears, 0);
  EXPECT_TRUE(r.injected.empty());
  EXPECT_EQ(r.held, 2u);
}

TEST(ControlCommands, UnknownCommandListsTheKnownOnes) {
  Recorder r;
  const std::string e = reply(R"({"cmd":"stop"})", r)["error"];
  EXPECT_NE(e.find("status, inject, clear"), std::string::npos) << e;
}

}  // namespace
}  // namespace gnssemu::daemon

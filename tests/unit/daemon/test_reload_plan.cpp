// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "daemon/reload_plan.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;

namespace {

config::Config base() {
  config::Config c = config::default_config();
  config::OutputPortConfig tcp;
  tcp.name = "net";
  tcp.transport = config::TcpPortConfig{"127.0.0.1", 0};
  c.outputs.push_back(tcp);
  return c;
}

}  // namespace

TEST(ReloadPlan, SameConfigChangesNothing) {
  const ReloadPlan p = plan_reload(base(), base());
  EXPECT_FALSE(p.applies());
  EXPECT_TRUE(p.need_restart.empty());
  EXPECT_EQ(p.describe(base()), "nothing");
}

TEST(ReloadPlan, LiveChanges) {
  config::Config b = base();
  b.log.level = "debug";
  b.truth.vehicle = "ego";
  b.demo.radius_m = 80.0;
  b.world.seed = b.world.seed + 1;
  const ReloadPlan p = plan_reload(base(), b);
  EXPECT_TRUE(p.log_level && p.truth && p.demo && p.receiver);
  EXPECT_FALSE(p.scene);
  EXPECT_TRUE(p.reopen.empty());
  EXPECT_TRUE(p.need_restart.empty());
}

TEST(ReloadPlan, OnlyTheChangedTransportIsReopened) {
  config::Config b = base();
  b.outputs[0].transport = config::PtyPortConfig{"/tmp/elsewhere/gps0"};
  const ReloadPlan p = plan_reload(base(), b);
  ASSERT_EQ(p.reopen.size(), 1u);
  EXPECT_EQ(p.reopen[0], 0u);
  EXPECT_TRUE(p.need_restart.empty());
}

TEST(ReloadPlan, RestartOnlyChangesAreNamed) {
  config::Config b = base();
  b.rate_hz = 5.0;
  b.truth.port = 6000;
  b.outputs[1].baud = 115200;
  b.origin.height_m += 1.0;
  const ReloadPlan p = plan_reload(base(), b);
  EXPECT_FALSE(p.applies());
  const std::vector<std::string> want{"[origin]", "rate_hz", "[truth] bind/port", "output net protocols/messages/baud"};
  EXPECT_EQ(p.need_restart, want);
  config::Config c = base();
  c.outputs.pop_back();
  EXPECT_EQ(plan_reload(base(), c).need_restart.back(), "outputs added or removed (2 -> 1)");
  config::Config renamed = base();
  renamed.outputs[1].name = "net2";
  EXPECT_EQ(plan_reload(base(), renamed).need_restart, std::vector<std::string>{"output net name (\"net2\" in the file)"});
}

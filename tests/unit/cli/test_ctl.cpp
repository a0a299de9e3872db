// SPDX-License-Identifier: Apache-2.0
// gnssemu ctl without a daemon: usage errors exit 2, an absent socket or an
// unreadable file exit 1 naming it (the live exchange is tested with a real
// gnssemud in tests/integration/daemon/ctl_integration.py).
#include <gtest/gtest.h>

#include "cli_test_util.hpp"

using namespace gnssemu::cli;
using namespace gnssemu::cli::test;

TEST(Ctl, UsageErrors) {
  EXPECT_EQ(run({"ctl", "status"}).status, kExitUsage);                        // no --socket
  EXPECT_EQ(run({"ctl", "--socket", "/tmp/x.sock"}).status, kExitUsage);       // no command
  EXPECT_EQ(run({"ctl", "--socket", "/tmp/x.sock", "reboot"}).status, kExitUsage);
  EXPECT_EQ(run({"ctl", "--socket", "/tmp/x.sock", "inject"}).status, kExitUsage);  // no file
  EXPECT_EQ(run({"ctl", "--socket", "/tmp/x.sock", "--timeout", "0", "status"}).status, kExitUsage);
}

TEST(Ctl, NoDaemonNamesTheSocket) {
  const CliResult r = run({"ctl", "--socket", "/nonexistent/gnssemu.sock", "status"});
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_NE(r.err.find("/nonexistent/gnssemu.sock"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(Ctl, UnreadableScenarioNamesTheFile) {
  const CliResult r = run({"ctl", "--socket", "/nonexistent/gnssemu.sock", "inject", "/nonexistent/s.toml"});
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_NE(r.err.find("/nonexistent/s.toml"), std::string::npos) << r.err;
}

// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <csignal>

#include "daemon/service/signals.hpp"

using namespace gnssemu::daemon;

TEST(Signals, EveryTerminatingSignalShutsDownCleanly) {
  for (int s : {SIGINT, SIGTERM, SIGQUIT, SIGALRM, SIGVTALRM, SIGPROF, SIGIO, SIGPWR, SIGXCPU, SIGXFSZ}) {
    EXPECT_EQ(signal_action(s), SignalAction::kTerminate) << s;
  }
  EXPECT_EQ(signal_action(SIGHUP), SignalAction::kReload);
  EXPECT_EQ(signal_action(SIGUSR1), SignalAction::kStatus);
  EXPECT_EQ(signal_action(SIGUSR2), SignalAction::kStatus);
  EXPECT_EQ(signal_action(SIGPIPE), SignalAction::kIgnore);
  EXPECT_EQ(signal_action(SIGCHLD), SignalAction::kIgnore);
}

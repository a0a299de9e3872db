// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "daemon/status/status_line.hpp"

using namespace gnssemu::daemon;

TEST(StatusLine, RatesSinceTheLastLine) {
  StatusLine s;
  StatusSnapshot a;
  a.now_s = 60.0;
  a.fix_type = 3;
  a.sats_used = 9;
  a.packets_ok = 600;
  a.drops = 5;
  a.epochs = 60;
  a.driver = "ego";
  a.driver_fresh = true;
  a.vehicles = 2;
  a.ports = {{"gps0", 1}, {"net", 2}, {"log", -1}};
  EXPECT_EQ(s.line(a), "fix 3D, 9 sats; truth 10.0 Hz from 'ego' (2 vehicles); 5 drops; 60 epochs; "
                       "readers: gps0 1, net 2, log ?");
  StatusSnapshot b = a;
  b.now_s = 120.0;
  b.packets_ok = 600 + 6000;
  b.drops = 5;
  b.epochs = 120;
  b.fix_type = 0;
  b.sats_tracked = 3;
  b.driver_fresh = false;
  b.vehicles = 1;
  b.ports.clear();
  EXPECT_EQ(s.line(b), "no fix, 3 sats tracked; truth 100.0 Hz from 'ego' (stale); 0 drops in 60 s; 120 epochs");
}

TEST(StatusLine, DemoAndNoTruth) {
  StatusLine s;
  StatusSnapshot a;
  a.now_s = 1.0;
  a.fix_type = 3;
  a.sats_used = 10;
  a.demo = true;
  EXPECT_EQ(s.line(a), "fix 3D, 10 sats; demo circle (no truth yet); 0 drops; 0 epochs");
  a.demo = false;
  a.now_s = 2.0;
  EXPECT_EQ(s.line(a), "fix 3D, 10 sats; no truth yet; 0 drops in 1 s; 0 epochs");
}

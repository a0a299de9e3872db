// SPDX-License-Identifier: Apache-2.0
// FaultLog: one log line when a fault event starts and one when it ends
// (docs/daemon.md §Logs), never per epoch; and the line's text.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/faults/fault_event.hpp"
#include "core/faults/fault_stage.hpp"
#include "daemon/fault_log.hpp"
#include "tests/support/alloc_counter.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;
using faults::FaultEvent;
using faults::FaultType;
using faults::LinkFault;
using faults::Param;

namespace {

/// The stage's status of events at elapsed time s (as FaultStage::status()).
std::vector<faults::FaultStatus> status_at(const std::vector<FaultEvent>& events, double s) {
  std::vector<faults::FaultStatus> out;
  for (const FaultEvent& e : events) out.push_back({&e, e.active_at(s), s - e.start_s});
  return out;
}

FaultEvent cw_jammer_ramp() {
  FaultEvent e = FaultEvent::of(FaultType::kJammer, 12.0, 20.0, static_cast<std::uint8_t>(faults::JammerKind::kCw));
  e.put(Param::kJsDb, faults::Ramp{20.0, 50.0});
  return e;
}

FaultEvent byte_loss(double output) {
  FaultEvent e = FaultEvent::of(FaultType::kPort, 3.0, faults::kForever_s, static_cast<std::uint8_t>(LinkFault::kByteLoss));
  e.put(Param::kProbability, 0.05);
  if (output >= 0.0) e.put(Param::kOutput, output);
  return e;
}

}  // namespace

TEST(FaultLog, OneStartAndOneEndPerEventOverARun) {
  const std::vector<FaultEvent> events{cw_jammer_ramp(), FaultEvent::of(FaultType::kOutage, 0.0, 4.0)};
  FaultLog log;
  std::vector<std::pair<std::size_t, bool>> seen;  // (index, started) with the epoch they came at
  std::vector<double> at_s;
  for (int k = 0; k <= 40; ++k) {  // 1 Hz epochs
    const auto st = status_at(events, k);
    for (const FaultTransition& t : log.update(st)) {
      seen.emplace_back(t.index, t.started);
      at_s.push_back(k);
    }
  }
  const std::vector<std::pair<std::size_t, bool>> want{{1, true}, {1, false}, {0, true}, {0, false}};
  EXPECT_EQ(seen, want);
  EXPECT_EQ(at_s, (std::vector<double>{0, 4, 12, 32}));
}

TEST(FaultLog, ActiveEventsEndOnceWhenClearedAndNewOnesStartAfresh) {
  const std::vector<FaultEvent> events{byte_loss(0), FaultEvent::of(FaultType::kOutage, 100.0)};
  FaultLog log;
  EXPECT_EQ(log.update(status_at(events, 5.0)).size(), 1u);  // byte loss started; the outage is pending
  EXPECT_TRUE(log.update(status_at(events, 6.0)).empty());
  const auto ended = log.end_all();
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(ended[0].index, 0u);
  EXPECT_FALSE(ended[0].started);
  EXPECT_TRUE(log.end_all().empty());                     // only once
  EXPECT_TRUE(log.update(std::vector<faults::FaultStatus>{}).empty());  // the cleared stage
  // An event injected after the clear at the same index is a new event.
  const std::vector<FaultEvent> injected{byte_loss(0)};
  const auto st = status_at(injected, 3.0);
  const auto started = log.update(st);
  ASSERT_EQ(started.size(), 1u);
  EXPECT_TRUE(started[0].started);
}

TEST(FaultLog, AnotherEventAtTheSameIndexIsNewEvenWithoutEndAll) {
  const std::vector<FaultEvent> a{byte_loss(0)};
  const std::vector<FaultEvent> b{byte_loss(1)};
  FaultLog log;
  EXPECT_EQ(log.update(status_at(a, 4.0)).size(), 1u);
  const auto t = log.update(status_at(b, 4.0));  // a replaced stage
  ASSERT_EQ(t.size(), 1u);
  EXPECT_TRUE(t[0].started);
}

TEST(FaultLog, UpdateAllocatesNothing) {
  std::vector<FaultEvent> events;
  for (int i = 0; i < 64; ++i) events.push_back(byte_loss(i % 2));
  events.push_back(byte_loss(0));  // past kMaxEvents: ignored
  FaultLog log;
  std::vector<std::vector<faults::FaultStatus>> st;
  for (int k = 0; k < 10; ++k) st.push_back(status_at(events, k));
  const long before = support::allocation_count();
  std::size_t changes = 0;
  for (const auto& s : st) changes += log.update(s).size();
  changes += log.end_all().size();
  EXPECT_EQ(support::allocation_count() - before, 0);
  EXPECT_EQ(changes, 128u);  // 64 starts at 3 s, 64 ends
}

TEST(FaultLog, TextNamesTheEventWithRampsDurationAndPort) {
  const std::vector<std::string> names{"gps0", "net"};
  EXPECT_EQ(fault_log_text(cw_jammer_ramp(), names), "jammer kind=cw js_db=20→50 for 20.0 s");
  EXPECT_EQ(fault_log_text(byte_loss(1), names), "port fault=byte_loss output=1 probability=0.05 on net");
  EXPECT_EQ(fault_log_text(byte_loss(-1), names), "port fault=byte_loss probability=0.05 on every output");
  EXPECT_EQ(fault_log_text(byte_loss(5), names), "port fault=byte_loss output=5 probability=0.05 on output 5 (none such)");
  FaultEvent sat = FaultEvent::of(FaultType::kSatellite, 0.0, 10.0);
  sat.put(Param::kPrn, 7.0);
  sat.put(Param::kBiasM, faults::Ramp{0.0, 40.0});
  sat.put(Param::kUnhealthy, 1.0);
  EXPECT_EQ(fault_log_text(sat, names), "satellite prn=7 bias_m=0→40 unhealthy=true for 10.0 s");
  EXPECT_EQ(fault_log_text(FaultEvent::of(FaultType::kOutage, 0.0), names), "outage antenna=blockage");
}

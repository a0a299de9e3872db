// SPDX-License-Identifier: Apache-2.0
// Link faults on a port (daemon/link_faults, PortChannel::send_epoch): each
// fault on the bytes a fake port receives, their combination, ramps, the
// seed, the scenario check and the allocation-free epoch path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/faults/fault_event.hpp"
#include "core/faults/fault_stage.hpp"
#include "daemon/ports/delay_line.hpp"
#include "daemon/ports/link_faults.hpp"
#include "tests/support/alloc_counter.hpp"
#include "channel_rig.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;
using namespace gnssemu::daemon::test;
using faults::FaultEvent;
using faults::FaultStatus;
using faults::FaultType;
using faults::LinkFault;
using faults::Param;

namespace {

FaultEvent port_event(LinkFault f, double duration_s = faults::kForever_s) {
  return FaultEvent::of(FaultType::kPort, 0.0, duration_s, static_cast<std::uint8_t>(f));
}

/// An endless port event with one parameter.
FaultEvent port_event(LinkFault f, Param p, double value) {
  FaultEvent e = port_event(f);
  e.put(p, value);
  return e;
}

/// Every event active, elapsed_s into it.
std::vector<FaultStatus> active(const std::vector<FaultEvent>& events, double elapsed_s = 0.0) {
  std::vector<FaultStatus> s;
  for (const FaultEvent& e : events) s.push_back({&e, true, elapsed_s});
  return s;
}

/// A port sending NMEA (RMC VTG GGA GSA GSV GLL) and UBX NAV-PVT, NAV-STATUS.
config::OutputPortConfig nmea_ubx() {
  config::OutputPortConfig c = port_cfg();
  c.ubx_messages = {{0x01, 0x07, 1}, {0x01, 0x03, 1}};
  return c;
}

/// Run epochs 1000 + k for k in [0, n) with these events active on every
/// channel (elapsed time k s); returns every epoch the first port was given.
std::vector<std::string> run(Rig& r, const std::vector<FaultEvent>& events, int n, int first = 0) {
  std::vector<std::string> out;
  for (int k = first; k < first + n; ++k) {
    r.now = 100.0 + k;
    const auto st = active(events, k);
    for (const auto& c : r.channels) c->set_link_faults(st);
    r.port->epochs.clear();
    r.on_epoch(good_fix(1000.0 + k));
    for (auto& e : r.port->epochs) out.push_back(e);
  }
  return out;
}

std::size_t total_bytes(const std::vector<std::string>& epochs) {
  std::size_t n = 0;
  for (const auto& e : epochs) n += e.size();
  return n;
}

/// Messages a parser accepts (valid checksums) in a stream.
std::size_t valid_messages(const std::vector<std::string>& epochs) {
  std::size_t n = 0;
  for (const auto& e : epochs) n += split(e).labels.size();
  return n;
}

/// n epochs of a clean port and of one with fault f at probability p.
struct CleanAndFaulted {
  std::vector<std::string> sent, got;
  LinkFaultStats stats;  ///< of the faulted port
};
CleanAndFaulted clean_and_faulted(LinkFault f, double p, int n) {
  Rig clean(nmea_ubx());
  Rig faulted(nmea_ubx());
  CleanAndFaulted r{run(clean, {}, n), run(faulted, {port_event(f, Param::kProbability, p)}, n), {}};
  r.stats = faulted.ch->stats().link_faults;
  return r;
}

}  // namespace

TEST(LinkFaults, WithoutPortEventsTheBytesAreUnchanged) {
  Rig plain(nmea_ubx());
  Rig other({nmea_ubx(), nmea_ubx()}, 1.0);
  // A jammer and a port event of output 1 are no link faults of output 0.
  FaultEvent jam = FaultEvent::of(FaultType::kJammer, 0.0);
  jam.put(Param::kJsDb, 30.0);
  FaultEvent elsewhere = port_event(LinkFault::kStop);
  elsewhere.put(Param::kOutput, 1.0);
  const auto a = run(plain, {}, 5);
  const auto b = run(other, {jam, elsewhere}, 5);
  ASSERT_EQ(a.size(), 5u);
  EXPECT_EQ(a, b);
  EXPECT_TRUE(other.ports[1]->epochs.empty());  // output 1 is stopped
  EXPECT_EQ(other.channels[1]->stats().link_faults.epochs_stopped, 5u);
  EXPECT_EQ(other.ch->stats().link_faults.epochs_stopped, 0u);
}

TEST(LinkFaults, ByteLossTakesBytesAtItsProbabilityAndBreaksFrames) {
  const auto [sent, got, stats] = clean_and_faulted(LinkFault::kByteLoss, 0.02, 200);
  const std::size_t lost = total_bytes(sent) - total_bytes(got);
  EXPECT_EQ(stats.bytes_lost, lost);
  const double rate = static_cast<double>(lost) / static_cast<double>(total_bytes(sent));
  EXPECT_NEAR(rate, 0.02, 0.003);  // ~110 kB drawn: 3 sigma is 0.0013
  // A message survives only if none of its bytes went, nor a byte that
  // framed it (a lost UBX length or NMEA line end swallows the next one).
  const double kept = static_cast<double>(valid_messages(got)) / static_cast<double>(valid_messages(sent));
  EXPECT_GT(kept, 0.15);
  EXPECT_LT(kept, 0.9);
  FaultEvent all = port_event(LinkFault::kByteLoss);
  all.put(Param::kProbability, 1.0);
  Rig dead(nmea_ubx());
  EXPECT_TRUE(run(dead, {all}, 3).empty());
}

TEST(LinkFaults, CorruptBreaksTheChecksumOfExactlyTheDrawnMessages) {
  const auto [sent, got, stats] = clean_and_faulted(LinkFault::kCorrupt, 0.3, 50);
  EXPECT_EQ(total_bytes(sent), total_bytes(got));  // same length, wrong checksums
  const std::uint64_t corrupted = stats.messages_corrupted;
  EXPECT_EQ(valid_messages(got), valid_messages(sent) - corrupted);
  const double share = static_cast<double>(corrupted) / static_cast<double>(valid_messages(sent));
  EXPECT_NEAR(share, 0.3, 0.06);
}

TEST(LinkFaults, BreakChecksumMakesAUbxOrNmeaMessageInvalidOnly) {
  std::string ubx_frame = frame(ubx::msg::kMonVer);
  ASSERT_EQ(split(ubx_frame).labels.size(), 1u);
  EXPECT_TRUE(break_checksum(ubx_frame));
  EXPECT_TRUE(split(ubx_frame).labels.empty());
  std::string gga = "$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B\r\n";
  ASSERT_EQ(split(gga).labels.size(), 1u);
  EXPECT_TRUE(break_checksum(gga));
  EXPECT_EQ(gga.substr(gga.size() - 5), "*5C\r\n");
  EXPECT_TRUE(split(gga).labels.empty());
  std::string text = "hello";
  EXPECT_FALSE(break_checksum(text));
  EXPECT_EQ(text, "hello");
}

TEST(LinkFaults, DropRemovesWholeMessagesAndTheRestStayValid) {
  const auto [sent, got, stats] = clean_and_faulted(LinkFault::kDrop, 0.5, 40);
  const std::uint64_t dropped = stats.messages_dropped;
  EXPECT_EQ(valid_messages(got) + dropped, valid_messages(sent));
  EXPECT_GT(dropped, valid_messages(sent) * 4 / 10);
  EXPECT_LT(dropped, valid_messages(sent) * 6 / 10);
}

TEST(LinkFaults, LatencyHoldsEpochsInOrderEvenWhenItRampsDown) {
  Rig r(nmea_ubx());
  FaultEvent e = port_event(LinkFault::kLatency, 10.0);
  e.put(Param::kLatencyMs, faults::Ramp{3000.0, 0.0});
  std::vector<std::pair<double, std::string>> delivered;  // (clock, GGA time)
  const auto collect = [&] {
    for (const auto& ep : r.port->epochs) {
      const std::size_t at = ep.find("GPGGA,");
      delivered.emplace_back(r.now, ep.substr(at + 6, 9));
    }
    r.port->epochs.clear();
  };
  for (int k = 0; k < 14; ++k) {
    r.now = 100.0 + k;
    const std::vector<FaultEvent> events{e};
    r.ch->set_link_faults(k < 10 ? active(events, k) : std::vector<FaultStatus>{});
    r.on_epoch(good_fix(1000.0 + k));
    collect();
    r.now += 0.5;  // the timer firing between epochs
    r.ch->check_delayed();
    collect();
  }
  r.now = 200.0;
  EXPECT_FALSE(r.ch->check_delayed());
  collect();
  ASSERT_EQ(delivered.size(), 14u);
  // The first epoch (sent at 100 s with 3 s latency) leaves at 103 s.
  EXPECT_DOUBLE_EQ(delivered.front().first, 103.0);
  for (std::size_t i = 1; i < delivered.size(); ++i) {
    EXPECT_LT(delivered[i - 1].second, delivered[i].second) << "epochs reordered at " << i;
    EXPECT_LE(delivered[i - 1].first, delivered[i].first);
  }
  EXPECT_EQ(r.ch->stats().link_faults.epochs_delayed, 10u);  // latency > 0 in each of the event's 10 epochs
}

TEST(LinkFaults, LatencyHoldsRepliesBehindTheEpochsOnTheLine) {
  // A u-blox sends ACKs and poll answers through the same UART as its
  // epochs: a slow line delays them alike, in the order they entered it.
  Rig r(nmea_ubx());
  const std::vector<FaultEvent> events{port_event(LinkFault::kLatency, Param::kLatencyMs, 500.0)};
  r.ch->set_link_faults(active(events));
  r.on_epoch(good_fix(1000.0));  // at 100 s: due at 100.5 s
  r.now = 100.1;
  r.input(frame(ubx::msg::kMonVer));  // the reply is due at 100.6 s
  EXPECT_TRUE(r.port->epochs.empty());
  EXPECT_TRUE(r.port->replies.empty());
  r.now = 100.5;
  EXPECT_TRUE(r.ch->check_delayed());
  EXPECT_EQ(r.port->epochs.size(), 1u);
  EXPECT_TRUE(r.port->replies.empty());
  r.now = 100.6;
  EXPECT_FALSE(r.ch->check_delayed());
  ASSERT_EQ(r.port->replies.size(), 1u);
  EXPECT_EQ(message_label(r.port->replies.front()), "MON-VER");
  // The latency ends with an epoch still on the line: a reply waits behind it.
  r.now = 101.0;
  r.on_epoch(good_fix(1001.0));  // due at 101.5 s
  r.ch->set_link_faults({});
  r.now = 101.1;
  r.input(frame(ubx::msg::kMonVer));
  EXPECT_EQ(r.port->replies.size(), 1u);
  r.now = 101.5;
  EXPECT_FALSE(r.ch->check_delayed());
  EXPECT_EQ(r.port->epochs.size(), 2u);
  EXPECT_EQ(r.port->replies.size(), 2u);
  // Nothing held: a reply goes at once.
  r.input(frame(ubx::msg::kMonVer));
  EXPECT_EQ(r.port->replies.size(), 3u);
}

TEST(LinkFaults, FreezeRepeatsTheLastEpochByteForByte) {
  Rig r(nmea_ubx());
  const auto before = run(r, {}, 3);
  FaultEvent e = port_event(LinkFault::kFreeze);
  const auto frozen = run(r, {e}, 4, 3);
  ASSERT_EQ(frozen.size(), 4u);
  for (const auto& f : frozen) EXPECT_EQ(f, before.back());
  EXPECT_EQ(r.ch->stats().link_faults.epochs_frozen, 4u);
  const auto after = run(r, {}, 1, 7);
  ASSERT_EQ(after.size(), 1u);
  EXPECT_NE(after.front(), before.back());
  EXPECT_NE(after.front().find("GPGGA,"), std::string::npos);
}

TEST(LinkFaults, StopSilencesEpochsAndRepliesButTheChipStillHearsTheHost) {
  Rig r(nmea_ubx());
  FaultEvent e = port_event(LinkFault::kStop);
  r.ch->set_link_faults(active({e}));
  r.input(frame(ubx::msg::kMonVer));
  r.input(frame(ubx::msg::kCfgMsg, {0x01, 0x35, 1}));  // NAV-SAT on
  EXPECT_TRUE(r.port->replies.empty());
  EXPECT_TRUE(run(r, {e}, 3).empty());
  EXPECT_EQ(r.ch->stats().link_faults.epochs_stopped, 3u);
  EXPECT_EQ(r.ch->stats().link_faults.replies_stopped, 2u);
  const auto after = run(r, {}, 1, 3);
  ASSERT_EQ(after.size(), 1u);
  const auto labels = split(after.front()).labels;
  EXPECT_NE(std::find(labels.begin(), labels.end(), "NAV-SAT"), labels.end());
}

TEST(LinkFaults, RateSendsOnlyTheEpochsDueAtIt) {
  const auto sent_at = [](double nav_hz, double rate_hz, int n) {
    Rig r(nmea_ubx(), 1.0 / nav_hz);
    FaultEvent e = port_event(LinkFault::kRate);
    e.put(Param::kRateHz, rate_hz);
    std::vector<int> sent;
    for (int k = 0; k < n; ++k) {
      r.ch->set_link_faults(active({e}));
      r.port->epochs.clear();
      r.on_epoch(good_fix(1000.0 + k / nav_hz));
      if (!r.port->epochs.empty()) sent.push_back(k);
    }
    return sent;
  };
  EXPECT_EQ(sent_at(1.0, 0.5, 8), (std::vector<int>{0, 2, 4, 6}));
  EXPECT_EQ(sent_at(5.0, 1.0, 12), (std::vector<int>{0, 5, 10}));
  EXPECT_EQ(sent_at(1.0, 0.3, 10).size(), 3u);
  EXPECT_EQ(sent_at(1.0, 2.0, 5).size(), 5u);  // at or above the navigation rate: every epoch
}

TEST(LinkFaults, WrongFixIsReportedOnItsOutputOnly) {
  Rig r({nmea_ubx(), nmea_ubx()}, 1.0);
  FaultEvent e = port_event(LinkFault::kWrongFix);
  e.put(Param::kOutput, 0.0);
  e.put(Param::kFixType, 0.0);
  run(r, {e}, 1);
  const auto gga_quality = [](const std::string& bytes) {
    const std::size_t at = bytes.find("GPGGA,");
    std::size_t p = at;
    for (int i = 0; i < 6; ++i) p = bytes.find(',', p + 1);
    return bytes.substr(p + 1, 1);
  };
  EXPECT_EQ(gga_quality(r.ports[0]->epochs.back()), "0");
  EXPECT_EQ(gga_quality(r.ports[1]->epochs.back()), "1");
  EXPECT_EQ(r.ch->stats().link_faults.epochs_wrong_fix, 1u);
}

TEST(LinkFaults, SameSeedSameBytesOtherSeedOtherBytes) {
  const FaultEvent loss = port_event(LinkFault::kByteLoss, Param::kProbability, 0.05);
  const FaultEvent corrupt = port_event(LinkFault::kCorrupt, Param::kProbability, 0.2);
  const FaultEvent drop = port_event(LinkFault::kDrop, Param::kProbability, 0.2);
  const auto with_seed = [&](std::uint64_t seed) {
    Rig r(nmea_ubx());
    r.ch->set_link_seed(seed);
    return run(r, {loss, corrupt, drop}, 20);
  };
  EXPECT_EQ(with_seed(7), with_seed(7));
  EXPECT_NE(with_seed(7), with_seed(8));
}

TEST(LinkFaults, ProbabilityRampsFromZeroToOneOverTheEvent) {
  Rig r(nmea_ubx());
  Rig clean(nmea_ubx());
  FaultEvent e = port_event(LinkFault::kByteLoss, 10.0);
  e.put(Param::kProbability, faults::Ramp{0.0, 1.0});
  const auto got = run(r, {e}, 11);
  const auto sent = run(clean, {}, 11);
  ASSERT_EQ(got.size(), 10u);  // at the end (probability 1) nothing is left
  EXPECT_EQ(got.front(), sent.front());  // probability 0 at the start
  for (std::size_t k = 1; k < got.size(); ++k) {
    const double lost = 1.0 - static_cast<double>(got[k].size()) / static_cast<double>(sent[k].size());
    EXPECT_NEAR(lost, 0.1 * static_cast<double>(k), 0.08) << "epoch " << k;
  }
}

TEST(LinkFaults, SeveralEventsCombine) {
  const FaultEvent a = port_event(LinkFault::kByteLoss, Param::kProbability, 0.5);
  const FaultEvent b = a;
  const FaultEvent l1 = port_event(LinkFault::kLatency, Param::kLatencyMs, 200.0);
  const FaultEvent l2 = port_event(LinkFault::kLatency, Param::kLatencyMs, 300.0);
  const FaultEvent r1 = port_event(LinkFault::kRate, Param::kRateHz, 2.0);
  const FaultEvent r2 = port_event(LinkFault::kRate, Param::kRateHz, 0.5);
  const FaultEvent w1 = port_event(LinkFault::kWrongFix, Param::kFixType, 0.0);
  FaultEvent w2 = w1;
  w2.start_s = 5.0;
  w2.put(Param::kFixType, 5.0);
  FaultEvent other = a;
  other.put(Param::kOutput, 2.0);
  const std::vector<FaultEvent> events{a, b, l1, l2, r1, r2, w1, w2, other};
  std::vector<FaultStatus> st = active(events, 6.0);
  st.push_back({&events[0], false, -1.0});  // pending: no effect
  const LinkFaultSet s = active_link_faults(st, 0);
  EXPECT_DOUBLE_EQ(s.byte_loss, 0.75);
  EXPECT_DOUBLE_EQ(s.latency_s, 0.5);
  EXPECT_DOUBLE_EQ(s.rate_hz, 0.5);
  ASSERT_TRUE(s.fix_type.has_value());
  EXPECT_EQ(*s.fix_type, protocol::ReportedFix::kTimeOnly);  // the later event
  EXPECT_FALSE(active_link_faults({}, 0).any());
  EXPECT_DOUBLE_EQ(active_link_faults(st, 2).byte_loss, 1.0 - 0.125);
}

TEST(LinkFaults, ScenarioCheckNamesTheLineOfABadPortEvent) {
  FaultEvent ok = port_event(LinkFault::kDrop);
  ok.put(Param::kProbability, 0.1);
  ok.put(Param::kOutput, 1.0);
  FaultEvent far = ok;
  far.line = 12;
  far.put(Param::kOutput, 3.0);
  EXPECT_FALSE(check_port_events(std::vector{ok}, 2).has_value());
  const auto p = check_port_events(std::vector{ok, far}, 2, "rig.toml");
  ASSERT_TRUE(p.has_value());
  EXPECT_NE(p->find("rig.toml:12: port event (fault = \"drop\"): output = 3 does not exist"), std::string::npos) << *p;
  EXPECT_NE(p->find("index 0..1"), std::string::npos) << *p;
  FaultEvent bare = port_event(LinkFault::kLatency);
  bare.line = 4;
  const auto q = check_port_events(std::vector{bare}, 1);
  ASSERT_TRUE(q.has_value());
  EXPECT_NE(q->find("scenario:4: port event (fault = \"latency\"): latency_ms is required"), std::string::npos) << *q;
  EXPECT_FALSE(check_port_events(std::vector{port_event(LinkFault::kStop)}, 1).has_value());
}

TEST(LinkFaults, ReloadCheckNamesEventsWhoseOutputTheFileMovedOrRemoved) {
  FaultEvent on1 = port_event(LinkFault::kDrop, Param::kProbability, 0.5);
  on1.put(Param::kOutput, 1.0);
  on1.line = 7;
  FaultEvent on0 = on1;
  on0.put(Param::kOutput, 0.0);
  const FaultEvent every = port_event(LinkFault::kStop);  // no output: every output
  const std::vector<FaultEvent> events{on0, on1, every};
  const std::vector<std::string> running{"gps0", "log"};
  // Same list, a transport change, an output added at the end: nothing moves.
  EXPECT_TRUE(check_port_events_on_reload(events, running, running, "s.toml", "rig.toml").empty());
  EXPECT_TRUE(check_port_events_on_reload(events, running, std::vector<std::string>{"gps0", "log", "net"}, "s.toml",
                                          "rig.toml")
                  .empty());
  // Removed: a restart would refuse output = 1.
  auto p = check_port_events_on_reload(events, running, std::vector<std::string>{"gps0"}, "s.toml", "rig.toml");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0], "s.toml:7: port event (fault = \"drop\"): output = 1 (\"log\") does not exist in rig.toml: "
                  "1 [[output]] table(s)");
  // gps0 removed before it: index 0 is now "log", index 1 gone; a restart would put output = 0 on "log".
  p = check_port_events_on_reload(events, running, std::vector<std::string>{"log"}, "s.toml", "rig.toml");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], "s.toml:7: port event (fault = \"drop\"): output = 0 is \"gps0\" now but \"log\" in rig.toml");
  // Renamed counts as moved: the file no longer names the port the event acts on.
  p = check_port_events_on_reload(events, running, std::vector<std::string>{"gps0", "logger"}, "s.toml", "rig.toml");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p[0].find("output = 1 is \"log\" now but \"logger\""), std::string::npos) << p[0];
  // An index the running list lacks is check_port_events' error, not this one's.
  FaultEvent far = on1;
  far.put(Param::kOutput, 5.0);
  EXPECT_TRUE(check_port_events_on_reload(std::vector{far}, running, running, "s.toml", "rig.toml").empty());
}

TEST(LinkFaults, DelayLineKeepsTheOrderOfItsEpochs) {
  DelayLine d;
  EXPECT_TRUE(d.empty());
  const std::size_t ends[] = {2};
  d.push(5.0, "aa", ends);
  d.push(3.0, "bb", ends);  // due earlier than the one before: waits for it
  for (int i = 0; i < 10; ++i) d.push(6.0 + i, "cc", ends);
  EXPECT_DOUBLE_EQ(d.next_due_s(), 5.0);
  EXPECT_EQ(d.front().bytes, "aa");
  d.pop();
  EXPECT_DOUBLE_EQ(d.next_due_s(), 5.0);
  EXPECT_EQ(d.front().bytes, "bb");
  d.pop();
  EXPECT_EQ(d.size(), 10u);
  d.push(20.0, "dd", ends);
  d.push_reply(19.0, 7, "rr");  // a reply queues behind the epoch before it
  while (d.size() > 2) d.pop();
  EXPECT_EQ(d.front().bytes, "dd");
  EXPECT_EQ(d.front().ends, std::vector<std::size_t>{2});
  EXPECT_FALSE(d.front().reply);
  d.pop();
  EXPECT_DOUBLE_EQ(d.next_due_s(), 20.0);
  EXPECT_TRUE(d.front().reply);
  EXPECT_EQ(d.front().source, 7);
  EXPECT_EQ(d.front().bytes, "rr");
  EXPECT_TRUE(d.front().ends.empty());
}

TEST(LinkFaults, PerEpochPathDoesNotAllocateWithEveryLinkFaultActive) {
  config::OutputPortConfig c = nmea_ubx();
  c.baud = 115200;
  Rig r(c, 0.2);
  std::vector<FaultEvent> events;
  for (LinkFault f : {LinkFault::kByteLoss, LinkFault::kCorrupt, LinkFault::kDrop}) {
    events.push_back(port_event(f, 100.0));
    events.back().put(Param::kProbability, faults::Ramp{0.05, 0.2});
  }
  events.push_back(port_event(LinkFault::kLatency, 100.0));
  events.back().put(Param::kLatencyMs, faults::Ramp{1000.0, 500.0});
  events.push_back(port_event(LinkFault::kRate));
  events.back().put(Param::kRateHz, 2.5);
  events.push_back(port_event(LinkFault::kWrongFix));
  events.back().put(Param::kFixType, 3.0);
  FaultEvent freeze = port_event(LinkFault::kFreeze, 2.0);
  freeze.start_s = 6.0;
  events.push_back(freeze);
  const auto step = [&](int k) {
    r.now = 100.0 + 0.2 * k;
    const double elapsed = 0.2 * k;
    std::vector<FaultStatus> st;
    st.reserve(events.size());
    for (const FaultEvent& e : events) st.push_back({&e, e.active_at(elapsed), elapsed - e.start_s});
    r.ch->set_link_faults(st);
    r.on_epoch(good_fix(1000.0 + 0.2 * k));
    r.ch->check_delayed();
  };
  // Warm-up: the delay line reaches its most epochs held (1 s at 2.5 Hz) and
  // a freeze has held an epoch once.
  for (int k = 0; k < 50; ++k) step(k);
  r.port->epochs.clear();
  r.port->epochs.reserve(200);
  const long before = gnssemu::support::allocation_count();
  for (int k = 50; k < 100; ++k) step(k);
  const long allocations = gnssemu::support::allocation_count() - before;
  // The fake port copies each epoch (one allocation), step() builds one status vector per epoch.
  EXPECT_EQ(allocations, static_cast<long>(r.port->epochs.size()) + 50);
  const LinkFaultStats& s = r.ch->stats().link_faults;
  EXPECT_GT(s.bytes_lost, 0u);
  EXPECT_GT(s.messages_corrupted, 0u);
  EXPECT_GT(s.messages_dropped, 0u);
  EXPECT_GT(s.epochs_delayed, 0u);
  EXPECT_GT(s.epochs_frozen, 0u);
  EXPECT_GT(s.epochs_skipped, 0u);
  EXPECT_GT(s.epochs_wrong_fix, 0u);
}

namespace {

/// TPV reports gpsdecode (gpsd's own packet layer and drivers) makes of bytes; -1 without gpsdecode.
int gpsdecode_tpvs(const std::vector<std::string>& epochs, const std::string& name) {
  if (std::system("command -v gpsdecode > /dev/null 2>&1") != 0) return -1;
  const std::string path = ::testing::TempDir() + "link_faults_" + name + ".bin";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    for (const auto& e : epochs) std::fwrite(e.data(), 1, e.size(), f);
    std::fclose(f);
  }
  std::FILE* p = ::popen(("gpsdecode -j < " + path + " 2>/dev/null").c_str(), "r");
  if (p == nullptr) return -1;
  int tpv = 0;
  char line[4096];
  while (std::fgets(line, sizeof line, p) != nullptr) tpv += std::strstr(line, "\"class\":\"TPV\"") != nullptr;
  ::pclose(p);
  std::remove(path.c_str());
  return tpv;
}

}  // namespace

TEST(LinkFaults, GpsdRejectsTheCorruptedAndBrokenMessages) {
  // gpsd's parser on the channel's bytes: a corrupted or broken message gives
  // no report, so every message corrupted leaves gpsd with nothing.
  Rig clean(nmea_ubx());
  const auto sent = run(clean, {}, 30);
  const int tpv_clean = gpsdecode_tpvs(sent, "clean");
  if (tpv_clean < 0) GTEST_SKIP() << "gpsdecode not installed";
  ASSERT_GE(tpv_clean, 30);  // at least one per epoch
  const auto tpvs_with = [](LinkFault f, double p, const std::string& name) {
    Rig r(nmea_ubx());
    return gpsdecode_tpvs(run(r, {port_event(f, Param::kProbability, p)}, 30), name);
  };
  EXPECT_EQ(tpvs_with(LinkFault::kCorrupt, 1.0, "corrupt_all"), 0);
  // gpsd reports a TPV per epoch when any of RMC, GGA, GLL, NAV-PVT... got
  // through, so half the messages lost cost fewer than half the TPVs.
  const int tpv_half = tpvs_with(LinkFault::kCorrupt, 0.5, "corrupt_half");
  EXPECT_GT(tpv_half, 0);
  EXPECT_LT(tpv_half, tpv_clean);
  const int tpv_lossy = tpvs_with(LinkFault::kByteLoss, 0.01, "byte_loss");
  EXPECT_GT(tpv_lossy, 0);
  EXPECT_LT(tpv_lossy, tpv_clean);
  std::printf("gpsdecode TPVs over 30 epochs: clean %d, half corrupted %d, 1 %% byte loss %d\n", tpv_clean, tpv_half,
              tpv_lossy);
}

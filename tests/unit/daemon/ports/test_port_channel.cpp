// SPDX-License-Identifier: Apache-2.0
// PortChannel with a fake port: decoder -> device -> reply, the messages the
// device composes per port and epoch, budget drops and their warnings, and a
// channel following a reset another host sent to the chip.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "config/setup/device_setup.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "daemon/ports/port_channel.hpp"
#include "daemon/ports/tx_budget.hpp"
#include "tests/support/alloc_counter.hpp"
#include "channel_rig.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;
using namespace gnssemu::daemon::test;
namespace ubx = gnssemu::protocol::ubx;

namespace {

std::string pubx41(uint32_t baud) {
  const std::string body = "PUBX,41,1,0007,0003," + std::to_string(baud) + ",0";
  uint8_t cs = 0;
  for (char ch : body) cs ^= static_cast<uint8_t>(ch);
  char tail[8];
  std::snprintf(tail, sizeof tail, "*%02X\r\n", cs);
  return "$" + body + tail;
}

// The first frame of id in the last epoch written, "" if none.
std::string epoch_frame(const FakePort& port, ubx::MsgId id) {
  if (port.epochs.empty()) return {};
  const Messages m = split(port.epochs.back());
  for (const std::string& f : m.frames) {
    if (f.size() >= 8 && static_cast<uint8_t>(f[2]) == id.cls && static_cast<uint8_t>(f[3]) == id.id) return f;
  }
  return {};
}

uint32_t u32_at(const std::string& f, std::size_t payload_off) {
  uint32_t v = 0;
  std::memcpy(&v, f.data() + 6 + payload_off, 4);  // little-endian host
  return v;
}

// Captures spdlog output while alive.
struct LogCapture {
  std::ostringstream text;
  std::shared_ptr<spdlog::logger> saved = spdlog::default_logger();
  LogCapture() {
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(text);
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("capture", sink));
  }
  ~LogCapture() { spdlog::set_default_logger(saved); }
  int count(const std::string& what) const {
    const std::string t = text.str();
    int n = 0;
    for (std::size_t at = t.find(what); at != std::string::npos; at = t.find(what, at + 1)) ++n;
    return n;
  }
};


}  // namespace

TEST(PortChannel, FactoryPortSendsNmeaOnlyAndAnswersPollsAtOnce) {
  Rig r(port_cfg());
  EXPECT_EQ(r.ch->output_summary(), "NMEA");
  const auto labels = r.epoch(1000.0);
  EXPECT_EQ(labels, (std::vector<std::string>{"RMC", "VTG", "GGA", "GSA", "GSV", "GSV", "GLL"}));
  r.input("garbage" + frame(ubx::msg::kMonVer));
  ASSERT_EQ(r.port->replies.size(), 1u);
  EXPECT_EQ(message_label(r.port->replies[0]), "MON-VER");
}

TEST(PortChannel, CfgMsgRatesApplyFromTheNextEpochInUbloxOrder) {
  Rig r(port_cfg());
  r.input(frame(ubx::msg::kCfgMsg, {0x01, 0x35, 2}));  // NAV-SAT every 2nd epoch
  r.input(frame(ubx::msg::kCfgMsg, {0x01, 0x07, 1}));  // NAV-PVT every epoch
  r.input(frame(ubx::msg::kCfgMsg, {0xF0, 0x03, 0}));  // GSV off
  r.input(frame(ubx::msg::kCfgMsg, {0x01, 0x61, 1}));  // NAV-EOE
  ASSERT_EQ(r.port->replies.size(), 4u);
  for (const auto& rep : r.port->replies) EXPECT_EQ(message_label(rep), "ACK-ACK");
  EXPECT_EQ(r.ch->output_summary(), "NMEA+UBX");
  const auto e1 = r.epoch(1000.0);
  EXPECT_EQ(e1, (std::vector<std::string>{"NAV-PVT", "RMC", "VTG", "GGA", "GSA", "GLL", "NAV-SAT", "NAV-EOE"}));
  const auto e2 = r.epoch(1001.0);
  EXPECT_EQ(e2, (std::vector<std::string>{"NAV-PVT", "RMC", "VTG", "GGA", "GSA", "GLL", "NAV-EOE"}));
}

TEST(PortChannel, ConfiguredRatesAndProtocols) {
  config::OutputPortConfig c = port_cfg();
  c.protocols_out = ubx::proto::kUbx;
  c.ubx_messages = {{0x01, 0x07, 1}, {0x01, 0x04, 3}};
  Rig r(c);
  EXPECT_EQ(r.ch->output_summary(), "UBX");
  int dops = 0;
  for (int k = 0; k < 6; ++k) {
    const auto l = r.epoch(1000.0 + k);
    ASSERT_FALSE(l.empty());
    EXPECT_EQ(l.front(), "NAV-PVT");
    dops += static_cast<int>(std::count(l.begin(), l.end(), "NAV-DOP"));
  }
  EXPECT_EQ(dops, 2);  // every 3rd of 6 epochs
}

TEST(PortChannel, CfgRateReachesTheDaemonAndPubx41SwitchesBaudAfterTheReply) {
  config::OutputPortConfig c = port_cfg(9600);
  c.transport = config::PtyPortConfig{"/tmp/gnssemu-test-pty"};
  Rig r(c);
  int inputs = 0;
  r.ch->on_input([&](const ubx::InputResult& q) { inputs += q.nav_rate_changed; });
  r.input(frame(ubx::msg::kCfgRate, {200, 0, 1, 0, 0, 0}));
  EXPECT_EQ(inputs, 1);
  EXPECT_DOUBLE_EQ(r.device->epoch_period_s(), 0.2);
  const std::string body = "PUBX,41,1,0007,0003,38400,0";
  uint8_t cs = 0;
  for (char ch : body) cs ^= static_cast<uint8_t>(ch);
  char tail[8];
  std::snprintf(tail, sizeof tail, "*%02X\r\n", cs);
  r.input("$" + body + tail);
  ASSERT_EQ(r.port->bauds.size(), 1u);
  EXPECT_EQ(r.port->bauds[0], 38400u);
  EXPECT_DOUBLE_EQ(r.ch->budget().line_bytes_per_s(), 3840.0);
}

TEST(PortChannel, SlowLineDropsMessagesAndNeverExceedsIt) {
  config::OutputPortConfig c = port_cfg(9600);
  c.nmea.sentences.set(protocol::nmea::Sentence::kGst);
  c.nmea.sentences.set(protocol::nmea::Sentence::kZda);
  c.ubx_messages = {{0x01, 0x07, 1}, {0x01, 0x35, 1}, {0x01, 0x30, 1}, {0x01, 0x06, 1}};
  Rig r(c, 0.2);
  std::size_t sent = 0;
  for (int k = 0; k < 100; ++k) {  // 20 s at 5 Hz
    r.now = 100.0 + 0.2 * k;
    r.epoch(1000.0 + 0.2 * k);
    for (const auto& e : r.port->epochs) sent += e.size();
  }
  // At most 20 s of line (960 B/s) plus the 4 KiB buffer.
  EXPECT_LE(sent, 20u * 960u + kTxBufferBytes);
  EXPECT_GE(sent, 19u * 960u);
  EXPECT_GT(r.ch->stats().messages_dropped, 0u);
  EXPECT_GT(r.ch->stats().bytes_offered, 3u * sent);
  EXPECT_FALSE(r.ch->drops().empty());
}

TEST(PortChannel, PerEpochPathDoesNotAllocateAfterWarmUp) {
  config::OutputPortConfig c = port_cfg(9600);
  c.ubx_messages = {{0x01, 0x07, 1}, {0x01, 0x35, 1}, {0x01, 0x30, 1}};
  Rig r(c, 0.2);
  const receiver::Fix fix = good_fix(1000.0);
  // Warm-up: fills the TX buffer so drops happen, and the one warning is out.
  for (int k = 0; k < 50; ++k) {
    r.now = 100.0 + 0.2 * k;
    r.on_epoch(fix);
  }
  r.port->epochs.clear();
  r.port->epochs.reserve(100);
  const long before = gnssemu::support::allocation_count();
  for (int k = 50; k < 100; ++k) {
    r.now = 100.0 + 0.2 * k;
    r.on_epoch(fix);
  }
  // The fake port copies each epoch into a std::string (one allocation each);
  // the channel itself allocates nothing.
  EXPECT_EQ(gnssemu::support::allocation_count() - before, static_cast<long>(r.port->epochs.size()));
  EXPECT_GT(r.ch->stats().messages_dropped, 0u);
}

TEST(PortChannel, TruncatedHeaderIsAbandonedAfterTheLineGoesQuiet) {
  // A garbage header announcing a 1023-byte payload, then the host's MON-VER
  // polls: without the idle resync they wait for 1031 bytes that never come.
  Rig r(port_cfg());
  const std::string garbage("\xB5\x62\x06\x01\xFF\x03", 6);
  r.input(garbage + frame(ubx::msg::kMonVer) + frame(ubx::msg::kMonVer));
  EXPECT_TRUE(r.port->replies.empty());
  EXPECT_TRUE(r.ch->check_idle());  // not quiet long enough yet: still pending
  EXPECT_TRUE(r.port->replies.empty());
  r.now += kInputIdleS;
  EXPECT_FALSE(r.ch->check_idle());  // nothing pending afterwards
  ASSERT_EQ(r.port->replies.size(), 2u);
  EXPECT_EQ(message_label(r.port->replies[0]), "MON-VER");
  EXPECT_EQ(message_label(r.port->replies[1]), "MON-VER");
  // Input keeps the line busy: a fresh partial frame is not abandoned early.
  r.input(garbage);
  r.now += 0.05;
  r.input(frame(ubx::msg::kMonVer));
  r.now += 0.06;
  EXPECT_TRUE(r.ch->check_idle());
  EXPECT_EQ(r.port->replies.size(), 2u);
  r.now += 0.05;
  EXPECT_FALSE(r.ch->check_idle());
  EXPECT_EQ(r.port->replies.size(), 3u);
}

TEST(PortChannel, BaudChangeAndReopenDropThePartialFrame) {
  config::OutputPortConfig c = port_cfg(9600);
  c.transport = config::PtyPortConfig{"/tmp/gnssemu-test-pty"};
  Rig r(c);
  const std::string poll = frame(ubx::msg::kMonVer);
  // Bytes after $PUBX,41 in the same read were sent at the old rate: the
  // partial frame they start must not swallow what comes at the new rate.
  r.input(pubx41(38400) + poll.substr(0, 4));
  ASSERT_EQ(r.port->bauds.size(), 1u);
  r.input(poll.substr(4));
  EXPECT_TRUE(r.port->replies.empty());
  r.input(poll);
  ASSERT_EQ(r.port->replies.size(), 1u);
  // The device went away and came back (serial reopen): a fresh decoder.
  r.input(poll.substr(0, 4));
  r.ch->on_source_closed(0);
  r.input(poll.substr(4));
  EXPECT_EQ(r.port->replies.size(), 1u);
  r.input(poll);
  EXPECT_EQ(r.port->replies.size(), 2u);
}

TEST(PortChannel, BaudRecordedOnALinelessPortKeepsAFrameSplitAcrossReads) {
  // TCP: the baud is only recorded, no rate changes, so a frame TCP split
  // across two reads after $PUBX,41 is still answered.
  Rig r(port_cfg());
  const std::string poll = frame(ubx::msg::kMonVer);
  r.input(pubx41(38400) + poll.substr(0, 4));
  r.input(poll.substr(4));
  EXPECT_EQ(r.port->replies.size(), 1u);
}

TEST(PortChannel, UptimeAndTtffCountFromPowerOnAndFromCfgRst) {
  config::OutputPortConfig c = port_cfg();
  c.protocols_out = ubx::proto::kUbx;
  c.ubx_messages = {{0x01, 0x03, 1}};  // NAV-STATUS
  Rig r(c);  // powered on at clock 100 s
  int resets = 0;
  ubx::Reset last{};
  r.ch->on_input([&](const ubx::InputResult& q) {
    if (!q.reset) return;
    ++resets;
    last = *q.reset;
  });
  receiver::Fix none = good_fix(1000.0);
  none.type = receiver::FixType::kNone;
  r.now = 100.2;
  r.on_epoch(none);
  std::string st = epoch_frame(*r.port, ubx::msg::kNavStatus);
  ASSERT_EQ(st.size(), 24u);
  EXPECT_EQ(u32_at(st, 8), 0u);    // ttff: no fix yet
  EXPECT_EQ(u32_at(st, 12), 200u);  // msss
  r.now = 100.35;
  r.epoch(1000.35);
  st = epoch_frame(*r.port, ubx::msg::kNavStatus);
  EXPECT_EQ(u32_at(st, 8), 350u);  // the real time to the first fix
  EXPECT_EQ(u32_at(st, 12), 350u);
  r.now = 105.0;
  r.epoch(1005.0);
  st = epoch_frame(*r.port, ubx::msg::kNavStatus);
  EXPECT_EQ(u32_at(st, 8), 350u);
  EXPECT_EQ(u32_at(st, 12), 5000u);
  // Cold start, hardware reset (watchdog): no ACK, the daemon is told.
  r.input(frame(ubx::msg::kCfgRst, {0xFF, 0xFF, 0, 0}));
  EXPECT_TRUE(r.port->replies.empty());
  ASSERT_EQ(resets, 1);
  EXPECT_EQ(last.nav_bbr_mask, 0xFFFF);
  EXPECT_EQ(last.mode_number(), 0u);
  r.now = 105.2;
  r.on_epoch(none);  // the restarted receiver has no fix yet
  st = epoch_frame(*r.port, ubx::msg::kNavStatus);
  EXPECT_EQ(u32_at(st, 8), 0u);
  EXPECT_EQ(u32_at(st, 12), 200u);  // uptime restarted at the reset
  r.now = 106.25;
  r.epoch(1006.25);
  st = epoch_frame(*r.port, ubx::msg::kNavStatus);
  EXPECT_EQ(u32_at(st, 8), 1250u);  // ttff measured from the reset
  EXPECT_EQ(u32_at(st, 12), 1250u);
}

TEST(PortChannel, GnssStopKeepsUptimeAndAnotherPortsResetRestartsIt) {
  config::OutputPortConfig c = port_cfg();
  c.protocols_out = ubx::proto::kUbx;
  c.ubx_messages = {{0x01, 0x03, 1}};  // NAV-STATUS
  config::OutputPortConfig other = port_cfg();
  other.name = "other";
  Rig r({c, other}, 1.0);  // powered on at clock 100 s
  r.now = 100.35;
  r.epoch(1000.35);
  r.now = 105.0;
  r.epoch(1005.0);
  std::string st = epoch_frame(*r.port, ubx::msg::kNavStatus);
  EXPECT_EQ(u32_at(st, 8), 350u);
  EXPECT_EQ(u32_at(st, 12), 5000u);
  // GNSS stop (resetMode 8): the receiver keeps navigating (daemon.cpp), so
  // uptime and ttff go on; ttff never exceeds msss.
  r.input(frame(ubx::msg::kCfgRst, {0, 0, 8, 0}));
  r.now = 106.0;
  r.epoch(1006.0);
  st = epoch_frame(*r.port, ubx::msg::kNavStatus);
  EXPECT_EQ(u32_at(st, 8), 350u);
  EXPECT_EQ(u32_at(st, 12), 6000u);
  // A CFG-RST on another port of the same chip restarted the receiver
  // (GNSS-only cold start).
  r.input(frame(ubx::msg::kCfgRst, {0xFF, 0xFF, 2, 0}), 1);
  receiver::Fix none = good_fix(1006.2);
  none.type = receiver::FixType::kNone;
  r.now = 106.2;
  r.on_epoch(none);
  st = epoch_frame(*r.port, ubx::msg::kNavStatus);
  EXPECT_EQ(u32_at(st, 8), 0u);
  EXPECT_EQ(u32_at(st, 12), 200u);
  r.now = 107.0;
  r.epoch(1007.0);
  st = epoch_frame(*r.port, ubx::msg::kNavStatus);
  EXPECT_EQ(u32_at(st, 8), 1000u);
  EXPECT_EQ(u32_at(st, 12), 1000u);
}

TEST(PortChannel, BudgetWarnsOnceUntilTheBaudChanges) {
  LogCapture log;
  config::OutputPortConfig c = port_cfg(9600);
  c.transport = config::PtyPortConfig{"/tmp/gnssemu-test-pty"};
  c.ubx_messages = {{0x01, 0x07, 1}, {0x01, 0x35, 1}, {0x01, 0x30, 1}, {0x01, 0x06, 1}};
  Rig r(c, 0.2);
  const auto run = [&](int from, int to) {
    for (int k = from; k < to; ++k) {
      r.now = 100.0 + 0.2 * k;
      r.epoch(1000.0 + 0.2 * k);
    }
  };
  run(0, 100);
  ASSERT_GT(r.ch->stats().messages_dropped, 10u);
  EXPECT_EQ(log.count("transmit buffer is full"), 1);
  EXPECT_EQ(log.count("at 5 Hz but 9600 baud"), 1);
  // A new line rate gets its own warning, once, with its own figures.
  r.input(pubx41(4800));
  run(100, 200);
  EXPECT_EQ(log.count("transmit buffer is full"), 2);
  EXPECT_EQ(log.count("at 5 Hz but 4800 baud"), 1);
}

TEST(PortChannel, BudgetWarningQuotesTheRunRateAndCoversReplies) {
  {
    // A host asked for 20 Hz; the daemon runs 10 Hz (clamped) and says so.
    LogCapture log;
    config::OutputPortConfig c = port_cfg(9600);
    c.ubx_messages = {{0x01, 0x07, 1}, {0x01, 0x35, 1}, {0x01, 0x30, 1}, {0x01, 0x06, 1}};
    Rig r(c, 0.1);
    r.input(frame(ubx::msg::kCfgRate, {50, 0, 1, 0, 1, 0}));
    EXPECT_DOUBLE_EQ(r.device->config().nav_period_s(), 0.05);
    EXPECT_DOUBLE_EQ(r.device->epoch_period_s(), 0.1);
    for (int k = 0; k < 100; ++k) {
      r.now = 100.0 + 0.1 * k;
      r.epoch(1000.0 + 0.1 * k);
    }
    EXPECT_EQ(log.count("at 10 Hz but 9600 baud carries 96 "), 1) << log.text.str();
    EXPECT_EQ(log.count("at 20 Hz"), 0);
  }
  {
    // Replies alone overflow the buffer: the first dropped one warns.
    LogCapture log;
    Rig r(port_cfg(9600));
    for (int k = 0; k < 40; ++k) r.input(frame(ubx::msg::kMonVer));  // 40 x 168 B at once
    EXPECT_LT(r.port->replies.size(), 40u);
    EXPECT_GT(r.ch->stats().messages_dropped, 0u);
    EXPECT_EQ(log.count("transmit buffer is full"), 1) << log.text.str();
    EXPECT_EQ(log.count("reply MON-VER"), 1);
  }
}

TEST(PortChannel, FollowsAResetAnotherHostSentToTheChip) {
  config::OutputPortConfig a = port_cfg(9600);
  a.transport = config::PtyPortConfig{"/tmp/gnssemu-test-pty"};
  config::OutputPortConfig b = a;
  b.name = "b";
  Rig r({a, b}, 1.0);
  // What the daemon does with a host's input: the other channels follow.
  r.channels[0]->on_input([&](const ubx::InputResult& q) {
    if (q.reset || q.ports_changed) r.channels[1]->follow_device(q.reset.has_value());
  });
  r.input(pubx41(38400), 1);
  ASSERT_EQ(r.ports[1]->bauds, (std::vector<uint32_t>{38400}));
  const std::string poll = frame(ubx::msg::kMonVer);
  r.input(poll.substr(0, 4), 1);  // B's host is midway through a frame
  // A hardware reset from A's host: the chip loads its saved configuration,
  // B's UART1 included, so B's line goes back to 9600 and its partial frame is gone.
  r.input(frame(ubx::msg::kCfgRst, {0xFF, 0xFF, 0, 0}), 0);
  EXPECT_EQ(r.ports[1]->bauds, (std::vector<uint32_t>{38400, 9600}));
  EXPECT_DOUBLE_EQ(r.channels[1]->budget().line_bytes_per_s(), 960.0);
  r.input(poll.substr(4), 1);
  EXPECT_TRUE(r.ports[1]->replies.empty());
  r.input(poll, 1);
  EXPECT_EQ(r.ports[1]->replies.size(), 1u);
  EXPECT_TRUE(r.ports[0]->bauds.empty());  // A never left 9600
}

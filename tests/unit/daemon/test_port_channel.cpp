// TX budget, message splitting, port validation and PortChannel (decoder ->
// responder -> reply, per-port rates, budget drops) with a fake port.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "core/common/error.hpp"
#include "core/protocol/ubx/ubx_frame.hpp"
#include "daemon/message_split.hpp"
#include "daemon/port_channel.hpp"
#include "daemon/tx_budget.hpp"
#include "tests/support/alloc_counter.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;
namespace ubx = gnssemu::protocol::ubx;

namespace {

std::string frame(ubx::MsgId id, std::vector<uint8_t> payload = {}) {
  std::string out;
  ubx::append_frame(out, id, payload);
  return out;
}

class FakePort final : public OutputPort {
public:
  explicit FakePort(const config::OutputPortConfig& c) : OutputPort(c) {}
  std::string describe() const override { return "fake"; }
  void set_baud_after_drain(uint32_t b) noexcept override { bauds.push_back(b); }
  uint32_t baud() const noexcept override { return bauds.empty() ? config_.baud : bauds.back(); }
  std::vector<std::string> epochs, replies;
  std::vector<uint32_t> bauds;

protected:
  void deliver(int, std::string_view data, bool epoch) noexcept override {
    (epoch ? epochs : replies).emplace_back(data);
  }
};

receiver::Fix good_fix(double tow_s) {
  receiver::Fix f;
  f.t = time::GpsTime(2190, tow_s);
  f.time_valid = true;
  f.type = receiver::FixType::k3D;
  f.lla = {48.8738 * kDegToRad, 2.295 * kDegToRad, 100.0};
  f.num_used = 8;
  f.num_sats = 8;
  for (int i = 0; i < 8; ++i) {
    f.sats[static_cast<std::size_t>(i)] = {i + 1, 0.5 * i, 0.3 + 0.1 * i, 40.0, true, true, true, true};
  }
  f.dop = {1.9, 1.6, 0.9, 1.3, 0.8};
  return f;
}

struct Rig {
  double now = 100.0;
  FakePort* port = nullptr;
  std::unique_ptr<PortChannel> ch;
  explicit Rig(config::OutputPortConfig c, double period_s = 1.0) {
    auto p = std::make_unique<FakePort>(c);
    port = p.get();
    ch = std::make_unique<PortChannel>(c, std::move(p), period_s, [this] { return now; });
  }
  void input(const std::string& bytes) {
    ch->on_port_input(0, {reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()});
  }
  std::vector<std::string> epoch(double tow_s) {
    port->epochs.clear();
    ch->on_epoch(good_fix(tow_s));
    std::vector<std::string> labels;
    if (port->epochs.empty()) return labels;
    std::string_view d = port->epochs.front();
    while (!d.empty()) {
      const std::size_t n = message_length(d);
      labels.emplace_back(message_label(d.substr(0, n)));
      d.remove_prefix(n);
    }
    return labels;
  }
};

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
  std::string_view d = port.epochs.back();
  while (!d.empty()) {
    const std::size_t n = message_length(d);
    if (n >= 8 && static_cast<uint8_t>(d[0]) == 0xB5 && static_cast<uint8_t>(d[2]) == id.cls &&
        static_cast<uint8_t>(d[3]) == id.id) {
      return std::string(d.substr(0, n));
    }
    d.remove_prefix(n);
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

config::OutputPortConfig port_cfg(uint32_t baud = 0) {
  config::OutputPortConfig c;
  c.name = "t";
  c.type = config::PortType::kTcp;
  c.address = "127.0.0.1";
  c.baud = baud;
  return c;
}

}  // namespace

TEST(TxBudget, DrainsAtBaudOverTenAndDropsWholeMessages) {
  TxBudget b(9600, 4096);
  EXPECT_DOUBLE_EQ(b.line_bytes_per_s(), 960.0);
  EXPECT_TRUE(b.admit(4000, 0.0));
  EXPECT_FALSE(b.admit(100, 0.0));  // 4100 > 4096: dropped whole
  EXPECT_TRUE(b.admit(96, 0.0));    // a smaller one still fits
  EXPECT_FALSE(b.admit(1, 0.0));
  EXPECT_TRUE(b.admit(960, 1.0));   // one second drained 960 bytes
  EXPECT_FALSE(b.admit(1, 1.0));
  b.advance(100.0);
  EXPECT_EQ(b.level_bytes(), 0.0);
  b.set_baud(115200, 100.0);
  EXPECT_DOUBLE_EQ(b.line_bytes_per_s(), 11520.0);
  TxBudget none(0);
  EXPECT_TRUE(none.admit(1 << 20, 0.0));
}

TEST(MessageSplit, FramesSentencesAndGarbage) {
  const std::string pvt = frame(ubx::msg::kNavPvt, std::vector<uint8_t>(92));
  const std::string gga = "$GPGGA,1*00\r\n";
  const std::string s = pvt + gga + "xx" + gga;
  std::string_view d = s;
  EXPECT_EQ(message_length(d), 100u);
  EXPECT_EQ(message_label(d), "NAV-PVT");
  d.remove_prefix(100);
  EXPECT_EQ(message_length(d), gga.size());
  EXPECT_EQ(message_label(d), "GGA");
  d.remove_prefix(gga.size());
  EXPECT_EQ(message_length(d), 2u);  // garbage up to the next '$'
  EXPECT_EQ(message_length(std::string_view(pvt).substr(0, 50)), 50u);  // truncated: the rest
  EXPECT_EQ(message_length({}), 0u);
  EXPECT_EQ(message_label(frame(ubx::msg::kAckAck, {6, 1})), "ACK-ACK");
}

TEST(ValidatePort, EveryType) {
  config::OutputPortConfig c = port_cfg();
  EXPECT_NO_THROW(validate_port(c));
  c.address = "not-an-ip";
  EXPECT_THROW(validate_port(c), Error);
  c.type = config::PortType::kUdp;
  c.address = "127.0.0.1";
  c.port = 0;
  EXPECT_THROW(validate_port(c), Error);
  c.type = config::PortType::kSerial;
  c.path = "/dev/ttyUSB-absent-gnssemu";  // absent: fine, the port retries
  c.baud = 9600;
  EXPECT_NO_THROW(validate_port(c));
  c.path = GNSSEMU_SOURCE_DIR "/CMakeLists.txt";  // a regular file is a mistake
  EXPECT_THROW(validate_port(c), Error);
  c.path = "ttyS0";
  EXPECT_THROW(validate_port(c), Error);
}

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
  c.type = config::PortType::kPty;
  Rig r(c);
  double period = 0.0;
  r.ch->on_nav_period_change([&](double p) { period = p; });
  r.input(frame(ubx::msg::kCfgRate, {200, 0, 1, 0, 0, 0}));
  EXPECT_DOUBLE_EQ(period, 0.2);
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
    r.ch->on_epoch(fix);
  }
  r.port->epochs.clear();
  r.port->epochs.reserve(100);
  const long before = gnssemu::support::allocation_count();
  for (int k = 50; k < 100; ++k) {
    r.now = 100.0 + 0.2 * k;
    r.ch->on_epoch(fix);
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
  c.type = config::PortType::kPty;
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
  protocol::ubx::ResetRequest last{};
  r.ch->on_reset([&](const protocol::ubx::ResetRequest& q) {
    ++resets;
    last = q;
  });
  receiver::Fix none = good_fix(1000.0);
  none.type = receiver::FixType::kNone;
  r.now = 100.2;
  r.ch->on_epoch(none);
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
  EXPECT_EQ(last.reset_mode, 0);
  r.now = 105.2;
  r.ch->on_epoch(none);  // the restarted receiver has no fix yet
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
  Rig r(c);  // powered on at clock 100 s
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
  // A CFG-RST on another port of the same chip restarted the receiver.
  r.ch->navigation_restarted();
  receiver::Fix none = good_fix(1006.2);
  none.type = receiver::FixType::kNone;
  r.now = 106.2;
  r.ch->on_epoch(none);
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
  c.type = config::PortType::kPty;
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
    EXPECT_DOUBLE_EQ(r.ch->responder().nav_period_s(), 0.05);
    r.ch->set_epoch_period(0.1);
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

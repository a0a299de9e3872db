// SPDX-License-Identifier: Apache-2.0
#include "daemon/ports/port_channel.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace gnssemu::daemon {

namespace ubx = protocol::ubx;

// Decoded input of one source goes to the device.
class PortChannel::Sink final : public ubx::DecoderSink {
public:
  explicit Sink(PortChannel& ch) : ch_(ch) {}
  int source = 0;
  void on_ubx(const ubx::FrameView& frame) override {
    ch_.reply_.clear();
    ch_.handle_result(source, ch_.device_.handle_ubx(ch_.link(), frame, ch_.clock_(), ch_.reply_));
  }
  void on_nmea(std::string_view sentence) override {
    ch_.reply_.clear();
    ch_.handle_result(source, ch_.device_.handle_nmea(ch_.link(), sentence, ch_.reply_));
  }
  void on_rtcm(std::span<const uint8_t> payload, bool crc_ok) override {
    // The correction link's faults on this port (docs/rtk.md).
    const LinkFaultSet& f = ch_.link_.active();
    ch_.device_.rtcm_input().set_outage(f.rtcm_outage);
    ch_.device_.rtcm_input().set_stale(f.rtcm_stale);
    ch_.reply_.clear();
    ch_.handle_result(source, ch_.device_.handle_rtcm(ch_.link(), payload, crc_ok, ch_.reply_));
  }

private:
  PortChannel& ch_;
};

PortChannel::PortChannel(std::unique_ptr<OutputPort> port, ubx::Device& device, std::size_t output, Clock clock)
    : port_(std::move(port)),
      device_(device),
      output_(output),
      clock_(clock),
      line_clock_(std::move(clock)),
      budget_(port_->config().baud),
      line_(port_->config().baud != 0),
      sink_(std::make_unique<Sink>(*this)),
      link_(output) {
  out_.reserve(ubx::MessageList::kMaxBytes);
  out_ends_.reserve(ubx::MessageList::kMaxMessages);
  wire_.reserve(std::max<std::size_t>(ubx::MessageList::kMaxBytes, 4096));
  wire_ends_.reserve(ubx::MessageList::kMaxMessages);
  reply_.reserve(4096);
  between_bytes_.reserve(256);
  epoch_dropped_.reserve(512);
}

PortChannel::~PortChannel() = default;

void PortChannel::start() { port_->start(port_->config().protocols_in != 0 ? this : nullptr); }

std::string_view PortChannel::output_summary() const noexcept {
  const uint16_t sent = device_.protocols_sent(link());
  const bool ubx_on = (sent & ubx::proto::kUbx) != 0;
  const bool nmea_on = (sent & ubx::proto::kNmea) != 0;
  if (ubx_on && nmea_on) return "NMEA+UBX";
  if (ubx_on) return "UBX";
  return nmea_on ? "NMEA" : "nothing";
}

void PortChannel::on_port_input(int source, std::span<const uint8_t> bytes) {
  auto& in = inputs_[source];
  if (!in) in = std::make_unique<Input>();
  sink_->source = source;
  in->last_input_s = clock_();
  feeding_ = true;
  in->decoder.feed(bytes, *sink_);
  feeding_ = false;
  if (drop_after_feed_) {
    inputs_.erase(source);
  } else if (reset_after_feed_) {
    in->decoder.reset();
  } else if (in->decoder.pending_bytes() > 0) {
    arm(idle_timer_, kInputIdleS, &PortChannel::check_idle);
  }
  drop_after_feed_ = reset_after_feed_ = false;
}

void PortChannel::on_source_closed(int source) {
  // A closed or reopened source (tcp client gone, serial device lost) starts
  // again with an empty decoder.
  if (feeding_ && source == sink_->source) {
    drop_after_feed_ = true;
    return;
  }
  inputs_.erase(source);
}

void PortChannel::use_idle_timer(boost::asio::io_context& io) {
  idle_timer_.timer = std::make_unique<boost::asio::steady_timer>(io);
  delay_timer_.timer = std::make_unique<boost::asio::steady_timer>(io);
}

void PortChannel::arm(Timer& t, double delay_s, bool (PortChannel::*check)() noexcept) {
  if (!t.timer) return;
  const auto due = std::chrono::steady_clock::now() + std::chrono::nanoseconds(std::llround(delay_s * 1e9));
  // Never later than a wait already pending: what it waits for is still due then.
  if (t.armed && t.timer->expiry() <= due) return;
  t.armed = true;
  t.timer->expires_at(due);
  t.timer->async_wait([this, &t, check, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (ec || alive.expired()) return;  // re-armed earlier, or shut down
    t.armed = false;
    (this->*check)();
  });
}

bool PortChannel::check_delayed() noexcept {
  const double now = clock_();
  // The 1 ns slack keeps a timer that fired on time from waiting for rounding.
  while (!delay_.empty() && delay_.next_due_s() <= now + 1e-9) {
    const DelayLine::Entry& e = delay_.front();
    if (e.reply) {
      port_->write_reply(e.source, e.bytes);
    } else {
      port_->write_epoch(e.bytes, e.ends);
    }
    delay_.pop();
  }
  if (delay_.empty()) return false;
  arm(delay_timer_, delay_.next_due_s() - now, &PortChannel::check_delayed);
  return true;
}

bool PortChannel::check_idle() noexcept {
  const double now = clock_();
  double next_s = -1.0;  // earliest time another check is due
  for (auto it = inputs_.begin(); it != inputs_.end();) {
    Input& in = *it->second;
    const int source = it->first;
    ++it;  // the sink may close sources (a reply's write failing)
    if (in.decoder.pending_bytes() == 0) continue;
    const double quiet_s = now - in.last_input_s;
    if (quiet_s + 1e-9 < kInputIdleS) {
      const double due = kInputIdleS - quiet_s;
      if (next_s < 0.0 || due < next_s) next_s = due;
      continue;
    }
    // The line is quiet, so nothing held is the start of a frame still on
    // its way: resync until no partial frame is left.
    sink_->source = source;
    feeding_ = true;
    for (std::size_t before = in.decoder.pending_bytes(); before > 0;) {
      in.decoder.on_idle(*sink_);
      const std::size_t after = in.decoder.pending_bytes();
      if (after >= before || drop_after_feed_ || reset_after_feed_) break;
      before = after;
    }
    feeding_ = false;
    if (drop_after_feed_) {
      inputs_.erase(source);  // it already points past source
    } else if (reset_after_feed_) {
      in.decoder.reset();
    }
    drop_after_feed_ = reset_after_feed_ = false;
  }
  if (next_s >= 0.0) arm(idle_timer_, next_s, &PortChannel::check_idle);
  return next_s >= 0.0;
}

void PortChannel::handle_result(int source, const ubx::InputResult& r) {
  if (r.bytes > 0) send_reply(source, r.label);
  const std::string& name = port_->config().name;
  if (r.reset) {
    const bool restart = r.reset->restarts_navigation();
    spdlog::info("output {}: host sent CFG-RST (navBbrMask 0x{:04x}, resetMode {}){}{}", name, r.reset->nav_bbr_mask,
                 r.reset->mode_number(), restart ? ": uptime restarts" : "",
                 r.reset->reloads_saved_config() ? ", saved configuration loaded" : "");
    // Whatever arrived before the reset is gone.
    reset_after_feed_ = true;
  }
  const uint32_t baud = r.new_baud_bps;
  if (baud != 0 && baud != port_->baud()) {
    spdlog::info("output {}: host set {} baud (was {}){}", name, baud, port_->baud(),
                 line_ ? "; switching after the transmit buffer drains" : " (recorded; no line on this port)");
    port_->set_baud_after_drain(baud);
    if (line_) {
      reset_after_feed_ = true;  // bytes after the switch arrive at the new rate
      budget_.set_baud(baud, line_clock_());
      warned_ = false;  // new figures deserve a new warning
    }
  }
  // A reset restores the saved port settings, baud included.
  if (r.reset) follow_device(false);
  if (on_input_) on_input_(r);
  if (r.rates_changed || r.ports_changed) {
    spdlog::debug("output {}: host changed the output: now {}", name, output_summary());
  }
}

void PortChannel::follow_device(bool reset) noexcept {
  if (reset && !feeding_) {
    for (auto& [source, in] : inputs_) in->decoder.reset();
  }
  if (!line_) return;
  const uint32_t baud = device_.port(link()).baud_bps;
  if (baud != 0 && baud != port_->baud()) switch_baud(baud);
}

void PortChannel::switch_baud(uint32_t baud) noexcept {
  port_->set_baud_after_drain(baud);
  budget_.set_baud(baud, line_clock_());
}

void PortChannel::count_drop(std::string_view label) {
  ++stats_.messages_dropped;
  auto it = drops_by_name_.find(label);
  if (it == drops_by_name_.end()) it = drops_by_name_.emplace(std::string(label), 0).first;
  ++it->second;
}

void PortChannel::send_reply(int source, std::string_view label) noexcept {
  // A stopped output sends nothing, replies included: the host sees a dead
  // receiver (docs/faults.md "Link faults").
  if (link_.active().stop) {
    link_.count_stopped_reply();
    stats_.link_faults = link_.stats();
    return;
  }
  // Replies share the TX buffer with the epochs: a full buffer drops them too.
  if (!budget_.admit(reply_.size(), line_clock_())) {
    count_drop(label);
    if (!warned_) {
      warned_ = true;
      spdlog::warn("output {}: the {} B transmit buffer is full at {} baud (8N1, {:.0f} B/s), so the reply {} ({} B) "
                   "is dropped as a u-blox drops it; the epochs' messages need more than the line carries. Raise the "
                   "baud or lower the rates (warned once; totals at exit)",
                   port_->config().name, budget_.capacity_bytes(), budget_.baud_bps(), budget_.line_bytes_per_s(),
                   label, reply_.size());
    }
    return;
  }
  std::string_view bytes = reply_;
  if (link_.active().byte_loss > 0.0) {
    link_.lose_bytes(0, true, reply_, {}, wire_, wire_ends_);
    stats_.link_faults = link_.stats();
    bytes = wire_;
  }
  if (bytes.empty()) return;
  // A latency holds replies as it holds epochs, in the order they entered
  // the line: a u-blox's ACKs share the UART with its epochs.
  const double latency_s = link_.active().latency_s;
  if (latency_s > 0.0 || !delay_.empty()) {
    delay_.push_reply(clock_() + latency_s, source, bytes);
    check_delayed();
    return;
  }
  port_->write_reply(source, bytes);
}

void PortChannel::send_epoch() noexcept {
  send_composed(clock_());
  stats_.link_faults = link_.stats();
}

bool PortChannel::admit(std::string_view message, std::string_view label, double now) noexcept {
  stats_.bytes_offered += message.size();
  epoch_bytes_ += message.size();
  if (budget_.admit(message.size(), now)) {
    out_.append(message);
    out_ends_.push_back(out_.size());
    ++stats_.messages_sent;
    return true;
  }
  count_drop(label);
  if (!warned_ && epoch_dropped_.size() < 400) {
    if (!epoch_dropped_.empty()) epoch_dropped_ += ", ";
    epoch_dropped_ += fmt::format("{} ({} B)", label, message.size());
  }
  return false;
}

void PortChannel::send_composed(double now) noexcept {
  const LinkFaultSet& faults = link_.active();
  device_.compose(link(), epoch_, ubx::Layout::kLine, faults.fix_type);
  if (faults.fix_type) link_.count_wrong_fix();
  // The firmware: a stopped, slowed or frozen output (out_ still holds the
  // epoch last sent).
  const LinkFaults::Release release = link_.release(device_.epoch_period_s(), out_, out_ends_);
  if (release == LinkFaults::Release::kNothing) {
    check_delayed();
    return;
  }
  const std::uint64_t epoch = device_.epoch_count();
  const double line_s = line_clock_();
  out_.clear();
  out_ends_.clear();
  epoch_bytes_ = 0;
  epoch_dropped_.clear();
  if (release == LinkFaults::Release::kHeld) {
    const std::string_view held = link_.held();
    std::size_t begin = 0;
    for (const std::size_t end : link_.held_ends()) {
      admit(held.substr(begin, end - begin), "frozen epoch", line_s);
      begin = end;
    }
  } else {
    const auto& messages = epoch_.messages();
    for (std::size_t i = 0; i < messages.size(); ++i) {
      const ubx::MessageList::Message& m = messages[i];
      if (link_.drops(epoch, i)) continue;
      const std::size_t begin = out_.size();
      if (admit(epoch_.bytes(m), m.label, line_s) && link_.corrupts(epoch, i)) {
        break_checksum(std::span<char>(out_.data() + begin, out_.size() - begin));
      }
    }
  }
  if (!epoch_dropped_.empty() && !warned_) warn_drops();
  // The line: bytes lost on the way, then a delay.
  std::string_view bytes = out_;
  std::span<const std::size_t> ends = out_ends_;
  if (faults.byte_loss > 0.0) {
    link_.lose_bytes(epoch, false, out_, out_ends_, wire_, wire_ends_);
    bytes = wire_;
    ends = wire_ends_;
  }
  if (faults.latency_s > 0.0 || !delay_.empty()) {
    // Behind epochs still held, even once the latency is gone: bytes keep their order.
    if (!bytes.empty()) delay_.push(now + faults.latency_s, bytes, ends);
    if (faults.latency_s > 0.0) link_.count_delayed();
    check_delayed();
    return;
  }
  if (!bytes.empty()) port_->write_epoch(bytes, ends);
}

void PortChannel::send_relative_position() noexcept {
  device_.compose_relposned(link(), between_);
  const auto& messages = between_.messages();
  if (messages.empty()) return;
  const LinkFaultSet& faults = link_.active();
  if (faults.stop || faults.freeze || faults.rate_hz > 0.0) return;
  const std::uint64_t epoch = device_.epoch_count();
  const double line_s = line_clock_();
  between_bytes_.clear();
  for (std::size_t i = 0; i < messages.size(); ++i) {
    const ubx::MessageList::Message& m = messages[i];
    const std::size_t index = epoch_.messages().size() + i;  // after the epoch's own messages
    if (link_.drops(epoch, index)) continue;
    const std::string_view bytes = between_.bytes(m);
    stats_.bytes_offered += bytes.size();
    if (!budget_.admit(bytes.size(), line_s)) {
      count_drop(m.label);
      continue;
    }
    const std::size_t begin = between_bytes_.size();
    between_bytes_.append(bytes);
    ++stats_.messages_sent;
    if (link_.corrupts(epoch, index)) {
      break_checksum(std::span<char>(between_bytes_.data() + begin, between_bytes_.size() - begin));
    }
  }
  std::string_view out = between_bytes_;
  if (faults.byte_loss > 0.0) {
    link_.lose_bytes(0, true, between_bytes_, {}, wire_, wire_ends_);
    out = wire_;
  }
  stats_.link_faults = link_.stats();
  if (out.empty()) return;
  if (faults.latency_s > 0.0 || !delay_.empty()) {
    delay_.push_reply(clock_() + faults.latency_s, OutputPort::kEveryReader, out);
    check_delayed();
    return;
  }
  port_->write_reply(OutputPort::kEveryReader, out);
}

void PortChannel::warn_drops() {
  warned_ = true;
  const double period_s = device_.epoch_period_s();
  const double line_per_epoch = budget_.line_bytes_per_s() * period_s;
  spdlog::warn("output {}: the configured messages need {} bytes per epoch at {:.3g} Hz but {} baud carries {:.0f} "
               "(8N1, {:.0f} B/s); the {} B transmit buffer is full, so messages are dropped as a u-blox drops "
               "them. Dropped this epoch: {}. Raise the baud or lower the rates (warned once; totals at exit)",
               port_->config().name, epoch_bytes_, 1.0 / period_s, budget_.baud_bps(), line_per_epoch,
               budget_.line_bytes_per_s(), budget_.capacity_bytes(), epoch_dropped_);
}

}  // namespace gnssemu::daemon

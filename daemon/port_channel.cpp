#include "daemon/port_channel.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "config/message_names.hpp"
#include "daemon/message_split.hpp"

namespace gnssemu::daemon {

namespace ubx = protocol::ubx;

namespace {

// UBX messages sent before the NMEA block of an epoch; the others follow it
// (order of a real u-blox stream with both protocols, e.g. gpsd's
// ublox-zed-f9t-ubx_nmea_l5.log: NAV-PVT first, NMEA, then NAV-SAT/DOP/TIME, NAV-EOE last).
bool before_nmea(std::string_view frame) {
  if (frame.size() < 4 || static_cast<uint8_t>(frame[2]) != ubx::cls::kNav) return false;
  const auto id = static_cast<uint8_t>(frame[3]);
  return id == ubx::msg::kNavPvt.id || id == ubx::msg::kNavPosllh.id || id == ubx::msg::kNavStatus.id ||
         id == ubx::msg::kNavSol.id || id == ubx::msg::kNavVelned.id;
}

}  // namespace

// Decoded input of one source goes to the responder.
class PortChannel::Sink final : public ubx::DecoderSink {
public:
  explicit Sink(PortChannel& ch) : ch_(ch) {}
  int source = 0;
  void on_ubx(const ubx::FrameView& frame) override {
    ch_.reply_.clear();
    const ubx::ResponderResult r = ch_.responder_.handle_ubx(kWiredPort, frame, ch_.reply_);
    ch_.handle_result(source, r);
  }
  void on_nmea(std::string_view sentence) override {
    ch_.reply_.clear();
    const ubx::ResponderResult r = ch_.responder_.handle_nmea(kWiredPort, sentence, ch_.reply_);
    ch_.handle_result(source, r);
  }

private:
  PortChannel& ch_;
};

PortChannel::PortChannel(const config::OutputPortConfig& cfg, std::unique_ptr<OutputPort> port, double nav_period_s,
                         Clock clock, const ubx::ResponderConfig& responder_cfg)
    : cfg_(cfg),
      port_(std::move(port)),
      clock_(std::move(clock)),
      responder_(responder_cfg),
      nmea_cfg_(cfg.nmea),
      budget_(cfg.baud),
      line_(cfg.baud != 0),
      sink_(std::make_unique<Sink>(*this)),
      uptime_origin_s_(clock_()),
      epoch_period_s_(nav_period_s) {
  ubx::ReceiverConfig& rc = responder_.current();
  ubx::PortSettings& p = rc.ports[kWiredPort];
  if (cfg.baud != 0) p.baud_bps = cfg.baud;
  const uint16_t ours = ubx::proto::kUbx | ubx::proto::kNmea;
  p.in_proto_mask = cfg.protocols_in == 0 ? 0 : static_cast<uint16_t>((p.in_proto_mask & ~ours) | cfg.protocols_in);
  p.out_proto_mask = static_cast<uint16_t>((p.out_proto_mask & ~ours) | cfg.protocols_out);
  for (const config::MessageName& m : config::nmea_sentences()) rc.set_message_rate(kWiredPort, {m.msg_class, m.msg_id}, 0);
  for (const config::MessageRate& m : config::message_rates(cfg)) {
    rc.set_message_rate(kWiredPort, {m.msg_class, m.msg_id}, m.rate);
  }
  const auto meas_ms = static_cast<uint16_t>(std::lround(nav_period_s * 1000.0));
  rc.rate.measRate = meas_ms;
  rc.rate.navRate = 1;
  responder_.save_current();
  ubx_buf_.reserve(2 * ubx::kMaxEpochBytes);
  nmea_buf_.reserve(2 * protocol::nmea::kMaxEpochBytes);
  out_.reserve(2 * (ubx::kMaxEpochBytes + protocol::nmea::kMaxEpochBytes));
  reply_.reserve(4096);
  epoch_dropped_.reserve(512);
}

PortChannel::~PortChannel() = default;

void PortChannel::start() { port_->start(cfg_.protocols_in != 0 ? this : nullptr); }

std::string PortChannel::output_summary() const {
  bool ubx_on = false;
  bool nmea_on = false;
  const ubx::PortSettings& p = responder_.port(kWiredPort);
  for (const ubx::MessageRate& m : responder_.current().rate_table()) {
    if (m.rate[kWiredPort] == 0) continue;
    (m.id.cls == ubx::cls::kNmeaStd ? nmea_on : ubx_on) = true;
  }
  ubx_on = ubx_on && p.outputs_ubx();
  nmea_on = nmea_on && p.outputs_nmea();
  if (ubx_on && nmea_on) return "NMEA+UBX";
  if (ubx_on) return "UBX";
  return nmea_on ? "NMEA" : "nothing";
}

void PortChannel::set_nav_rate(const ubx::wire::CfgRate& rate) noexcept { responder_.current().rate = rate; }

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
    arm_idle_timer(kInputIdleS);
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
  idle_timer_ = std::make_unique<boost::asio::steady_timer>(io);
}

void PortChannel::arm_idle_timer(double delay_s) {
  if (!idle_timer_) return;
  const auto due = std::chrono::steady_clock::now() + std::chrono::nanoseconds(std::llround(delay_s * 1e9));
  // One timer for every source: a busy source must not push back the check
  // another, quiet one is waiting for.
  if (idle_armed_ && idle_timer_->expiry() <= due) return;
  idle_armed_ = true;
  idle_timer_->expires_at(due);
  idle_timer_->async_wait([this](const boost::system::error_code& ec) {
    if (ec) return;  // re-armed earlier, or shut down
    idle_armed_ = false;
    check_idle();
  });
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
  if (next_s >= 0.0) arm_idle_timer(next_s);
  return next_s >= 0.0;
}

void PortChannel::handle_result(int source, const ubx::ResponderResult& r) {
  if (r.bytes > 0) send_reply(source);
  if (!r.nmea_poll.empty()) {
    if (have_fix_) {
      protocol::nmea::NmeaConfig c = nmea_cfg_;
      c.sentences = r.nmea_poll;
      reply_.clear();
      protocol::nmea::NmeaEncoder(c).encode_epoch(last_fix_, reply_);
      send_reply(source);
    }
  }
  if (r.reset.requested) {
    // GNSS stop (8) keeps navigating (daemon.cpp): uptime and ttff stay.
    const bool restart = r.reset.reset_mode != 8;
    spdlog::info("output {}: host sent CFG-RST (navBbrMask 0x{:04x}, resetMode {}){}{}", cfg_.name,
                 r.reset.nav_bbr_mask, r.reset.reset_mode, restart ? ": uptime restarts" : "",
                 r.reset.reset_mode == 0 || r.reset.reset_mode == 1 || r.reset.reset_mode == 4
                     ? ", saved configuration loaded"
                     : "");
    // The receiver restarts: uptime (msss) and time to first fix count from
    // now; whatever arrived before the reset is gone.
    if (restart) uptime_origin_s_ = clock_();
    reset_after_feed_ = true;
  }
  const uint32_t baud = r.new_baud_bps[kWiredPort];
  if (baud != 0 && baud != port_->baud()) {
    spdlog::info("output {}: host set {} baud (was {}){}", cfg_.name, baud, port_->baud(),
                 line_ ? "; switching after the transmit buffer drains" : " (recorded; no line on this port)");
    port_->set_baud_after_drain(baud);
    if (line_) {
      reset_after_feed_ = true;  // bytes after the switch arrive at the new rate
      budget_.set_baud(baud, clock_());
      warned_ = false;  // new figures deserve a new warning
    }
  }
  if (r.reset.requested && line_) {
    // A reset restores the saved port settings, baud included.
    const uint32_t saved = responder_.port(kWiredPort).baud_bps;
    if (saved != 0 && saved != port_->baud()) {
      port_->set_baud_after_drain(saved);
      budget_.set_baud(saved, clock_());
    }
  }
  if ((r.nav_rate_changed || r.reset.requested) && on_nav_period_) on_nav_period_(responder_.nav_period_s());
  if (r.reset.requested && on_reset_) on_reset_(r.reset);
  if (r.rates_changed || r.ports_changed) {
    spdlog::debug("output {}: host changed the output: now {}", cfg_.name, output_summary());
  }
}

void PortChannel::navigation_restarted() noexcept {
  uptime_origin_s_ = clock_();
  responder_.navigation_restarted();
}

void PortChannel::send_reply(int source) noexcept {
  // Replies share the TX buffer with the epochs: a full buffer drops them too.
  if (!budget_.admit(reply_.size(), clock_())) {
    ++stats_.messages_dropped;
    const std::string_view label = message_label(reply_);
    ++drops_by_name_[std::string(label)];
    if (!warned_) {
      warned_ = true;
      spdlog::warn("output {}: the {} B transmit buffer is full at {} baud (8N1, {:.0f} B/s), so the reply {} ({} B) "
                   "is dropped as a u-blox drops it; the epochs' messages need more than the line carries. Raise the "
                   "baud or lower the rates (warned once; totals at exit)",
                   cfg_.name, budget_.capacity_bytes(), budget_.baud_bps(), budget_.line_bytes_per_s(), label,
                   reply_.size());
    }
    return;
  }
  port_->write_reply(source, reply_);
}

void PortChannel::admit_all(std::string_view data, double now_s) noexcept {
  while (!data.empty()) {
    const std::size_t n = message_length(data);
    const std::string_view m = data.substr(0, n);
    data.remove_prefix(n);
    stats_.bytes_offered += n;
    epoch_bytes_ += n;
    if (budget_.admit(n, now_s)) {
      out_.append(m);
      ++stats_.messages_sent;
      continue;
    }
    ++stats_.messages_dropped;
    const std::string_view label = message_label(m);
    auto it = drops_by_name_.find(label);
    if (it == drops_by_name_.end()) it = drops_by_name_.emplace(std::string(label), 0).first;
    ++it->second;
    if (!warned_ && epoch_dropped_.size() < 400) {
      if (!epoch_dropped_.empty()) epoch_dropped_ += ", ";
      epoch_dropped_ += fmt::format("{} ({} B)", label, n);
    }
  }
}

void PortChannel::on_epoch(const receiver::Fix& fix) noexcept {
  last_fix_ = fix;
  have_fix_ = true;
  const double now = clock_();
  responder_.on_epoch(fix, now - uptime_origin_s_);
  ubx_buf_.clear();
  responder_.encode_epoch(kWiredPort, ubx_buf_);
  nmea_cfg_.sentences = responder_.nmea_sentences(kWiredPort);
  nmea_buf_.clear();
  protocol::nmea::NmeaEncoder(nmea_cfg_).encode_epoch(fix, nmea_buf_);

  out_.clear();
  epoch_bytes_ = 0;
  epoch_dropped_.clear();
  // UBX position/velocity, then NMEA, then the rest of UBX (NAV-EOE last).
  const auto admit_ubx = [&](bool first_group) {
    std::string_view ubx(ubx_buf_);
    while (!ubx.empty()) {
      const std::size_t n = message_length(ubx);
      if (before_nmea(ubx.substr(0, n)) == first_group) admit_all(ubx.substr(0, n), now);
      ubx.remove_prefix(n);
    }
  };
  admit_ubx(true);
  admit_all(nmea_buf_, now);
  admit_ubx(false);
  if (!out_.empty()) port_->write_epoch(out_);
  if (!epoch_dropped_.empty() && !warned_) warn_drops();
}

void PortChannel::warn_drops() {
  warned_ = true;
  const double period_s = epoch_period_s_;
  const double line_per_epoch = budget_.line_bytes_per_s() * period_s;
  spdlog::warn("output {}: the configured messages need {} bytes per epoch at {:.3g} Hz but {} baud carries {:.0f} "
               "(8N1, {:.0f} B/s); the {} B transmit buffer is full, so messages are dropped as a u-blox drops "
               "them. Dropped this epoch: {}. Raise the baud or lower the rates (warned once; totals at exit)",
               cfg_.name, epoch_bytes_, 1.0 / period_s, budget_.baud_bps(), line_per_epoch,
               budget_.line_bytes_per_s(), budget_.capacity_bytes(), epoch_dropped_);
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/device/ubx_device.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/protocol/nmea/nmea_format.hpp"
#include "core/protocol/ubx/config/ubx_cfg_nmea.hpp"
#include "core/protocol/ubx/config/ubx_config_keys.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "core/protocol/ubx/wire/ubx_pubx.hpp"

namespace gnssemu::protocol::ubx {

static_assert(MessageList::kMaxBytes >= kMaxEpochBytes + nmea::kMaxEpochBytes);

namespace {

constexpr MsgId kInfWarning{cls::kInf, 0x01};
constexpr std::uint8_t kInfWarningBit = 0x02;  // infMsgMask: b0 ERROR, b1 WARNING, b2 NOTICE (CFG-INF)

std::vector<nmea::NmeaEncoder> nmea_encoders(const DeviceSetup& setup) {
  std::vector<nmea::NmeaEncoder> out;
  const std::size_t n = std::max<std::size_t>(setup.outputs.size(), 1);
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    nmea::NmeaConfig c;
    c.device = nmea_device(setup.mon_ver.generation);
    if (i < setup.outputs.size()) {
      c.version = setup.outputs[i].nmea_version;
      c.course_min_speed_m_s = setup.outputs[i].course_min_speed_m_s;
    }
    out.emplace_back(c);
  }
  return out;
}

/// Both configurations store id and its payloads differ.
bool block_differs(const DeviceConfig& a, const DeviceConfig& b, MsgId id) noexcept {
  const StoredBlock* x = a.stored(id);
  const StoredBlock* y = b.stored(id);
  return x != nullptr && y != nullptr &&
         !std::equal(x->payload().begin(), x->payload().end(), y->payload().begin(), y->payload().end());
}

bool ports_differ(const PortSettings& a, const PortSettings& b) noexcept {
  return a.mode != b.mode || a.baud_bps != b.baud_bps || a.in_proto_mask != b.in_proto_mask ||
         a.out_proto_mask != b.out_proto_mask || a.tx_ready != b.tx_ready || a.flags != b.flags;
}

/// Tells a MessageList where each NMEA sentence ends.
class SentenceCloser final : public nmea::SentenceSink {
public:
  explicit SentenceCloser(MessageList& list) : list_(list) {}
  void on_sentence(nmea::Sentence sentence, std::size_t /*end*/) noexcept override {
    list_.close(nmea::info(sentence).name, Protocol::kNmea);
  }

private:
  MessageList& list_;
};

}  // namespace

Device::Device(const DeviceSetup& setup)
    : ack_unknown_cfg_(setup.ack_unknown_cfg),
      coast_as_no_fix_(setup.coast_as_no_fix),
      raw_firmware_(setup.raw_firmware),
      encoder_(setup.mon_ver),
      nmea_(nmea_encoders(setup)),
      defaults_(DeviceConfig::factory_defaults(nmea_.size(), setup.mon_ver.generation)),
      saved_(defaults_),
      current_(defaults_),
      before_(defaults_),
      saved_before_(defaults_),
      val_(defaults_),
      sky_systems_(setup.sky_systems),
      epoch_period_s_(setup.nav_period_s) {
  for (std::size_t k = 0; k < setup.outputs.size(); ++k) {
    const OutputSetup& o = setup.outputs[k];
    const std::size_t col = current_.column(k, kPortUart1);
    PortSettings& p = current_.port(col);
    if (o.baud_bps != 0) p.baud_bps = o.baud_bps;
    // The UBX and NMEA bits are the output's; the others (RTCM) stay the factory's.
    const std::uint16_t ours = proto::kUbx | proto::kNmea;
    p.in_proto_mask = o.protocols_in == 0 ? 0 : static_cast<std::uint16_t>((p.in_proto_mask & ~ours) | o.protocols_in);
    p.out_proto_mask = static_cast<std::uint16_t>((p.out_proto_mask & ~ours) | o.protocols_out);
    for (const nmea::SentenceInfo& s : nmea::kSentences) current_.set_message_rate(col, {nmea::kMsgClass, s.msg_id}, 0);
    for (const MessageRate& m : o.rates) current_.set_message_rate(col, m.id, m.rate);
  }
  current_.rate.measRate = static_cast<std::uint16_t>(std::lround(setup.nav_period_s * 1000.0));
  current_.rate.navRate = 1;
  current_.nav5.dynModel = setup.dyn_model;
  current_.nav5.staticHoldThresh = setup.static_hold_thresh_cm_s;
  current_.nav5.staticHoldMaxDist = setup.static_hold_max_dist_m;
  if (const StoredBlock* b = current_.stored(msg::kCfgSbas); b != nullptr && b->size >= 2) {
    StoredBlock sbas = *b;
    sbas.bytes[1] = static_cast<std::uint8_t>(setup.sbas_diffcorr ? sbas.bytes[1] | 0x02 : sbas.bytes[1] & ~0x02);
    current_.store(msg::kCfgSbas, 0, sbas.payload());
  }
  // CFG-NMEA is the chip's, not a port's: it reports the version the first
  // output is configured with (a host polling it sees what that port prints).
  if (const StoredBlock* b = current_.stored(msg::kCfgNmea); b != nullptr && b->size >= 2 && !setup.outputs.empty()) {
    StoredBlock nmea = *b;
    nmea.bytes[1] = cfg_nmea_version(setup.outputs.front().nmea_version);
    current_.store(msg::kCfgNmea, 0, nmea.payload());
  }
  save_config();
  apply_nmea(false);
}

InputResult Device::handle_ubx(Link at, const FrameView& frame, double now_s, std::string& out) {
  InputResult r;
  if (!valid(at) || !current_.port(column(at)).accepts_ubx()) {
    ++stats_.ignored;
    return r;
  }
  const std::size_t start = out.size();
  const bool cfg = frame.id.cls == cls::kCfg;
  if (cfg) {
    before_ = current_;
    saved_before_ = saved_;
  }
  // Any other CFG message cancels a started VALSET transaction (UBX-18010854 CFG-VALSET v1).
  if (cfg && frame.id != msg::kCfgValset) val_.cancel();
  HandlerContext ctx{current_, saved_, defaults_, at.output, at.port_id, out, encoder_, last_fix_, info_,
                     ack_unknown_cfg_, generation(), std::nullopt, &val_};
  const Handler handle = cfg && !cfg_message_exists(frame.id, generation()) ? handle_cfg_unknown : find_handler(frame.id);
  r.reply = handle != nullptr ? handle(ctx, frame) : Reply::kNone;
  if (ctx.reset) {
    r.reset = ctx.reset;
    ++stats_.resets;
    if (ctx.reset->restarts_navigation()) restart_navigation(now_s);
  }
  if (cfg) diff(at, r);

  // Replies go out only when the port (as now configured) outputs UBX.
  if (!current_.port(column(at)).outputs_ubx()) {
    out.resize(start);
    if (r.reply != Reply::kReset) r.reply = Reply::kNone;
  }
  r.bytes = out.size() - start;
  if (r.bytes >= kHeaderBytes) {
    r.label = message_label(MsgId{static_cast<std::uint8_t>(out[start + 2]), static_cast<std::uint8_t>(out[start + 3])});
  }
  switch (r.reply) {
    case Reply::kAck: ++stats_.acks; break;
    case Reply::kNak: ++stats_.naks; break;
    case Reply::kPollData: ++stats_.polls; break;
    case Reply::kNone: ++stats_.ignored; break;
    case Reply::kReset: break;
  }
  after_input(r);
  return r;
}

InputResult Device::handle_nmea(Link at, std::string_view sentence, std::string& out) {
  InputResult r;
  if (!valid(at) || !current_.port(column(at)).accepts_nmea()) {
    ++stats_.ignored;
    return r;
  }
  before_ = current_;
  saved_before_ = saved_;
  if (const auto p41 = parse_pubx41(sentence)) {
    PortSettings& s = current_.port(current_.column(at.output, p41->port_id));
    if (s.exists) {
      s.in_proto_mask = p41->in_proto_mask;
      s.out_proto_mask = p41->out_proto_mask;
      if (is_uart(p41->port_id)) s.baud_bps = p41->baud_bps;
      s.autobauding = p41->autobauding;
    }
  } else if (const auto p40 = parse_pubx40(sentence)) {
    for (std::uint8_t port = 0; port < kNumPorts; ++port) {
      current_.set_message_rate(current_.column(at.output, port), MsgId{cls::kNmeaStd, p40->nmea_id}, p40->rates[port]);
    }
  } else if (sentence.size() >= 11 && sentence[0] == '$' && sentence.substr(5, 2) == "Q," &&
             current_.port(column(at)).outputs_nmea()) {
    // Standard poll $ttxxQ,sss*hh, e.g. $EIGPQ,RMC*3A: that sentence, now.
    const std::optional<nmea::Sentence> asked = nmea::sentence_by_name(sentence.substr(7, sentence.size() - 10));
    if (!asked) {
      ++stats_.ignored;
      return r;
    }
    r.nmea_poll.set(*asked);
    if (epochs_ > 0) {
      r.bytes = nmea_[at.output].encode_epoch(last_fix_, r.nmea_poll, out);
      r.label = nmea::info(*asked).name;
    }
    return r;
  } else {
    ++stats_.ignored;  // u-blox sends no answer to PUBX,40/41 either
    return r;
  }
  diff(at, r);
  after_input(r);
  return r;
}

void Device::diff(Link at, InputResult& r) const noexcept {
  for (std::size_t col = 0; col < current_.columns(); ++col) {
    if (ports_differ(before_.port(col), current_.port(col))) r.ports_changed = true;
  }
  const std::size_t uart1 = current_.column(at.output, kPortUart1);
  const std::uint32_t baud = current_.port(uart1).baud_bps;
  if (before_.port(uart1).baud_bps != baud && baud != 0) r.new_baud_bps = baud;
  if (!before_.same_rates(current_)) r.rates_changed = true;
  if (before_.nav_period_s() != current_.nav_period_s()) r.nav_rate_changed = true;
  if (std::memcmp(&before_.nav5, &current_.nav5, sizeof current_.nav5) != 0) r.nav_config_changed = true;
  const StoredBlock* gnss_before = before_.stored(msg::kCfgGnss);
  const StoredBlock* gnss_now = current_.stored(msg::kCfgGnss);
  if (gnss_before != nullptr && gnss_now != nullptr && !same_signals(gnss_before->payload(), gnss_now->payload())) {
    r.gnss_changed = true;
  }
  if (block_differs(before_, current_, msg::kCfgNmea)) r.nmea_config_changed = true;
  if (!(ubx::hpg_settings(before_) == ubx::hpg_settings(current_))) r.hpg_changed = true;
  if (!(saved_before_ == saved_)) r.saved_changed = true;
}

void Device::load_saved(const DeviceConfig& saved) {
  saved_ = saved;
  current_ = saved;
  InputResult boot;
  boot.reset = Reset{};
  after_input(boot);  // the saved CFG-RATE sets the epoch period
  // A saved CFG-NMEA a host changed replaces the output's configured version and settings.
  apply_nmea(block_differs(defaults_, current_, msg::kCfgNmea));
}

SbasSettings Device::sbas_settings() const noexcept {
  const StoredBlock* b = current_.stored(msg::kCfgSbas);
  if (b == nullptr || b->size < 2) return {};
  return SbasSettings{(b->bytes[0] & 0x01) != 0, (b->bytes[1] & 0x02) != 0};
}

SystemSet Device::enabled_systems() const noexcept { return ubx::enabled_systems(current_); }

ChannelLimits Device::channel_limits() const noexcept { return ubx::channel_limits(current_, generation()); }

NavRateLimits Device::nav_rate_limits() const noexcept {
  return ubx::nav_rate_limits(generation(), enabled_systems());
}

void Device::apply_nmea(bool from_cfg_nmea) noexcept {
  const SystemSet systems = enabled_systems().intersect(sky_systems_);
  for (nmea::NmeaEncoder& e : nmea_) {
    nmea::NmeaSettings s = e.config();
    s.systems = systems;
    if (from_cfg_nmea) s = nmea_settings_from(nmea_settings(), s, systems);
    e.set_settings(s);
  }
}

void Device::after_input(const InputResult& r) noexcept {
  if (r.nmea_config_changed || r.gnss_changed) apply_nmea(r.nmea_config_changed);
  if (!r.nav_rate_changed && !r.reset) return;
  // A host asking for more or less than the emulator runs gets the nearest rate it does.
  double p = current_.nav_period_s();
  if (!(p >= kMinEpochPeriodS)) p = kMinEpochPeriodS;
  if (p > kMaxEpochPeriodS) p = kMaxEpochPeriodS;
  epoch_period_s_ = p;
}

void Device::restart_navigation(double now_s) noexcept {
  // The next fix is a first fix again, its ttff measured from now, and
  // uptime (NAV-STATUS msss) counts from now: on every output at once.
  uptime_origin_s_ = now_s;
  have_fix_once_ = false;
  info_.ttff_ms = 0;
}

void Device::on_epoch(const receiver::Fix& fix, double now_s, const RawSource& raw) noexcept {
  last_fix_ = fix;
  raw_ = raw;
  if (fix.time_valid) rtcm_.set_time(fix.t, fix.leap_seconds);
  if (raw.epoch != nullptr) rtcm_.learn_glonass_channels(*raw.epoch);
  if (raw.epoch != nullptr && raw.epoch->time_valid) {
    // SFRBX sends what finished since the last epoch: one period after a gap.
    const double dt = raw.epoch->t_rx - last_raw_t_;
    raw_period_s_ = dt > 0.0 && dt <= 2.0 * epoch_period_s_ ? dt : epoch_period_s_;
    last_raw_t_ = raw.epoch->t_rx;
  }
  ++epochs_;
  const double uptime_s = now_s - uptime_origin_s_;
  const double ms = std::isfinite(uptime_s) ? std::clamp(uptime_s * 1e3, 0.0, 4294967295.0) : 0.0;
  // Whole ms; the 1 ns slack keeps a clock difference such as 100.35 - 100
  // (0.34999...) from losing a ms to binary rounding.
  constexpr double kSlackMs = 1e-6;
  info_.msss_ms = static_cast<std::uint32_t>(std::min(ms + kSlackMs, 4294967295.0));
  const bool gnss_fix = fix.type == receiver::FixType::k2D || fix.type == receiver::FixType::k3D;
  if (!have_fix_once_ && gnss_fix && fix.time_valid) {
    have_fix_once_ = true;
    // The uptime of this epoch (msss of the same NAV-STATUS, so ttff <= msss);
    // at least 1 ms: 0 on the wire means "no fix yet".
    info_.ttff_ms = std::max<std::uint32_t>(1, info_.msss_ms);
  }
  info_.itfm = itfm_settings(current_);
  if (generation() == Generation::kF9P) {
    rtcm_out_.encode(fix, raw.epoch, [this](MsgId id) { return rtcm_wanted(id); });
  }
  const bool big = generation() == Generation::kF9P && fix.rel_pos.valid &&
                   fix.rel_pos.length_m > kBaselineBigM;
  baseline_big_due_ = big && (!baseline_big_ || now_s - baseline_big_sent_s_ >= kBaselineBigRepeatS);
  if (baseline_big_due_) baseline_big_sent_s_ = now_s;
  baseline_big_ = big;
}

bool Device::inf_enabled(std::size_t column, std::uint8_t port_id, std::uint8_t bit,
                         std::uint8_t protocol) const noexcept {
  // CFG-INF block of protocolID protocol: infMsgMask of port port_id at byte 4 + port_id.
  const StoredBlock* b = current_.stored(msg::kCfgInf, protocol);
  const std::size_t at = 4u + port_id;
  const bool out = protocol == 0 ? current_.port(column).outputs_ubx() : current_.port(column).outputs_nmea();
  return out && b != nullptr && b->size > at && (b->bytes[at] & bit) != 0;
}

bool Device::rtcm_wanted(MsgId id) const noexcept {
  for (std::size_t o = 0; o < outputs(); ++o) {
    for (std::uint8_t p = 0; p < kNumPorts; ++p) {
      const std::size_t col = column(Link{o, p});
      if ((current_.port(col).out_proto_mask & proto::kRtcm3) != 0 && due(col, id)) return true;
    }
  }
  return false;
}

bool Device::due(std::size_t col, MsgId id) const noexcept {
  const std::uint8_t rate = current_.message_rate(col, id);
  return rate != 0 && (epochs_ - 1) % rate == 0;
}

nmea::SentenceSet Device::nmea_due(Link at) const noexcept {
  nmea::SentenceSet s;
  if (!valid(at) || epochs_ == 0 || !port(at).outputs_nmea()) return s;
  for (const nmea::SentenceInfo& info : nmea::kSentences) {
    s.set(info.sentence, due(column(at), MsgId{nmea::kMsgClass, info.msg_id}));
  }
  return s;
}

void Device::compose(Link at, MessageList& out, Layout layout, FixOverride reported) const noexcept {
  out.clear();
  if (!valid(at) || epochs_ == 0) return;
  const std::size_t col = column(at);
  if (!reported && coast_as_no_fix_ && last_fix_.type == receiver::FixType::kDeadReckoning) {
    reported = ReportedFix::kNoFix;
  }
  EpochInfo info = info_;
  info.reported_fix = reported;
  const bool ubx_on = current_.port(col).outputs_ubx();
  // A moving-base rover's time-matched RELPOSNED of an earlier epoch (its
  // base epoch came after that epoch's period): it leads, after that epoch's
  // NAV-PVT and before this one's (a host pairing them by iTOW, as ArduPilot
  // does, sees them in that order). One whose base epoch is expected within
  // this period (held) goes out on its own when it arrives (compose_relposned).
  const bool late_relposned = last_fix_.rel_pos.late;
  if (ubx_on && late_relposned && due(col, msg::kNavRelposned) &&
      encoder_.encode(msg::kNavRelposned, last_fix_, info, out.buffer()) > 0) {
    out.close("NAV-RELPOSNED", Protocol::kUbx);
  }
  const auto ubx_messages = [&](bool before_nmea) {
    if (!ubx_on) return;
    for (const std::size_t i : kEpochOrder) {
      const PeriodicMessage& m = kPeriodicMessages[i];
      if ((late_relposned || last_fix_.rel_pos.held) && m.id == msg::kNavRelposned) continue;
      if (layout == Layout::kLine && (m.group == EpochGroup::kBeforeNmea) != before_nmea) continue;
      if (!due(col, m.id)) continue;
      if (m.raw) {
        if (raw_firmware_) raw_message(m, out);
        continue;
      }
      if (encoder_.encode(m.id, last_fix_, info, out.buffer()) > 0) out.close(m.name, Protocol::kUbx);
    }
  };
  ubx_messages(true);
  const nmea::SentenceSet sentences = nmea_due(at);
  if (!sentences.empty()) {
    SentenceCloser closer(out);
    nmea_[at.output].encode_epoch(last_fix_, sentences, out.buffer(), &closer, reported);
  }
  if (layout == Layout::kLine) ubx_messages(false);
  static constexpr std::string_view kBaselineBig = "DGNSS baseline big";
  if (baseline_big_due_ && inf_enabled(col, at.port_id, kInfWarningBit, 0)) {
    append_frame(out.buffer(), kInfWarning,
                 {reinterpret_cast<const std::uint8_t*>(kBaselineBig.data()), kBaselineBig.size()});
    out.close("INF-WARNING", Protocol::kUbx);
  }
  if (baseline_big_due_ && inf_enabled(col, at.port_id, kInfWarningBit, 1)) {
    // The same as NMEA TXT where the port's NMEA info messages carry warnings
    // (factory: errors, warnings, notices): one sentence, type 01 warning,
    // talker GN as u-blox 9 logs show ($GNTXT,01,01,00,txbuf alloc in
    // shared/data/receiver-logs).
    nmea::SentenceWriter txt("GNTXT");
    txt.text("01");
    txt.text("01");
    txt.text("01");
    txt.text(kBaselineBig);
    out.buffer() += txt.finish();
    out.close("TXT", Protocol::kNmea);
  }
  if ((current_.port(col).out_proto_mask & proto::kRtcm3) != 0) {
    for (std::size_t i = 0; i < rtcm_out_.size(); ++i) {
      if (!due(col, rtcm_out_.id(i))) continue;
      out.buffer().append(rtcm_out_.bytes(i));
      out.close(rtcm_out_.label(i), Protocol::kRtcm3);
    }
  }
}

void Device::compose_relposned(Link at, MessageList& out) const noexcept {
  out.clear();
  if (!valid(at) || epochs_ == 0 || last_fix_.rel_pos.held) return;
  const std::size_t col = column(at);
  if (!current_.port(col).outputs_ubx() || !due(col, msg::kNavRelposned)) return;
  if (encoder_.encode(msg::kNavRelposned, last_fix_, info_, out.buffer()) > 0) out.close("NAV-RELPOSNED", Protocol::kUbx);
}

void Device::raw_message(const PeriodicMessage& m, MessageList& out) const noexcept {
  if (raw_.epoch == nullptr) return;
  if (m.id == msg::kRxmRawx) {
    if (rxm_rawx(*raw_.epoch, generation(), out.buffer()) > 0) out.close(m.name, Protocol::kUbx);
  } else if (m.id == msg::kRxmSfrbx) {
    rxm_sfrbx_due(raw_, raw_period_s_, generation(), out);
  }
}

std::uint16_t Device::protocols_sent(Link at) const noexcept {
  if (!valid(at)) return 0;
  bool ubx_on = false;
  bool nmea_on = false;
  for (const MsgId id : current_.rated_messages()) {
    if (current_.message_rate(column(at), id) == 0) continue;
    (id.cls == nmea::kMsgClass ? nmea_on : ubx_on) = true;
  }
  std::uint16_t mask = 0;
  if (ubx_on && port(at).outputs_ubx()) mask |= proto::kUbx;
  if (nmea_on && port(at).outputs_nmea()) mask |= proto::kNmea;
  return mask;
}

}  // namespace gnssemu::protocol::ubx

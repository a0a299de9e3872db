#include "core/protocol/ubx/ubx_responder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/protocol/ubx/ubx_pubx.hpp"

namespace gnssemu::protocol::ubx {

namespace {

/// Output order within an epoch: NAV by id (the M8 message table order),
/// MON-HW, then NAV-EOE closing the epoch (ubx.md §3 NAV-EOE).
constexpr MsgId kEpochOrder[] = {msg::kNavPosllh, msg::kNavStatus, msg::kNavDop,     msg::kNavSol,
                                 msg::kNavPvt,    msg::kNavVelned, msg::kNavTimegps, msg::kNavTimeutc,
                                 msg::kNavSvinfo, msg::kNavSat,    msg::kMonHw,      msg::kNavEoe};

constexpr std::uint16_t kMinMeasRate_ms = 25;  // M8: up to 40 Hz measurement rate (GPS only)
constexpr std::uint16_t kMaxNavRate = 127;

/// Classes whose messages CFG-MSG can rate: output messages only.
bool rateable_class(std::uint8_t cls) noexcept {
  return cls != cls::kAck && cls != cls::kCfg && cls != cls::kUpd;
}

wire::CfgPrt to_wire(const PortSettings& s) noexcept {
  wire::CfgPrt w{};
  w.portID = s.port_id;
  w.txReady = s.tx_ready;
  w.mode = s.mode;
  w.baudRate = s.baud_bps;
  w.inProtoMask = s.in_proto_mask;
  w.outProtoMask = s.out_proto_mask;
  w.flags = s.flags;
  return w;
}

bool ports_differ(const PortSettings& a, const PortSettings& b) noexcept {
  return a.mode != b.mode || a.baud_bps != b.baud_bps || a.in_proto_mask != b.in_proto_mask ||
         a.out_proto_mask != b.out_proto_mask || a.tx_ready != b.tx_ready || a.flags != b.flags;
}

bool rates_differ(const ReceiverConfig& a, const ReceiverConfig& b) noexcept {
  for (const MessageRate& m : a.rate_table()) {
    if (b.message_rates(m.id) != m.rate) return true;
  }
  for (const MessageRate& m : b.rate_table()) {
    if (a.message_rates(m.id) != m.rate) return true;
  }
  return false;
}

/// Fill the change flags and baud switches of r from before -> after.
void diff(const ReceiverConfig& before, const ReceiverConfig& after, ResponderResult& r) noexcept {
  for (std::uint8_t p = 0; p < kNumPorts; ++p) {
    if (ports_differ(before.ports[p], after.ports[p])) r.ports_changed = true;
    if (is_uart(p) && before.ports[p].baud_bps != after.ports[p].baud_bps && after.ports[p].baud_bps != 0) {
      r.new_baud_bps[p] = after.ports[p].baud_bps;
    }
  }
  if (rates_differ(before, after)) r.rates_changed = true;
  if (before.nav_period_s() != after.nav_period_s()) r.nav_rate_changed = true;
  if (std::memcmp(&before.nav5, &after.nav5, sizeof before.nav5) != 0) r.nav_config_changed = true;
}

/// Generic stored CFG messages: accepted set lengths (0 = end of list).
struct StoredSpec {
  MsgId id;
  std::uint16_t lengths[3];
};
constexpr StoredSpec kStored[] = {
    {msg::kCfgSbas, {8}},       {msg::kCfgItfm, {8}},     {msg::kCfgNavx5, {40, 44}},
    {msg::kCfgPm2, {44, 48}},   {msg::kCfgRxm, {2}},      {msg::kCfgUsb, {108}},
    {msg::kCfgAnt, {4}},        {msg::kCfgOdo, {20}},     {msg::kCfgNmea, {4, 12, 20}},
    {msg::kCfgPms, {8}},        {msg::kCfgLogfilter, {12}},
};

const StoredSpec* stored_spec(MsgId id) noexcept {
  for (const StoredSpec& s : kStored) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

bool length_ok(const StoredSpec& s, std::size_t len) noexcept {
  for (std::uint16_t l : s.lengths) {
    if (l != 0 && l == len) return true;
  }
  return false;
}

/// NAV5 dynModel values an M8 accepts (1 is reserved).
bool dyn_model_ok(std::uint8_t m) noexcept { return m == 0 || (m >= 2 && m <= 9); }

/// Apply the fields of a CFG-NAV5 set that its mask selects (UBX-13003221 CFG-NAV5).
void apply_nav5(wire::CfgNav5& cur, const wire::CfgNav5& in) noexcept {
  const std::uint16_t m = in.mask;
  if (m & 0x0001) cur.dynModel = in.dynModel;
  if (m & 0x0002) cur.minElev = in.minElev;
  if (m & 0x0004) {
    cur.fixMode = in.fixMode;
    cur.fixedAlt = in.fixedAlt;
    cur.fixedAltVar = in.fixedAltVar;
  }
  if (m & 0x0008) cur.drLimit = in.drLimit;
  if (m & 0x0010) {
    cur.pDop = in.pDop;
    cur.pAcc = in.pAcc;
  }
  if (m & 0x0020) {
    cur.tDop = in.tDop;
    cur.tAcc = in.tAcc;
  }
  if (m & 0x0040) {
    cur.staticHoldThresh = in.staticHoldThresh;
    cur.staticHoldMaxDist = in.staticHoldMaxDist;
  }
  if (m & 0x0080) cur.dgnssTimeout = in.dgnssTimeout;
  if (m & 0x0100) {
    cur.cnoThreshNumSVs = in.cnoThreshNumSVs;
    cur.cnoThresh = in.cnoThresh;
  }
  if (m & 0x0400) cur.utcStandard = in.utcStandard;
  cur.mask = 0xFFFF;  // a poll reports every field
}

}  // namespace

ConfigResponder::ConfigResponder(const ResponderConfig& config)
    : config_(config),
      encoder_(config.mon_ver),
      defaults_(ReceiverConfig::factory_defaults()),
      saved_(defaults_),
      current_(defaults_) {}

const PortSettings& ConfigResponder::port(std::uint8_t port_id) const noexcept {
  return current_.ports[std::min<std::size_t>(port_id, kNumPorts - 1)];
}

ResponderResult ConfigResponder::handle_ubx(std::uint8_t port_id, const FrameView& frame, std::string& out) {
  ResponderResult r;
  if (port_id >= kNumPorts || !current_.ports[port_id].accepts_ubx()) {
    ++stats_.ignored;
    return r;
  }
  const std::size_t start = out.size();
  const MsgId id = frame.id;
  const auto p = frame.payload;
  const auto ack = [&](bool ok) {
    UbxEncoder::ack(id, ok, out);
    r.reply = ok ? Reply::kAck : Reply::kNak;
  };
  const auto poll_reply = [&](std::span<const std::uint8_t> data) {
    append_frame(out, id, data);
    UbxEncoder::ack(id, true, out);
    r.reply = Reply::kPollData;
  };

  if (id.cls == cls::kCfg) {
    const ReceiverConfig before = current_;
    if (id == msg::kCfgPrt) {
      if (p.size() <= 1) {
        const std::uint8_t which = p.empty() ? port_id : p[0];
        if (which >= kNumPorts || !current_.ports[which].exists) {
          ack(false);
        } else {
          const wire::CfgPrt w = to_wire(current_.ports[which]);
          poll_reply({reinterpret_cast<const std::uint8_t*>(&w), sizeof w});
        }
      } else if (p.size() % sizeof(wire::CfgPrt) != 0) {
        ack(false);
      } else {
        bool ok = true;
        for (std::size_t off = 0; off < p.size(); off += sizeof(wire::CfgPrt)) {
          wire::CfgPrt w{};
          read_wire(p, w, off);
          if (w.portID >= kNumPorts || !current_.ports[w.portID].exists) ok = false;
          // A UART block must ask for what the emulated line can really be
          // set to: a standard u-blox baud and 8N1. Anything else would be
          // ACKed and then silently not applied (the daemon's lines run
          // 8N1 at the standard rates only), so it gets a NAK.
          if (ok && is_uart(w.portID) && (!is_ubx_baud(w.baudRate) || !is_8n1(w.mode))) ok = false;
        }
        if (ok) {
          for (std::size_t off = 0; off < p.size(); off += sizeof(wire::CfgPrt)) {
            wire::CfgPrt w{};
            read_wire(p, w, off);
            PortSettings& s = current_.ports[w.portID];
            s.tx_ready = w.txReady;
            s.mode = w.mode;
            if (is_uart(w.portID)) s.baud_bps = w.baudRate;
            s.in_proto_mask = w.inProtoMask;
            s.out_proto_mask = w.outProtoMask;
            s.flags = w.flags;
          }
        }
        ack(ok);
      }
    } else if (id == msg::kCfgMsg) {
      if (p.size() == 2) {
        const MsgId target{p[0], p[1]};
        if (!rateable_class(target.cls)) {
          ack(false);
        } else {
          std::uint8_t data[8] = {p[0], p[1]};
          const auto rates = current_.message_rates(target);
          std::copy(rates.begin(), rates.end(), data + 2);
          poll_reply(data);
        }
      } else if ((p.size() == 3 || p.size() == 8) && rateable_class(p[0])) {
        const MsgId target{p[0], p[1]};
        bool ok = false;
        if (p.size() == 3) {
          ok = current_.set_message_rate(port_id, target, p[2]);
        } else {
          std::array<std::uint8_t, kNumPorts> rates{};
          std::copy(p.begin() + 2, p.end(), rates.begin());
          ok = current_.set_message_rates(target, rates);
        }
        ack(ok);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgRate) {
      if (p.empty()) {
        poll_reply({reinterpret_cast<const std::uint8_t*>(&current_.rate), sizeof current_.rate});
      } else if (p.size() == sizeof(wire::CfgRate)) {
        wire::CfgRate w{};
        read_wire(p, w);
        const bool ok = w.measRate >= kMinMeasRate_ms && w.navRate >= 1 && w.navRate <= kMaxNavRate && w.timeRef <= 4;
        if (ok) current_.rate = w;
        ack(ok);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgNav5) {
      if (p.empty()) {
        poll_reply({reinterpret_cast<const std::uint8_t*>(&current_.nav5), sizeof current_.nav5});
      } else if (p.size() == sizeof(wire::CfgNav5)) {
        wire::CfgNav5 w{};
        read_wire(p, w);
        const bool ok = (!(w.mask & 0x0001) || dyn_model_ok(w.dynModel)) &&
                        (!(w.mask & 0x0004) || (w.fixMode >= 1 && w.fixMode <= 3));
        if (ok) apply_nav5(current_.nav5, w);
        ack(ok);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgGnss) {
      const StoredBlock* cur = current_.stored(msg::kCfgGnss);
      if (p.empty()) {
        poll_reply(cur->payload());
      } else if (p.size() >= 4 && p[0] == 0 && p[3] >= 1 && p.size() == 4u + 8u * p[3] && p[3] <= 7) {
        // Merge the given blocks by gnssId into the stored set (an M8 keeps
        // the systems a host does not mention).
        std::array<std::uint8_t, kMaxStoredBytes> merged{};
        std::copy(cur->bytes.begin(), cur->bytes.begin() + cur->size, merged.begin());
        std::size_t n = merged[3];
        bool ok = true;
        for (std::size_t b = 0; b < p[3]; ++b) {
          const std::uint8_t* blk = p.data() + 4 + 8 * b;
          if (blk[0] > 6) {
            ok = false;
            break;
          }
          std::size_t slot = n;
          for (std::size_t k = 0; k < n; ++k) {
            if (merged[4 + 8 * k] == blk[0]) slot = k;
          }
          if (slot == n) ++n;
          std::copy(blk, blk + 8, merged.begin() + 4 + 8 * slot);
        }
        if (ok) {
          if (p[2] != 0 && p[2] != 0xFF) merged[2] = p[2];  // numTrkChUse (0xFF = max)
          merged[3] = static_cast<std::uint8_t>(n);
          current_.store(msg::kCfgGnss, 0, {merged.data(), 4 + 8 * n});
        }
        ack(ok);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgTp5) {
      if (p.size() <= 1) {
        const std::uint8_t idx = p.empty() ? 0 : p[0];
        const StoredBlock* b = current_.stored(msg::kCfgTp5, idx);
        if (b == nullptr) {
          ack(false);
        } else {
          poll_reply(b->payload());
        }
      } else if (p.size() == 32 && p[0] <= 1) {
        current_.store(msg::kCfgTp5, p[0], p);
        ack(true);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgInf) {
      if (p.size() == 1) {
        const StoredBlock* b = current_.stored(msg::kCfgInf, p[0]);
        if (b == nullptr) {
          ack(false);
        } else {
          poll_reply(b->payload());
        }
      } else if (!p.empty() && p.size() % 10 == 0) {
        bool ok = true;
        for (std::size_t off = 0; off < p.size(); off += 10) ok = ok && p[off] <= 1;
        if (ok) {
          for (std::size_t off = 0; off < p.size(); off += 10) current_.store(msg::kCfgInf, p[off], p.subspan(off, 10));
        }
        ack(ok);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgDat) {
      if (p.empty()) {
        poll_reply(current_.stored(msg::kCfgDat)->payload());
      } else if (p.size() == 44) {
        // A set carries the user datum; the poll form adds datumNum and name.
        std::uint8_t poll[52] = {0xFF, 0xFF, 'U', 'S', 'E', 'R', 0, 0};
        std::copy(p.begin(), p.end(), poll + 8);
        current_.store(msg::kCfgDat, 0, poll);
        ack(true);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgRinv) {
      if (p.empty()) {
        poll_reply(current_.stored(msg::kCfgRinv)->payload());
      } else if (p.size() <= 31) {
        current_.store(msg::kCfgRinv, 0, p);
        ack(true);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgGeofence) {
      if (p.empty()) {
        poll_reply(current_.stored(msg::kCfgGeofence)->payload());
      } else if (p.size() >= 8 && p[1] <= 4 && p.size() == 8u + 12u * p[1]) {
        current_.store(msg::kCfgGeofence, 0, p);
        ack(true);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgPwr) {
      ack(p.size() == 8);  // command: run/stop/backup; nothing to store
    } else if (id == msg::kCfgCfg) {
      if (p.size() == 12 || p.size() == 13) {
        wire::CfgCfg w{};
        read_wire(p, w);
        if (w.clearMask != 0) saved_.copy_sections(defaults_, w.clearMask);
        if (w.saveMask != 0) saved_.copy_sections(current_, w.saveMask);
        if (w.loadMask != 0) current_.copy_sections(saved_, w.loadMask);
        ack(true);
      } else {
        ack(false);
      }
    } else if (id == msg::kCfgRst) {
      wire::CfgRst w{};
      const std::uint8_t m = p.size() == 4 ? p[2] : 0xFF;
      if (p.size() == 4 && (m == 0 || m == 1 || m == 2 || m == 4 || m == 8 || m == 9)) {
        read_wire(p, w);
        r.reset = {true, w.navBbrMask, w.resetMode};
        r.reply = Reply::kReset;
        ++stats_.resets;
        // A hardware or software reset reboots the chip: RAM configuration is
        // lost and the saved one loaded. GNSS-only resets keep it.
        if (m == 0 || m == 1 || m == 4) current_ = saved_;
        if (m != 8) navigation_restarted();
      } else {
        ack(false);
      }
    } else if (const StoredSpec* spec = stored_spec(id)) {
      const StoredBlock* cur = current_.stored(id);
      if (p.empty()) {
        poll_reply(cur->payload());
      } else if (length_ok(*spec, p.size())) {
        if (id == msg::kCfgNmea && p.size() < cur->size) {
          // Older, shorter CFG-NMEA forms set a prefix of the fields.
          std::array<std::uint8_t, kMaxStoredBytes> merged = cur->bytes;
          std::copy(p.begin(), p.end(), merged.begin());
          current_.store(id, 0, {merged.data(), cur->size});
        } else {
          current_.store(id, 0, p);
        }
        ack(true);
      } else {
        ack(false);
      }
    } else {
      // CFG-VALSET/VALGET/VALDEL and every other id an M8 lacks.
      ack(config_.ack_unknown_cfg && id != msg::kCfgValset && id != msg::kCfgValget && id != msg::kCfgValdel);
    }
    diff(before, current_, r);
  } else if (id == msg::kMonVer && p.empty()) {
    encoder_.mon_ver(out);
    r.reply = Reply::kPollData;
  } else if (id.cls == cls::kNav || id == msg::kMonHw) {
    if (p.empty() && UbxEncoder::can_encode(id)) {
      encoder_.encode(id, last_fix_, info_, out);
      r.reply = Reply::kPollData;
    }
  }

  // Replies go out only when the port (as now configured) outputs UBX.
  if (!current_.ports[port_id].outputs_ubx()) {
    out.resize(start);
    if (r.reply != Reply::kReset) r.reply = Reply::kNone;
  }
  r.bytes = out.size() - start;
  switch (r.reply) {
    case Reply::kAck: ++stats_.acks; break;
    case Reply::kNak: ++stats_.naks; break;
    case Reply::kPollData: ++stats_.polls; break;
    case Reply::kNone: ++stats_.ignored; break;
    case Reply::kReset: break;
  }
  return r;
}

ResponderResult ConfigResponder::handle_nmea(std::uint8_t port_id, std::string_view sentence, std::string& out) {
  (void)out;  // u-blox sends no answer to PUBX,40/41
  ResponderResult r;
  if (port_id >= kNumPorts || !current_.ports[port_id].accepts_nmea()) {
    ++stats_.ignored;
    return r;
  }
  const ReceiverConfig before = current_;
  if (const auto p41 = parse_pubx41(sentence)) {
    PortSettings& s = current_.ports[p41->port_id];
    if (s.exists) {
      s.in_proto_mask = p41->in_proto_mask;
      s.out_proto_mask = p41->out_proto_mask;
      if (is_uart(p41->port_id)) s.baud_bps = p41->baud_bps;
      s.autobauding = p41->autobauding;
    }
  } else if (const auto p40 = parse_pubx40(sentence)) {
    std::array<std::uint8_t, kNumPorts> rates{};
    std::copy(p40->rates.begin(), p40->rates.end(), rates.begin());
    current_.set_message_rates(MsgId{cls::kNmeaStd, p40->nmea_id}, rates);
  } else if (sentence.size() >= 11 && sentence[0] == '$' && sentence.substr(5, 2) == "Q," &&
             current_.ports[port_id].outputs_nmea()) {
    // Standard poll $ttxxQ,sss*hh, e.g. $EIGPQ,RMC*3A.
    const std::optional<nmea::Sentence> asked = nmea::sentence_by_name(sentence.substr(7, sentence.size() - 10));
    if (asked) {
      r.nmea_poll.set(*asked);
    } else {
      ++stats_.ignored;
    }
    return r;
  } else {
    ++stats_.ignored;
    return r;
  }
  diff(before, current_, r);
  return r;
}

void ConfigResponder::on_epoch(const receiver::Fix& fix, double uptime_s) noexcept {
  last_fix_ = fix;
  ++epochs_;
  const double ms = std::isfinite(uptime_s) ? std::clamp(uptime_s * 1e3, 0.0, 4294967295.0) : 0.0;
  // Whole ms; the 1 ns slack keeps a clock difference such as 100.35 - 100
  // (0.34999...) from losing a ms to binary rounding.
  constexpr double kSlackMs = 1e-6;
  info_.msss_ms = static_cast<std::uint32_t>(std::min(ms + kSlackMs, 4294967295.0));
  if (!have_fix_once_ && fix.type != receiver::FixType::kNone && fix.time_valid) {
    have_fix_once_ = true;
    // The uptime of this epoch, rounded up to the ms: a fix comes after the
    // start, and 0 on the wire means "no fix yet".
    info_.ttff_ms = static_cast<std::uint32_t>(std::max(1.0, std::ceil(ms - kSlackMs)));
  }
  const StoredBlock* itfm = current_.stored(msg::kCfgItfm);
  info_.itfm_enabled = itfm != nullptr && itfm->size >= 4 && (itfm->bytes[3] & 0x80) != 0;
}

std::size_t ConfigResponder::encode_epoch(std::uint8_t port_id, std::string& out) const {
  if (port_id >= kNumPorts || epochs_ == 0 || !current_.ports[port_id].outputs_ubx()) return 0;
  std::size_t n = 0;
  for (MsgId id : kEpochOrder) {
    const std::uint8_t rate = current_.message_rate(port_id, id);
    if (rate != 0 && (epochs_ - 1) % rate == 0) n += encoder_.encode(id, last_fix_, info_, out);
  }
  return n;
}

nmea::SentenceSet ConfigResponder::nmea_sentences(std::uint8_t port_id) const noexcept {
  nmea::SentenceSet s;
  if (port_id >= kNumPorts || epochs_ == 0 || !current_.ports[port_id].outputs_nmea()) return s;
  for (const nmea::SentenceInfo& info : nmea::kSentences) {
    const std::uint8_t rate = current_.message_rate(port_id, MsgId{nmea::kMsgClass, info.msg_id});
    s.set(info.sentence, rate != 0 && (epochs_ - 1) % rate == 0);
  }
  return s;
}

}  // namespace gnssemu::protocol::ubx

#pragma once
// ConfigResponder: the configuration side of an emulated u-blox M8 with its
// ports. Pure and deterministic, no I/O: the daemon feeds it decoded input
// frames with the port they arrived on and gets back the bytes to send on
// that port plus what changed (rates, baud, epoch period, reset). It also
// produces each port's per-epoch UBX output and NMEA sentence selection
// from the stored message rates. Behaviour and sources: docs/ubx.md.
//
// Typical use (one responder per emulated receiver):
//   ConfigResponder r({});                         // factory M8
//   r.current().ports[kPortUart1].baud_bps = 115200;  // daemon's start-up
//   r.save_current();                              // = the "flash" config
//   per input frame:  auto res = r.handle_ubx(kPortUart1, frame, tx);
//                     send tx; if res.new_baud_bps[p] switch port p after tx drained
//   per epoch:        r.on_epoch(fix, uptime_s);
//                     for each port: r.encode_epoch(p, tx); r.nmea_sentences(p)
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/protocol/ubx/ubx_config_state.hpp"
#include "core/protocol/ubx/ubx_encoder.hpp"
#include "core/protocol/ubx/ubx_frame.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::ubx {

struct ResponderConfig {
  MonVerConfig mon_ver;
  /// M8 firmware NAKs CFG ids it does not implement (that is how PX4 tells an
  /// M8 from an M9 with CFG-VALSET). true ACKs them instead (lenient hosts).
  bool ack_unknown_cfg = false;
};

/// What one input message did.
enum class Reply : std::uint8_t {
  kNone,      ///< ignored (not for us, or UBX output off on the port)
  kAck,       ///< ACK-ACK sent (a CFG set was applied)
  kNak,       ///< ACK-NAK sent
  kPollData,  ///< poll answered with data (CFG polls: data then ACK-ACK)
  kReset,     ///< CFG-RST: no answer, see ResponderResult::reset
};

/// CFG-RST request (UBX-13003221 CFG-RST).
struct ResetRequest {
  bool requested = false;
  std::uint16_t nav_bbr_mask = 0;  ///< 0x0000 hot, 0x0001 warm, 0xFFFF cold
  std::uint8_t reset_mode = 0;     ///< 0/4 hardware, 1 software, 2 GNSS only, 8 GNSS stop, 9 GNSS start
};

struct ResponderResult {
  Reply reply = Reply::kNone;
  std::size_t bytes = 0;            ///< appended to the caller's out (send on the receiving port)
  bool rates_changed = false;       ///< some port's message rates (UBX or NMEA) changed
  bool nav_rate_changed = false;    ///< CFG-RATE changed nav_period_s()
  bool ports_changed = false;       ///< a port's protocol masks, mode or baud changed
  bool nav_config_changed = false;  ///< CFG-NAV5 (or another navConf section) changed
  /// Non-zero: switch that port's line to this baud (bit/s) once the bytes
  /// already queued on it, including this reply, have been transmitted.
  std::array<std::uint32_t, kNumPorts> new_baud_bps{};
  ResetRequest reset;
  /// NMEA standard poll ($xxGPQ,sss): sentences to send once, now.
  nmea::SentenceSet nmea_poll;
};

/// Counters for logs and tests.
struct ResponderStats {
  std::uint64_t acks = 0, naks = 0, polls = 0, resets = 0;
  std::uint64_t ignored = 0;  ///< non-CFG input we do not answer, or input on a port with that protocol off
};

class ConfigResponder {
public:
  /// Throws gnssemu::Error for a bad MON-VER config.
  explicit ConfigResponder(const ResponderConfig& config);

  /// A UBX frame received on port_id (0..5). Replies are appended to out.
  /// Never throws; no allocation once out has capacity (out.size() + 2 KiB).
  ResponderResult handle_ubx(std::uint8_t port_id, const FrameView& frame, std::string& out);
  /// An NMEA sentence (as StreamDecoder delivers it, checksum verified)
  /// received on port_id: $PUBX,41 (port protocols and baud), $PUBX,40
  /// (NMEA rates), $xxGPQ/GNQ polls. Others are ignored.
  ResponderResult handle_nmea(std::uint8_t port_id, std::string_view sentence, std::string& out);

  /// Start of a navigation epoch: keeps fix for encode_epoch and NAV polls,
  /// counts epochs for rates > 1. uptime_s: time since start-up or the last
  /// reset (monotonic, s), for NAV-STATUS msss and ttff.
  void on_epoch(const receiver::Fix& fix, double uptime_s) noexcept;
  /// Navigation restarted (a reset on this or another port of the chip):
  /// the next fix is a first fix again, its ttff measured anew.
  void navigation_restarted() noexcept {
    have_fix_once_ = false;
    info_.ttff_ms = 0;
  }
  /// Append the UBX messages due on port_id this epoch (rate divides the
  /// epoch count, UBX in outProtoMask), NAV in id order, MON-HW after, NAV-EOE
  /// last. Returns bytes. No allocation once out has capacity (+ kMaxEpochBytes).
  std::size_t encode_epoch(std::uint8_t port_id, std::string& out) const;
  /// NMEA sentences due on port_id this epoch (CFG-MSG 0xF0 rates; none when
  /// NMEA is off in outProtoMask).
  nmea::SentenceSet nmea_sentences(std::uint8_t port_id) const noexcept;

  /// Current (RAM) configuration. Mutable for start-up settings; call
  /// save_current() afterwards so CFG-CFG load and resets restore them.
  ReceiverConfig& current() noexcept { return current_; }
  const ReceiverConfig& current() const noexcept { return current_; }
  /// The saved (BBR/flash) configuration loaded at start-up and reset.
  const ReceiverConfig& saved() const noexcept { return saved_; }
  void save_current() noexcept { saved_ = current_; }

  /// Shorthands over current().
  const PortSettings& port(std::uint8_t port_id) const noexcept;
  double nav_period_s() const noexcept { return current_.nav_period_s(); }
  std::uint8_t message_rate(std::uint8_t port_id, MsgId id) const noexcept {
    return current_.message_rate(port_id, id);
  }

  const UbxEncoder& encoder() const noexcept { return encoder_; }
  const ResponderStats& stats() const noexcept { return stats_; }
  std::uint64_t epoch_count() const noexcept { return epochs_; }

private:
  ResponderConfig config_;
  UbxEncoder encoder_;
  ReceiverConfig defaults_, saved_, current_;
  receiver::Fix last_fix_{};
  EpochInfo info_{};
  std::uint64_t epochs_ = 0;
  bool have_fix_once_ = false;
  ResponderStats stats_;
};

}  // namespace gnssemu::protocol::ubx

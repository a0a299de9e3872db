// SPDX-License-Identifier: Apache-2.0
#pragma once
// Device: the one emulated u-blox M8 behind every output of the emulator.
// Each output is a UART1 of this chip (a host on any output configures "its"
// port 1); the navigation rate, NAV5, the stored CFG blocks, the DDC, USB
// and SPI settings, the saved configuration, uptime, time to first fix and
// resets exist once. Pure and deterministic, no I/O: callers feed it
// decoded input with the output it arrived on and the epochs' Fixes, and
// get back replies and, per output and epoch, the framed messages due.
// Behaviour and sources: docs/ubx.md.
//
//   Device d(setup);                      // factory M8 + the outputs' start-up settings, saved
//   d.power_on(now_s);
//   per input frame:  InputResult r = d.handle_ubx(output, frame, now_s, reply);
//                     send reply; r.new_baud_bps: switch the line after it drained;
//                     r.reset / r.nav_rate_changed: restart navigation, reschedule at d.epoch_period_s()
//   per epoch:        d.on_epoch(fix, now_s);
//                     for each output: d.compose(output, list); send list.messages()
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/protocol/ubx/config/ubx_cfg_nmea.hpp"
#include "core/protocol/ubx/config/ubx_config_keys.hpp"
#include "core/protocol/ubx/config/ubx_device_config.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/config/ubx_gnss.hpp"
#include "core/protocol/ubx/handlers/ubx_handlers.hpp"
#include "core/protocol/ubx/config/ubx_hpg.hpp"
#include "core/protocol/ubx/wire/ubx_message_list.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "core/protocol/ubx/config/ubx_reset.hpp"
#include "core/protocol/ubx/device/ubx_rtcm_input.hpp"
#include "core/protocol/ubx/device/ubx_rtcm_output.hpp"
#include "core/protocol/ubx/wire/ubx_rxm.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::ubx {

/// Epoch periods the emulator runs, s (1..10 Hz, docs/configuration.md
/// rate_hz): a CFG-RATE outside is stored as set and run at the nearest.
inline constexpr double kMinEpochPeriodS = 0.1;
inline constexpr double kMaxEpochPeriodS = 1.0;

/// Beyond this RTK baseline the ZED-F9P warns INF-WARNING "DGNSS baseline
/// big" (ZED-F9P Integration Manual R08 §3.1.5.4), m.
inline constexpr double kBaselineBigM = 50.0e3;
/// How often the warning repeats while the baseline stays beyond, s. u-blox
/// does not document it; ours: once when it starts, then at most every 60 s.
inline constexpr double kBaselineBigRepeatS = 60.0;

/// A CFG-MSG rate: id sent every rate navigation epochs (0 = off).
struct MessageRate {
  MsgId id;
  std::uint8_t rate = 1;
};

/// One output's UART1 at start-up (the daemon's [[output]]).
struct OutputSetup {
  std::uint32_t baud_bps = 0;  ///< line rate, bit/s; 0: the port has no line, UART1 keeps 9600
  std::uint16_t protocols_in = proto::kUbx | proto::kNmea;   ///< inProtoMask UBX/NMEA bits; 0: no input at all
  std::uint16_t protocols_out = proto::kUbx | proto::kNmea;  ///< outProtoMask UBX/NMEA bits
  /// Rates on this UART1, UBX and NMEA (class 0xF0); NMEA sentences not
  /// listed are off, UBX messages not listed stay off.
  std::vector<MessageRate> rates;
  nmea::NmeaVersion nmea_version = nmea::NmeaVersion::k411;
  double course_min_speed_m_s = 0.5;  ///< NMEA course blanking, m/s (>= 0, see nmea::NmeaConfig)
};

struct DeviceSetup {
  /// The chip's identity; its generation decides the configuration interface
  /// and the output messages (ubx_generation.hpp). mon_ver_of(g) for a factory chip.
  MonVerConfig mon_ver;
  /// M8 firmware NAKs CFG ids it does not implement (that is how PX4 tells an
  /// M8 from an M9 with CFG-VALSET). true ACKs them instead (lenient hosts).
  bool ack_unknown_cfg = false;
  /// Epoch period at start-up, s (> 0): CFG-RATE measRate round(1000 period) ms, navRate 1.
  double nav_period_s = 1.0;
  /// CFG-NAV5 at start-up: dynModel (0 portable, 2..9), staticHoldThresh
  /// (cm/s) and staticHoldMaxDist (m), as the receiver is configured.
  std::uint8_t dyn_model = 0;
  std::uint8_t static_hold_thresh_cm_s = 0;
  std::uint16_t static_hold_max_dist_m = 0;
  /// An extrapolated solution (receiver::FixType::kDeadReckoning) is
  /// reported as no fix on every port (receiver::CoastReport::kNoFix).
  bool coast_as_no_fix = true;
  /// The firmware is a variant with raw data output (a NEO-M8T/M8P class
  /// TIM or HPG firmware, a u-blox 9 HPG): RXM-RAWX and RXM-SFRBX go out
  /// where a host enables them. A NEO-M8N's or NEO-M9N's standard firmware
  /// has none; they then stay silent at any rate (docs/raw-output.md).
  bool raw_firmware = false;
  /// CFG-SBAS usage diffCorr from the factory ([receiver] sbas): SBAS
  /// corrections applied (a u-blox's factory setting) or not.
  bool sbas_diffcorr = true;
  /// One per output; empty: one factory UART1.
  std::vector<OutputSetup> outputs;
  /// Systems the emulator puts in the sky ([receiver] constellations). The
  /// NMEA sentences give each enabled system among them its GSA and GSV even
  /// with no satellite; an enabled system the world does not model stays
  /// silent instead of printing empty sentences forever.
  SystemSet sky_systems = SystemSet::only(GnssSystem::kGps);  // world::WorldConfig::systems default
};

/// Order of an epoch's messages.
enum class Layout : std::uint8_t {
  /// One line carrying both protocols, as a u-blox sends them (gpsd's
  /// ublox-zed-f9t-ubx_nmea_l5.log): UBX position and velocity, the NMEA
  /// sentences, the other UBX messages, NAV-EOE last.
  kLine,
  /// Each protocol in its own order, UBX first: NAV by id, MON-HW, NAV-EOE
  /// last; then NMEA. What separate UBX and NMEA logs of the port hold.
  kPerProtocol,
};

/// Where a host is attached: UART1 of an output (what the daemon wires every
/// output to), or another port of the chip as that host sees it.
struct Link {
  std::size_t output = 0;
  std::uint8_t port_id = kPortUart1;
};

/// What one input message did.
struct InputResult {
  Reply reply = Reply::kNone;
  std::size_t bytes = 0;        ///< reply bytes appended to the caller's out (send on the receiving port)
  std::string_view label;       ///< the reply's first message ("ACK-ACK", "MON-VER", "GGA"), for logs
  bool rates_changed = false;   ///< some port's message rates (UBX or NMEA) changed
  bool nav_rate_changed = false;  ///< CFG-RATE changed, see Device::epoch_period_s()
  bool ports_changed = false;   ///< some port's protocol masks, mode or baud changed (any output's UART1)
  bool nav_config_changed = false;  ///< CFG-NAV5 changed
  /// RTCM 3 changed the corrections (Corrections::revision): a moving-base
  /// rover may have its epoch's baseline now (pipeline::Pipeline::on_corrections).
  bool corrections_changed = false;
  /// The GNSS selection changed (CFG-GNSS, CFG-SIGNAL-* or a load of the
  /// saved configuration): a real chip restarts its GNSS engine; the
  /// receiver restarts tracking with Device::enabled_systems().
  bool gnss_changed = false;
  /// The NMEA settings changed (CFG-NMEA, CFG-NMEA-* keys): Device::nmea_settings().
  bool nmea_config_changed = false;
  /// The F9P's RTK, UART2 or base-mode settings changed: Device::hpg_settings().
  bool hpg_changed = false;
  /// The saved (BBR/flash) configuration changed (CFG-CFG save or clear,
  /// VALSET/VALDEL to BBR or Flash): write the state file (Device::saved()).
  bool saved_changed = false;
  /// Non-zero: switch the host's line (the UART1 of its output) to this baud
  /// (bit/s) once the bytes already queued on it, this reply included, are sent.
  std::uint32_t new_baud_bps = 0;
  std::optional<Reset> reset;   ///< CFG-RST: applied to the whole chip
  /// NMEA standard poll ($xxGPQ,sss): the sentences asked for, answered in
  /// the reply once an epoch has run.
  nmea::SentenceSet nmea_poll;
};

/// Counters for logs and tests.
struct DeviceStats {
  std::uint64_t acks = 0, naks = 0, polls = 0, resets = 0;
  std::uint64_t ignored = 0;  ///< non-CFG input we do not answer, or input on a port with that protocol off
};

/// CFG-SBAS mode b0 (SBAS enabled: GEOs tracked) and usage b1 diffCorr
/// (their corrections applied).
struct SbasSettings {
  bool enabled = true;
  bool diffcorr = true;
};

class Device {
public:
  /// Throws gnssemu::Error for a bad MON-VER config or NMEA setting.
  explicit Device(const DeviceSetup& setup);

  /// Outputs (UART1s), >= 1.
  std::size_t outputs() const noexcept { return nmea_.size(); }

  /// Power-on at now_s (a monotonic clock, s): uptime and ttff count from it,
  /// no fix yet, the epoch count for rates > 1 starts over; the configuration
  /// stays as it is (the daemon powers the chip on again where a lockstep run starts).
  void power_on(double now_s) noexcept {
    uptime_origin_s_ = now_s;
    have_fix_once_ = false;
    info_.ttff_ms = 0;
    epochs_ = 0;
    baseline_big_ = baseline_big_due_ = false;
  }

  /// A UBX frame received at at; now_s: the same clock as power_on (a reset
  /// restarts uptime). Replies are appended to out. Never throws; no
  /// allocation once out has capacity (out.size() + 2 KiB).
  InputResult handle_ubx(Link at, const FrameView& frame, double now_s, std::string& out);
  /// An NMEA sentence (as StreamDecoder delivers it, checksum verified)
  /// received at at: $PUBX,41 (port protocols and baud), $PUBX,40 (NMEA
  /// rates), $xxGPQ/GNQ polls (answered in out). Others are ignored.
  InputResult handle_nmea(Link at, std::string_view sentence, std::string& out);
  /// An RTCM 3 frame's payload received at at (crc_ok false: its CRC
  /// failed): decoded into corrections() where the port's inProtoMask has
  /// RTCM3, ignored elsewhere; an RXM-RTCM in out where at enables it.
  /// Never throws; no allocation once out has capacity.
  InputResult handle_rtcm(Link at, std::span<const std::uint8_t> payload, bool crc_ok, std::string& out);
  /// The corrections the ports' RTCM input filled (the receiver reads them).
  const receiver::Corrections& corrections() const noexcept { return rtcm_.corrections(); }
  /// The correction input: counters, and the link-outage fault.
  const RtcmInput& rtcm_input() const noexcept { return rtcm_; }
  RtcmInput& rtcm_input() noexcept { return rtcm_; }

  /// Start of a navigation epoch at now_s: keeps fix for compose() and
  /// polls, counts epochs for rates > 1, updates uptime and ttff. raw: the
  /// epoch's raw measurements and broadcast ephemerides for RXM-RAWX and
  /// RXM-SFRBX (its pointers must stay valid until the epoch is composed);
  /// empty: those messages are not sent.
  void on_epoch(const receiver::Fix& fix, double now_s, const RawSource& raw = {}) noexcept;
  /// The messages due at at this epoch (rates divide the epoch count;
  /// protocols per outProtoMask) in layout's order; an F9P's INF-WARNING
  /// "DGNSS baseline big" last among the UBX ones where CFG-INF (CFG-INFMSG-UBX_*)
  /// enables UBX warnings on the port. No allocation
  /// (MessageList reserves for the largest epoch). reported: the fix type
  /// every message that carries one reports on this port instead of the
  /// receiver's (a wrong_fix link fault, docs/faults.md); nothing: the receiver's.
  void compose(Link at, MessageList& out, Layout layout = Layout::kLine,
               FixOverride reported = std::nullopt) const noexcept;
  /// A moving-base rover's NAV-RELPOSNED of this epoch, solved when the
  /// base's epoch arrived after the epoch's output (the F9P sends it then,
  /// docs/rtk.md "Relative position"): rp replaces the epoch's.
  void on_relative_position(const receiver::RelativePosition& rp) noexcept { last_fix_.rel_pos = rp; }
  /// That NAV-RELPOSNED on at, where this epoch has it due; out empty otherwise.
  void compose_relposned(Link at, MessageList& out) const noexcept;
  /// NMEA sentences due at at this epoch (CFG-MSG class 0xF0 rates).
  nmea::SentenceSet nmea_due(Link at) const noexcept;
  /// outProtoMask bits of the protocols at at that have a message at a
  /// non-zero rate: what the port sends each epoch.
  std::uint16_t protocols_sent(Link at) const noexcept;

  /// The epoch period the emulator runs, s: the start-up period until a host
  /// changes CFG-RATE (or a reset or CFG-CFG load does), then measRate *
  /// navRate clamped to [kMinEpochPeriodS, kMaxEpochPeriodS].
  double epoch_period_s() const noexcept { return epoch_period_s_; }

  /// Current (RAM) configuration. Mutable for start-up settings; call
  /// save_config() afterwards so CFG-CFG load and resets restore them.
  DeviceConfig& config() noexcept { return current_; }
  const DeviceConfig& config() const noexcept { return current_; }
  /// DeviceSetup::coast_as_no_fix changed (a reload of [receiver.nav]).
  void set_coast_as_no_fix(bool on) noexcept { coast_as_no_fix_ = on; }
  /// The saved (BBR/flash) configuration loaded at start-up and reset.
  const DeviceConfig& saved() const noexcept { return saved_; }
  void save_config() { saved_ = current_; }
  /// Power up from a saved configuration (a state file's): it becomes the
  /// saved and the current one, as a module loads BBR/flash at boot.
  void load_saved(const DeviceConfig& saved);
  /// The NMEA output settings as CFG-NMEA now holds them (the chip's, every UART1).
  CfgNmeaSettings nmea_settings() const noexcept { return cfg_nmea_settings(current_); }
  /// The systems the receiver tracks (CFG-GNSS / CFG-SIGNAL-* as now set).
  SystemSet enabled_systems() const noexcept;
  /// Navigation rate limits of the chip with those systems (ubx_gnss.hpp).
  NavRateLimits nav_rate_limits() const noexcept;
  /// Tracking channels in all and per system (CFG-GNSS as now set).
  ChannelLimits channel_limits() const noexcept;
  /// CFG-SBAS as now set (the M9's CFG-SBAS-USE_* keys map onto it).
  SbasSettings sbas_settings() const noexcept;
  /// The ZED-F9P's RTK mode, correction time-out, UART2 and base (time)
  /// mode as now configured (ubx_hpg.hpp; factory values on other generations).
  HpgSettings hpg_settings() const noexcept { return ubx::hpg_settings(current_); }

  /// Settings of the port at at.
  const PortSettings& port(Link at) const noexcept { return current_.port(column(at)); }
  std::uint8_t message_rate(Link at, MsgId id) const noexcept { return current_.message_rate(column(at), id); }

  const UbxEncoder& encoder() const noexcept { return encoder_; }
  Generation generation() const noexcept { return encoder_.mon_ver_config().generation; }
  const DeviceStats& stats() const noexcept { return stats_; }
  std::uint64_t epoch_count() const noexcept { return epochs_; }
  /// Uptime and time to first fix as of the last on_epoch (NAV-STATUS msss, ttff).
  const EpochInfo& epoch_info() const noexcept { return info_; }

private:
  bool valid(Link at) const noexcept { return at.output < outputs() && at.port_id < kNumPorts; }
  std::size_t column(Link at) const noexcept { return current_.column(at.output, at.port_id); }
  bool due(std::size_t column, MsgId id) const noexcept;
  /// The port at column (u-blox port port_id) sends UBX and CFG-INF enables the INF bit on it.
  /// The port's CFG-INF infMsgMask has bit for protocol (0 UBX, 1 NMEA), and the port outputs that protocol.
  bool inf_enabled(std::size_t column, std::uint8_t port_id, std::uint8_t bit, std::uint8_t protocol) const noexcept;
  /// Some port sends id this epoch with RTCM 3 in its outProtoMask.
  bool rtcm_wanted(MsgId id) const noexcept;
  /// Fill the change flags of r and the host's baud switch from before_ to current_.
  void diff(Link at, InputResult& r) const noexcept;
  void restart_navigation(double now_s) noexcept;
  /// Append a raw-data message (RXM-RAWX, RXM-SFRBX) of the last epoch.
  void raw_message(const PeriodicMessage& m, MessageList& out) const noexcept;
  void after_input(const InputResult& r) noexcept;
  /// The NMEA encoders follow the enabled systems and, when from_cfg_nmea,
  /// every field of the stored CFG-NMEA.
  void apply_nmea(bool from_cfg_nmea) noexcept;

  bool ack_unknown_cfg_;
  bool coast_as_no_fix_;
  bool raw_firmware_;
  UbxEncoder encoder_;
  std::vector<nmea::NmeaEncoder> nmea_;  ///< per output
  DeviceConfig defaults_, saved_, current_;
  DeviceConfig before_;  ///< current_ before the input being handled (no allocation per input)
  DeviceConfig saved_before_;  ///< saved_ before it
  ValTransaction val_;   ///< CFG-VALSET transaction and scratch configurations (M9)
  SystemSet sky_systems_;
  double epoch_period_s_;
  double uptime_origin_s_ = 0.0;  ///< power-on or the last reset that restarted navigation
  receiver::Fix last_fix_{};
  EpochInfo info_{};
  std::uint64_t epochs_ = 0;
  bool have_fix_once_ = false;
  RawSource raw_;          ///< the last epoch's raw data
  double raw_period_s_ = 0.0;  ///< time since the previous epoch's raw data, s
  time::GpsTime last_raw_t_;
  DeviceStats stats_;
  /// INF-WARNING "DGNSS baseline big": the RTK baseline is beyond
  /// kBaselineBigM now (since the epoch it went beyond), sent this epoch, and when last sent.
  bool baseline_big_ = false;
  bool baseline_big_due_ = false;
  double baseline_big_sent_s_ = 0.0;
  RtcmInput rtcm_;  ///< RTCM 3 from the ports' hosts
  RtcmOutput rtcm_out_;  ///< the F9P's own RTCM 3 of the last epoch (a moving base)
};

}  // namespace gnssemu::protocol::ubx

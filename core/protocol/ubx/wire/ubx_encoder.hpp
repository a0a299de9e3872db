// SPDX-License-Identifier: Apache-2.0
#pragma once
// UBX output encoders of a u-blox M8 (protocol 18-23) and M9 (protocol 32,
// ubx_generation.hpp). Every message reads
// the same receiver::Fix (and its per-satellite state) as the NMEA encoder,
// so numSV, DOP, hAcc/vAcc and C/N0 agree across protocols. Conventions
// where u-blox leaves a choice are listed in docs/ubx.md.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/protocol/nmea/reported_fix.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/config/ubx_generation.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::ubx {

/// What MON-VER reports. Defaults: a NEO-M8N with firmware SPG 3.01
/// (protocol 18.00), as seen in public MON-VER dumps (docs/ubx.md).
struct MonVerConfig {
  std::string sw_version = "ROM CORE 3.01 (107888)";  ///< <= 29 characters
  std::string hw_version = "00080000";                ///< <= 9 characters; 00080000 = M8
  /// Firmware running from flash over a ROM: its first extension, before
  /// FWVER ("ROM BASE 0x118B2060" on a NEO-M9N); empty for ROM firmware.
  std::string rom_base;
  std::string fw_version = "SPG 3.01";                ///< sent as "FWVER=<fw_version>"
  /// Sent as "PROTVER=%05.2f". An M8 speaks 18.00 .. 23.01, an M9 27 and
  /// later (PX4 switches to CFG-VALSET from 27).
  double protocol_version = 18.00;
  /// Further extension strings after FWVER and PROTVER (each <= 29 chars, <= 8 of them).
  std::vector<std::string> extensions = {"GPS;GLO;GAL;BDS", "SBAS;IMES;QZSS"};
  Generation generation = Generation::kM8;  ///< must agree with protocol_version
};

/// MON-VER of a factory chip of generation g: the M8 above, or a NEO-M9N
/// module (flash firmware SPG 4.04 over ROM 4.04) as field logs and
/// ubxtool dumps show it: EXT CORE 4.04 (7f89f7), 00190000, ROM BASE
/// 0x118B2060, FWVER=SPG 4.04, PROTVER=32.01, MOD=NEO-M9N (docs/ubx.md
/// §Generations). ArduPilot takes "EXT CORE 4" with 00190000 for an M9.
MonVerConfig mon_ver_of(Generation g);

/// Throws gnssemu::Error("ubx", 0, reason) on a string too long, a hwVersion
/// that is not 8 hex digits, or a protocol version outside its generation's
/// range ([18, 24) for an M8, [27, 50) for an M9).
void validate(const MonVerConfig& config);

/// CFG-ITFM factory thresholds of the interference monitor, dB above normal
/// (the M8 and M9 default configuration: bbThreshold 3, cwThreshold 15).
inline constexpr double kFactoryItfmBbThreshold_db = 3.0;
inline constexpr double kFactoryItfmCwThreshold_db = 15.0;

/// The jamming/interference monitor as CFG-ITFM (or its CFG-ITFM-* keys on
/// an M9) configures it; itfm_settings() reads it from a configuration.
struct ItfmSettings {
  /// The monitor runs and MON-HW, MON-RF and SEC-SIG report its jammingState
  /// (else 0 = unknown). Off from the factory on both generations (docs/ubx.md).
  bool enabled = false;
  /// Interference is flagged this far above normal, dB: broadband [0, 15], CW [0, 31].
  double bb_threshold_db = kFactoryItfmBbThreshold_db;
  double cw_threshold_db = kFactoryItfmCwThreshold_db;
};

/// Receiver state that is not part of a Fix (kept by the responder).
struct EpochInfo {
  std::uint32_t msss_ms = 0;  ///< ms since start-up or reset (NAV-STATUS msss)
  std::uint32_t ttff_ms = 0;  ///< time to first fix, ms; 0 = no fix yet
  ItfmSettings itfm;  ///< the interference monitor's settings
  /// Fix type NAV-PVT, NAV-STATUS and NAV-SOL report instead of the Fix's
  /// (a wrong_fix link fault); nothing: the Fix's.
  FixOverride reported_fix;
};

/// Largest output of one epoch with every message enabled and
/// kMaxSatsInView satellites (NAV-SAT, NAV-SVINFO about 1.2-1.6 KB each,
/// NAV-SIG of both bands 3.1 KB). Reserve out.size() + this to never allocate.
inline constexpr std::size_t kMaxEpochBytes = 12288;

/// Encoders append one complete frame to out and return the bytes appended.
/// They never throw; they allocate only when out lacks capacity. A Fix
/// without valid time or with a non-finite position is sent as no fix
/// (fixType 0, gnssFixOK clear, zero position, large accuracies).
class UbxEncoder {
public:
  /// Validates config (throws gnssemu::Error) and preformats MON-VER.
  explicit UbxEncoder(const MonVerConfig& config = {});

  std::size_t nav_pvt(const receiver::Fix& fix, std::string& out) const;
  std::size_t nav_posllh(const receiver::Fix& fix, std::string& out) const;
  std::size_t nav_status(const receiver::Fix& fix, const EpochInfo& info, std::string& out) const;
  std::size_t nav_dop(const receiver::Fix& fix, std::string& out) const;
  std::size_t nav_sol(const receiver::Fix& fix, std::string& out) const;
  std::size_t nav_velned(const receiver::Fix& fix, std::string& out) const;
  std::size_t nav_timegps(const receiver::Fix& fix, std::string& out) const;
  std::size_t nav_timeutc(const receiver::Fix& fix, std::string& out) const;
  /// One entry per satellite in fix.sats[0..num_sats), every system, by
  /// gnssId then svId (QZSS 1-10, SBAS 120-158, GLONASS slot).
  std::size_t nav_sat(const receiver::Fix& fix, std::string& out) const;
  /// One channel per satellite in fix.sats[0..num_sats) as an M8 numbers it
  /// (svinfo_svid in ubx_gnss.hpp); chipGen 4 (M8).
  std::size_t nav_svinfo(const receiver::Fix& fix, std::string& out) const;
  /// NAV-SIG version 0 (M9, F9P): one L1-band signal per satellite (sigId 0;
  /// BeiDou GEOs 1 = B1I D2), on the F9P followed by its second-band signal
  /// (gnss_signals.hpp sigIds), GLONASS freqId k + 7, C/N0, quality, and
  /// which measurements and corrections the solution used.
  std::size_t nav_sig(const receiver::Fix& fix, std::string& out) const;
  /// NAV-TIMEGLO: GLONASS time (UTC + 3 h) as time of day, day in the four-year
  /// period and period number since 1996 (ICD GLONASS 5.1 N4, NT).
  std::size_t nav_timeglo(const receiver::Fix& fix, std::string& out) const;
  /// NAV-TIMEGAL: GST = GPST with weeks counted from GPS week 1024.
  std::size_t nav_timegal(const receiver::Fix& fix, std::string& out) const;
  /// NAV-TIMEBDS: BDT = GPST - 14 s with weeks counted from GPS week 1356.
  std::size_t nav_timebds(const receiver::Fix& fix, std::string& out) const;
  /// MON-HW2: I/Q imbalance and magnitude from the front end of MON-HW;
  /// configuration source flash, POST status 0 (constants).
  std::size_t mon_hw2(const receiver::Fix& fix, const EpochInfo& info, std::string& out) const;
  std::size_t nav_eoe(const receiver::Fix& fix, std::string& out) const;
  /// Noise level, AGC, jamming indicator and monitor state (ubx_front_end.hpp).
  std::size_t mon_hw(const receiver::Fix& fix, const EpochInfo& info, std::string& out) const;
  /// MON-RF version 0 with one block (blockId 0, L1): the same front end as MON-HW.
  std::size_t mon_rf(const receiver::Fix& fix, const EpochInfo& info, std::string& out) const;
  /// SEC-SIG version 1: jamming monitor as MON-RF, spoofing as NAV-STATUS.
  std::size_t sec_sig(const receiver::Fix& fix, const EpochInfo& info, std::string& out) const;
  std::size_t mon_ver(std::string& out) const;
  /// MON-GNSS version 1 of generation g with enabled the systems switched on.
  static std::size_t mon_gnss(Generation g, SystemSet enabled, std::string& out);
  /// ACK-ACK (ack = true) or ACK-NAK for the input message acked.
  static std::size_t ack(MsgId acked, bool ack, std::string& out);

  /// Encode message id from fix (the NAV/MON/SEC ids above), with the fix type
  /// info.reported_fix says if it says one. Returns 0 for ids this encoder
  /// does not produce and for messages the configured generation lacks
  /// (message_exists in ubx_message_table.hpp).
  std::size_t encode(MsgId id, const receiver::Fix& fix, const EpochInfo& info, std::string& out) const;
  /// True when encode() produces id on some generation.
  static bool can_encode(MsgId id) noexcept;

  const MonVerConfig& mon_ver_config() const noexcept { return config_; }

private:
  /// NAV-PVT / NAV-SOL with fixType (gpsFix) and gnssFixOK as reported says
  /// (nothing: the Fix's).
  std::size_t nav_pvt_as(const receiver::Fix& fix, FixOverride reported, std::string& out) const;
  std::size_t nav_sol_as(const receiver::Fix& fix, FixOverride reported, std::string& out) const;
  MonVerConfig config_;
  std::string mon_ver_payload_;
};

/// iTOW (ms) of fix.t, rounded to the nearest ms.
std::uint32_t itow_ms(const receiver::Fix& fix) noexcept;

/// gnssFixOK as NAV-PVT and NAV-STATUS report it for fix: a GNSS position
/// with time (not dead reckoning), or what reported says instead.
bool reports_fix_ok(const receiver::Fix& fix, FixOverride reported = std::nullopt) noexcept;

}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
#pragma once
// RTCM 3 decoder: CRC-checked payloads (a FrameReader's, or the UBX port
// decoder's) into a rover's receiver::Corrections. MSM4 to MSM7 of GPS,
// GLONASS, Galileo, QZSS, BeiDou and SBAS (RTCM 10403.3 §3.5.6), 1005/1006
// (§3.5.3), 1230 and u-blox's 4072 (rtcm_ublox.hpp). The MSMs of one epoch
// (multiple-message bit DF393) are gathered and handed over as one RawEpoch
// when the last arrives. Epoch times are resolved against the rover's GPS
// time: GPS, Galileo and QZSS time of week, BeiDou BDT = GPST - 14 s,
// GLONASS day of week and time of day in Moscow time (UTC + 3 h). Signals
// map to SignalId through the signal table (core/common/gnss_signals.hpp);
// others are counted and ignored. Fixed memory, never throws, no allocation.
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "core/receiver/corrections.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::protocol::rtcm {

/// What one message was, for UBX-RXM-RTCM and logs.
struct DecodeResult {
  int message = 0;       ///< DF002 (0: a payload too short to have one)
  int subtype = 0;       ///< 4072 sub-type, else 0
  int station_id = 0;    ///< DF003 where the message has one, else 0
  /// The corrections took it (RXM-RTCM msgUsed 2); false: recognised but
  /// not used, unknown or bad (msgUsed 1).
  bool used = false;
  bool epoch_complete = false;  ///< this message completed a base epoch (Corrections::obs)
};

/// Counts per reason (every payload decoded lands in exactly one of
/// msm, station, glonass_biases, ublox, not_used, unknown_messages, bad_masks, truncated).
struct DecoderStats {
  std::uint64_t msm = 0;               ///< MSM4-7 decoded
  std::uint64_t station = 0;           ///< 1005/1006
  std::uint64_t glonass_biases = 0;    ///< 1230
  std::uint64_t ublox = 0;             ///< 4072, every sub-type
  std::uint64_t ublox_subtype[2]{};    ///< 4072.0, 4072.1
  /// Known messages a rover does not use here (ephemerides, MSM1-3,
  /// antenna and receiver descriptors).
  std::uint64_t not_used = 0;
  std::uint64_t unknown_messages = 0;  ///< message numbers not in RTCM 3.3's table for a rover
  /// MSMs whose masks do not agree with each other or the payload length
  /// (more than 64 cells, fields beyond the payload): dropped whole.
  std::uint64_t bad_masks = 0;
  std::uint64_t truncated = 0;         ///< station, bias or 4072 payloads shorter than their fields
  std::uint64_t bad_time = 0;          ///< an MSM epoch field out of range (dropped)
  std::uint64_t unknown_signals = 0;   ///< MSM cells of signals outside the signal table (ignored)
  std::uint64_t unknown_satellites = 0;  ///< MSM satellites outside their system's numbering (ignored)
  std::uint64_t overflow_cells = 0;    ///< cells beyond one epoch's kMaxRawMeasurements, or repeated
  std::uint64_t epochs = 0;            ///< complete epochs handed over
  /// Epochs whose last MSM never came (the next epoch began first): handed
  /// over when the next began.
  std::uint64_t unterminated_epochs = 0;
};

class Decoder {
public:
  Decoder() noexcept { glonass_fcn_.fill(kUnknownFcn); }

  /// One payload (message number in its first 12 bits, CRC already
  /// checked) into out. now: the rover's GPS time (resolves the epoch's
  /// week and day, stamps arrival). leap_seconds: GPS - UTC, s (GLONASS time).
  DecodeResult decode(std::span<const std::uint8_t> payload, time::GpsTime now, receiver::Corrections& out,
                      int leap_seconds = 18) noexcept;

  /// Forget a partly received epoch (the link was reset).
  void reset() noexcept { pending_valid_ = false; }

  /// The GLONASS frequency channel of slot (1..27), -7..6, for MSM4
  /// (which has none): the carrier phase of a slot whose channel is not
  /// known is reported invalid. MSM5-7 teach it on their own.
  void set_glonass_channel(int slot, int channel) noexcept;

  const DecoderStats& stats() const noexcept { return stats_; }

private:
  static constexpr std::int8_t kUnknownFcn = 127;
  bool decode_msm(std::span<const std::uint8_t> payload, int number, time::GpsTime now, int leap_seconds,
                  DecodeResult& res) noexcept;
  bool decode_station(std::span<const std::uint8_t> payload, int number, time::GpsTime now, DecodeResult& res) noexcept;
  bool decode_biases(std::span<const std::uint8_t> payload, DecodeResult& res) noexcept;
  bool decode_ublox(std::span<const std::uint8_t> payload, time::GpsTime now, DecodeResult& res) noexcept;
  /// Hands the pending epoch to out_.
  void complete(time::GpsTime now) noexcept;

  receiver::Corrections* out_ = nullptr;  ///< during decode() only
  receiver::RawEpoch pending_;
  bool pending_valid_ = false;
  int pending_station_ = 0;
  std::array<std::int8_t, 28> glonass_fcn_{};  ///< by slot
  DecoderStats stats_;
};

/// The GPS time of an MSM epoch field (DF004, DF248, DF427, or DF416 and
/// DF034 for GLONASS) of system sys, the instant nearest to now; nullopt
/// for a field out of range.
std::optional<time::GpsTime> msm_epoch_time(GnssSystem sys, std::uint32_t field, time::GpsTime now,
                                            int leap_seconds) noexcept;

}  // namespace gnssemu::protocol::rtcm

// SPDX-License-Identifier: Apache-2.0
#pragma once
// RTCM 3 on a u-blox port: the frames a host sends beside UBX and NMEA
// (a port takes them where its inProtoMask has RTCM3, CFG-PRT bit 5 /
// CFG-UARTxINPROT-RTCM3X), decoded into the chip's corrections, and the
// UBX-RXM-RTCM the chip reports per message (ZED-F9P Interface Description
// UBX-18010854 §5.15.5: version 2, flags crcFailed b0 and msgUsed b1-2,
// subType, refStation, msgType; shared/reference/rtk-raw.md §1.4).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "core/protocol/rtcm/rtcm_decoder.hpp"
#include "core/receiver/corrections.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::protocol::ubx {

/// Payload bytes of RXM-RTCM.
inline constexpr std::size_t kRxmRtcmBytes = 8;

/// Appends one RXM-RTCM for a message: crc_failed (its CRC did not match;
/// msgUsed then 0, unknown), r as the decoder took it. Returns bytes appended.
std::size_t rxm_rtcm(const rtcm::DecodeResult& r, bool crc_failed, std::string& out);

/// What RTCM input did.
struct RtcmInputStats {
  std::uint64_t frames = 0;      ///< frames with a good CRC taken
  std::uint64_t crc_failed = 0;  ///< frames whose CRC-24Q failed
  std::uint64_t ignored = 0;     ///< frames on a port whose inProtoMask has no RTCM3
  std::uint64_t outage = 0;      ///< frames lost to a correction-link outage fault
  std::uint64_t stale = 0;       ///< frames a stale-corrections fault kept from the corrections
  std::uint64_t used = 0;        ///< messages the corrections took
};

/// The chip's correction input: decoder, the corrections it fills and the
/// rover time it resolves epochs against. Fixed memory, never throws.
class RtcmInput {
public:
  /// A frame's payload (crc_ok false: a CRC failure, counted and not
  /// decoded). Returns what the message was.
  rtcm::DecodeResult take(std::span<const std::uint8_t> payload, bool crc_ok) noexcept;
  void count_ignored() noexcept { ++stats_.ignored; }

  /// The rover's GPS time and GPS - UTC (s) at its latest epoch: MSM epochs
  /// are resolved against it and arrivals stamped with it, so the age of
  /// the corrections follows the simulation's time, not the wall clock's.
  void set_time(time::GpsTime t, int leap_seconds) noexcept {
    now_ = t;
    leap_seconds_ = leap_seconds;
  }
  /// The GLONASS channels of the satellites the rover tracks: an MSM4
  /// carries none, so the base's GLONASS carrier phases need them.
  void learn_glonass_channels(const receiver::RawEpoch& own) noexcept;
  /// A correction-link outage (fault): frames are lost before the decoder.
  void set_outage(bool on) noexcept { outage_ = on; }
  bool outage() const noexcept { return outage_; }
  /// Stale corrections (fault): frames arrive and are reported, but the
  /// corrections keep what they held, so their age grows.
  void set_stale(bool on) noexcept { stale_ = on; }

  const receiver::Corrections& corrections() const noexcept { return corrections_; }
  const rtcm::DecoderStats& decoder_stats() const noexcept { return decoder_.stats(); }
  const RtcmInputStats& stats() const noexcept { return stats_; }

private:
  rtcm::Decoder decoder_;
  receiver::Corrections corrections_;
  time::GpsTime now_;
  int leap_seconds_ = 18;
  bool outage_ = false;
  bool stale_ = false;
  receiver::Corrections stale_sink_;  ///< where a stale link's messages go
  RtcmInputStats stats_;
};

}  // namespace gnssemu::protocol::ubx

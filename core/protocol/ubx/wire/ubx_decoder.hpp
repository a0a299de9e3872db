// SPDX-License-Identifier: Apache-2.0
#pragma once
// Streaming decoder for the receive side of a port: UBX frames, NMEA
// sentences (host commands such as $PUBX,41) and RTCM 3 frames (0xD3,
// CRC-24Q: corrections) interleaved with garbage, as a u-blox port accepts
// them (CFG-PRT inProtoMask; the device decides which it takes). Bounded memory (one max-size frame), no
// allocation after construction, never throws. After a bad frame it rescans
// from the byte after the false sync, so a valid frame hidden in garbage is
// still found.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "core/protocol/ubx/wire/ubx_frame.hpp"

namespace gnssemu::protocol::ubx {

/// Longest NMEA input accepted, '$' to LF inclusive. NMEA 0183 allows 82;
/// u-blox accepts somewhat longer PUBX commands, so allow 120.
inline constexpr std::size_t kMaxNmeaBytes = 120;

/// Counts per reason; bytes are counted once in garbage_bytes when dropped.
struct DecoderStats {
  std::uint64_t ubx_frames = 0;         ///< good UBX frames delivered
  std::uint64_t nmea_sentences = 0;     ///< good NMEA sentences delivered
  std::uint64_t rtcm_frames = 0;        ///< good RTCM 3 frames delivered
  std::uint64_t rtcm_bad_crc = 0;       ///< RTCM 3 headers whose CRC-24Q did not match
  std::uint64_t ubx_bad_checksum = 0;
  std::uint64_t ubx_bad_length = 0;     ///< length field > kMaxPayloadBytes
  std::uint64_t nmea_bad_checksum = 0;  ///< '*hh' present but wrong or not hex
  std::uint64_t nmea_no_checksum = 0;   ///< no '*hh' before CR LF (rejected)
  std::uint64_t nmea_too_long = 0;      ///< no line end within kMaxNmeaBytes
  std::uint64_t nmea_bad_char = 0;      ///< non-printable byte inside a sentence
  std::uint64_t idle_resyncs = 0;       ///< partial frames abandoned by on_idle
  std::uint64_t garbage_bytes = 0;      ///< bytes discarded outside good frames
};

/// Receives what the decoder finds. Views are valid during the call only.
class DecoderSink {
public:
  virtual ~DecoderSink() = default;
  virtual void on_ubx(const FrameView& frame) = 0;
  /// sentence: from '$' up to and including "*hh", without CR LF; checksum verified.
  virtual void on_nmea(std::string_view sentence) = 0;
  /// An RTCM 3 frame's payload (message number in its first 12 bits).
  /// crc_ok false: a header whose CRC failed (what RXM-RTCM reports as
  /// crcFailed); the decoder then rescans from the byte after the 0xD3.
  virtual void on_rtcm(std::span<const std::uint8_t> payload, bool crc_ok) {
    (void)payload;
    (void)crc_ok;
  }
};

class StreamDecoder {
public:
  /// Process bytes in order, calling sink for every complete good frame.
  void feed(std::span<const std::uint8_t> bytes, DecoderSink& sink) noexcept;
  void feed(std::string_view bytes, DecoderSink& sink) noexcept {
    feed({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, sink);
  }
  /// The line has been idle (say 100 ms) with a partial frame pending: give up
  /// on it and rescan what is held from its second byte. A garbage header
  /// announcing a long payload would otherwise swallow the host's next
  /// commands until that many bytes arrived; hosts wait for a reply before
  /// sending more, so without this the handshake would stall.
  void on_idle(DecoderSink& sink) noexcept;
  /// Drop any partial frame (e.g. after a baud change garbles the line).
  void reset() noexcept { size_ = 0; }

  const DecoderStats& stats() const noexcept { return stats_; }
  /// Bytes held waiting for the rest of a frame.
  std::size_t pending_bytes() const noexcept { return size_; }

private:
  void parse(DecoderSink& sink) noexcept;
  void drop(std::size_t n) noexcept;

  std::array<std::uint8_t, kMaxPayloadBytes + kFrameOverheadBytes> buf_{};
  std::size_t size_ = 0;
  DecoderStats stats_;
};

}  // namespace gnssemu::protocol::ubx

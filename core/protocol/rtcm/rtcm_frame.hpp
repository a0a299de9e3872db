// SPDX-License-Identifier: Apache-2.0
#pragma once
// RTCM 3 transport frame: 0xD3, 6 reserved zero bits, 10-bit payload length,
// payload, CRC-24Q over preamble..payload (RTCM 10403.3 §4;
// shared/reference/rtk-raw.md §2.1). Output goes into std::string so RTCM
// shares the transmit buffers of the other protocols.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace gnssemu::protocol::rtcm {

inline constexpr std::uint8_t kPreamble = 0xD3;
inline constexpr std::size_t kMaxPayloadBytes = 1023;  ///< 10-bit length
inline constexpr std::size_t kFrameOverheadBytes = 6;  ///< preamble, 2 length bytes, 3 CRC bytes

/// CRC-24Q (polynomial 0x1864CFB, initial value 0) of bytes.
std::uint32_t crc24q(std::span<const std::uint8_t> bytes) noexcept;

/// Appends one frame around payload (at most kMaxPayloadBytes; longer payloads
/// are not framed and false is returned).
bool append_frame(std::span<const std::uint8_t> payload, std::string& out);

/// A payload buffer of the largest size: what every message encoder writes into.
using Payload = std::array<std::uint8_t, kMaxPayloadBytes>;

/// Counters of a frame reader.
struct FrameStats {
  std::uint64_t frames = 0;        ///< frames with a good CRC
  /// Candidate frames whose CRC did not match: corrupted bytes, or a frame
  /// cut short so that the next frame's bytes were read as its tail.
  std::uint64_t crc_errors = 0;
  std::uint64_t truncated = 0;     ///< a partial frame at the end of the stream (finish())
  std::uint64_t bad_header = 0;    ///< a preamble byte with non-zero reserved bits (not a frame)
  std::uint64_t skipped_bytes = 0; ///< bytes outside any frame
};

/// Receives whole, CRC-checked frames from a FrameReader.
class FrameSink {
public:
  virtual ~FrameSink() = default;
  /// payload: the frame's payload (message number in its first 12 bits).
  virtual void on_frame(std::span<const std::uint8_t> payload) = 0;
};

/// Incremental RTCM 3 frame reader for bytes from a host or a file: frames
/// may arrive split across calls; garbage and bad frames are counted and
/// skipped (on a CRC error it resynchronises one byte after the failed
/// preamble). Fixed buffer: never allocates, never throws.
class FrameReader {
public:
  explicit FrameReader(FrameSink& sink) noexcept : sink_(sink) {}
  void feed(std::span<const std::uint8_t> bytes) noexcept;
  /// End of the stream: a partial frame counts as truncated.
  void finish() noexcept;
  const FrameStats& stats() const noexcept { return stats_; }

private:
  void scan() noexcept;
  FrameSink& sink_;
  std::array<std::uint8_t, kMaxPayloadBytes + kFrameOverheadBytes> buf_{};
  std::size_t len_ = 0;
  FrameStats stats_;
};

/// Message number (DF002) of a payload; 0 when it is shorter than 12 bits.
int message_number(std::span<const std::uint8_t> payload) noexcept;

}  // namespace gnssemu::protocol::rtcm

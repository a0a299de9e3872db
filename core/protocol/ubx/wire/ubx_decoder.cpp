// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/wire/ubx_decoder.hpp"

#include <algorithm>
#include <cstring>

#include "core/protocol/rtcm/rtcm_frame.hpp"

namespace gnssemu::protocol::ubx {

namespace {

constexpr std::uint8_t kDollar = '$';

int hex_value(std::uint8_t c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool is_start(std::uint8_t c) noexcept { return c == kSync1 || c == kDollar || c == rtcm::kPreamble; }

}  // namespace

static_assert(kMaxPayloadBytes + kFrameOverheadBytes >= rtcm::kMaxPayloadBytes + rtcm::kFrameOverheadBytes,
              "the buffer holds the longest RTCM 3 frame");

void StreamDecoder::drop(std::size_t n) noexcept {
  n = std::min(n, size_);
  std::memmove(buf_.data(), buf_.data() + n, size_ - n);
  size_ -= n;
}

void StreamDecoder::feed(std::span<const std::uint8_t> bytes, DecoderSink& sink) noexcept {
  for (std::uint8_t b : bytes) {
    if (size_ == 0 && !is_start(b)) {  // fast path for line noise
      ++stats_.garbage_bytes;
      continue;
    }
    buf_[size_++] = b;  // parse() leaves size_ < buf_.size(): a full frame is consumed or dropped
    parse(sink);
  }
}

void StreamDecoder::on_idle(DecoderSink& sink) noexcept {
  if (size_ == 0) return;
  ++stats_.idle_resyncs;
  ++stats_.garbage_bytes;
  drop(1);
  parse(sink);
  // Whatever is still pending is itself a partial frame from a later start
  // byte; leave it for more input or the next idle call.
}

void StreamDecoder::parse(DecoderSink& sink) noexcept {
  while (size_ > 0) {
    const std::uint8_t first = buf_[0];
    if (first == kSync1) {
      if (size_ < 2) return;
      if (buf_[1] != kSync2) {
        ++stats_.garbage_bytes;
        drop(1);
        continue;
      }
      if (size_ < kHeaderBytes) return;
      const std::size_t len = static_cast<std::size_t>(buf_[4]) | static_cast<std::size_t>(buf_[5]) << 8;
      if (len > kMaxPayloadBytes) {
        ++stats_.ubx_bad_length;
        ++stats_.garbage_bytes;
        drop(1);
        continue;
      }
      const std::size_t total = len + kFrameOverheadBytes;
      if (size_ < total) return;
      const Checksum ck = fletcher8({buf_.data() + 2, len + 4});
      if (ck.ck_a != buf_[total - 2] || ck.ck_b != buf_[total - 1]) {
        ++stats_.ubx_bad_checksum;
        ++stats_.garbage_bytes;
        drop(1);
        continue;
      }
      ++stats_.ubx_frames;
      sink.on_ubx(FrameView{MsgId{buf_[2], buf_[3]}, {buf_.data() + kHeaderBytes, len}});
      drop(total);
      continue;
    }
    if (first == rtcm::kPreamble) {
      if (size_ < 3) return;
      const std::size_t len = static_cast<std::size_t>(buf_[1] & 0x03u) << 8 | buf_[2];
      if ((buf_[1] & 0xFCu) != 0) {  // reserved bits: not a frame
        ++stats_.garbage_bytes;
        drop(1);
        continue;
      }
      const std::size_t total = len + rtcm::kFrameOverheadBytes;
      if (size_ < total) return;
      const std::uint32_t want = static_cast<std::uint32_t>(buf_[3 + len]) << 16 |
                                 static_cast<std::uint32_t>(buf_[4 + len]) << 8 | buf_[5 + len];
      const std::span<const std::uint8_t> payload(buf_.data() + 3, len);
      if (rtcm::crc24q({buf_.data(), 3 + len}) != want) {
        ++stats_.rtcm_bad_crc;
        ++stats_.garbage_bytes;
        sink.on_rtcm(payload, false);
        drop(1);
        continue;
      }
      ++stats_.rtcm_frames;
      sink.on_rtcm(payload, true);
      drop(total);
      continue;
    }
    if (first == kDollar) {
      std::size_t end = 0;  // index of LF
      bool bad_char = false;
      for (std::size_t i = 1; i < size_; ++i) {
        const std::uint8_t c = buf_[i];
        if (c == '\n') {
          end = i;
          break;
        }
        if (c == '\r' && (i + 1 == size_ || buf_[i + 1] == '\n')) continue;
        if (c < 0x20 || c > 0x7E) {
          bad_char = true;
          break;
        }
      }
      if (bad_char) {
        ++stats_.nmea_bad_char;
        ++stats_.garbage_bytes;
        drop(1);
        continue;
      }
      if (end == 0) {
        if (size_ >= kMaxNmeaBytes) {
          ++stats_.nmea_too_long;
          ++stats_.garbage_bytes;
          drop(1);
          continue;
        }
        return;  // wait for the line end
      }
      std::size_t len = end;  // without LF
      if (len > 0 && buf_[len - 1] == '\r') --len;
      const char* s = reinterpret_cast<const char*>(buf_.data());
      if (len < 4 || s[len - 3] != '*') {
        ++stats_.nmea_no_checksum;
        ++stats_.garbage_bytes;
        drop(1);
        continue;
      }
      const int hi = hex_value(buf_[len - 2]), lo = hex_value(buf_[len - 1]);
      std::uint8_t sum = 0;
      for (std::size_t i = 1; i < len - 3; ++i) sum = static_cast<std::uint8_t>(sum ^ buf_[i]);
      if (hi < 0 || lo < 0 || sum != static_cast<std::uint8_t>(hi << 4 | lo)) {
        ++stats_.nmea_bad_checksum;
        ++stats_.garbage_bytes;
        drop(1);
        continue;
      }
      ++stats_.nmea_sentences;
      sink.on_nmea(std::string_view(s, len));
      drop(end + 1);
      continue;
    }
    // Garbage: skip to the next possible start byte.
    std::size_t next = 1;
    while (next < size_ && !is_start(buf_[next])) ++next;
    stats_.garbage_bytes += next;
    drop(next);
  }
}

}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/rtcm/rtcm_frame.hpp"

#include <algorithm>
#include <cstring>

namespace gnssemu::protocol::rtcm {

namespace {

constexpr std::uint32_t kCrc24qPoly = 0x1864CFB;

constexpr std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i << 16;
    for (int b = 0; b < 8; ++b) c = (c & 0x800000u) ? ((c << 1) ^ kCrc24qPoly) : (c << 1);
    t[i] = c & 0xFFFFFFu;
  }
  return t;
}
constexpr auto kCrcTable = make_crc_table();

std::size_t payload_length(const std::uint8_t* header) noexcept {
  return static_cast<std::size_t>((header[1] & 0x03u) << 8 | header[2]);
}

}  // namespace

std::uint32_t crc24q(std::span<const std::uint8_t> bytes) noexcept {
  std::uint32_t crc = 0;
  for (std::uint8_t b : bytes) crc = ((crc << 8) & 0xFFFFFFu) ^ kCrcTable[((crc >> 16) ^ b) & 0xFFu];
  return crc;
}

bool append_frame(std::span<const std::uint8_t> payload, std::string& out) {
  if (payload.size() > kMaxPayloadBytes) return false;
  std::array<std::uint8_t, 3> head{kPreamble, static_cast<std::uint8_t>(payload.size() >> 8),
                                   static_cast<std::uint8_t>(payload.size() & 0xFFu)};
  std::uint32_t crc = crc24q(head);
  for (std::uint8_t b : payload) crc = ((crc << 8) & 0xFFFFFFu) ^ kCrcTable[((crc >> 16) ^ b) & 0xFFu];
  out.append(reinterpret_cast<const char*>(head.data()), head.size());
  out.append(reinterpret_cast<const char*>(payload.data()), payload.size());
  out.push_back(static_cast<char>((crc >> 16) & 0xFFu));
  out.push_back(static_cast<char>((crc >> 8) & 0xFFu));
  out.push_back(static_cast<char>(crc & 0xFFu));
  return true;
}

int message_number(std::span<const std::uint8_t> payload) noexcept {
  if (payload.size() < 2) return 0;
  return payload[0] << 4 | payload[1] >> 4;
}

void FrameReader::feed(std::span<const std::uint8_t> bytes) noexcept {
  while (!bytes.empty()) {
    const std::size_t n = std::min(bytes.size(), buf_.size() - len_);
    std::memcpy(buf_.data() + len_, bytes.data(), n);
    len_ += n;
    bytes = bytes.subspan(n);
    scan();
  }
}

void FrameReader::finish() noexcept {
  if (len_ > 0) {
    ++stats_.truncated;
    stats_.skipped_bytes += len_;
  }
  len_ = 0;
}

void FrameReader::scan() noexcept {
  std::size_t start = 0;
  auto drop = [&](std::size_t n, bool skipped) {
    if (skipped) stats_.skipped_bytes += n;
    start += n;
  };
  while (start < len_) {
    const std::uint8_t* p = buf_.data() + start;
    const std::size_t avail = len_ - start;
    if (p[0] != kPreamble) {
      const void* next = std::memchr(p, kPreamble, avail);
      drop(next ? static_cast<std::size_t>(static_cast<const std::uint8_t*>(next) - p) : avail, true);
      continue;
    }
    if (avail < 3) break;
    if ((p[1] & 0xFCu) != 0) {
      ++stats_.bad_header;
      drop(1, true);
      continue;
    }
    const std::size_t len = payload_length(p);
    const std::size_t total = len + kFrameOverheadBytes;
    if (avail < total) break;
    const std::uint32_t want = static_cast<std::uint32_t>(p[3 + len]) << 16 |
                               static_cast<std::uint32_t>(p[4 + len]) << 8 | p[5 + len];
    if (crc24q(std::span<const std::uint8_t>(p, 3 + len)) == want) {
      ++stats_.frames;
      sink_.on_frame(std::span<const std::uint8_t>(p + 3, len));
      drop(total, false);
    } else {
      ++stats_.crc_errors;
      drop(1, true);
    }
  }
  if (start > 0) {
    std::memmove(buf_.data(), buf_.data() + start, len_ - start);
    len_ -= start;
  }
}

}  // namespace gnssemu::protocol::rtcm

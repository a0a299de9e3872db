// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/nmea/nmea_format.hpp"

#include <cmath>

namespace gnssemu::protocol::nmea {

namespace {
constexpr char kHex[] = "0123456789ABCDEF";

int hex_value(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

constexpr int64_t kPow10[] = {1,      10,      100,      1000,      10000,
                              100000, 1000000, 10000000, 100000000, 1000000000};
// Keeps value * 10^decimals well inside int64.
constexpr double kMaxScaled = 9.0e17;
}  // namespace

uint8_t nmea_checksum(std::string_view payload) noexcept {
  uint8_t sum = 0;
  for (char c : payload) sum = static_cast<uint8_t>(sum ^ static_cast<uint8_t>(c));
  return sum;
}

bool nmea_checksum_ok(std::string_view s) noexcept {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.remove_suffix(1);
  if (s.size() < 4 || s.front() != '$') return false;
  const std::size_t star = s.size() - 3;
  if (s[star] != '*') return false;
  const int hi = hex_value(s[star + 1]);
  const int lo = hex_value(s[star + 2]);
  if (hi < 0 || lo < 0) return false;
  return nmea_checksum(s.substr(1, star - 1)) == static_cast<uint8_t>(hi * 16 + lo);
}

SentenceWriter::SentenceWriter(std::string_view address) noexcept {
  character_raw('$');
  for (char c : address) character_raw(c);
}

void SentenceWriter::character_raw(char c) noexcept {
  // Room is kept for "*hh\r\n".
  if (len_ + 5 < kCapacity) {
    buf_[len_++] = c;
  } else {
    overflow_ = true;
  }
}

void SentenceWriter::text(std::string_view s) noexcept {
  character_raw(',');
  for (char c : s) character_raw(c);
}

void SentenceWriter::character(char c) noexcept {
  character_raw(',');
  character_raw(c);
}

void SentenceWriter::digits(uint64_t value, int width) noexcept {
  char tmp[24];
  int n = 0;
  do {
    tmp[n++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0 && n < 24);
  for (int i = n; i < width; ++i) character_raw('0');
  while (n > 0) character_raw(tmp[--n]);
}

void SentenceWriter::integer(int64_t value, int width) noexcept {
  character_raw(',');
  if (value < 0) {
    character_raw('-');
    value = -value;
  }
  digits(static_cast<uint64_t>(value), width);
}

void SentenceWriter::fixed(double value, int decimals, int min_int_digits) noexcept {
  character_raw(',');
  if (decimals < 0) decimals = 0;
  if (decimals > 9) decimals = 9;
  const double scaled = value * static_cast<double>(kPow10[decimals]);
  if (!std::isfinite(scaled) || std::fabs(scaled) > kMaxScaled) return;
  const long long r = std::llround(scaled);
  const uint64_t mag = static_cast<uint64_t>(r < 0 ? -r : r);
  if (r < 0) character_raw('-');
  const auto p = static_cast<uint64_t>(kPow10[decimals]);
  digits(mag / p, min_int_digits);
  if (decimals > 0) {
    character_raw('.');
    digits(mag % p, decimals);
  }
}

void SentenceWriter::angle(double deg, int deg_width, char pos, char neg) noexcept {
  // Units of 1e-5 arcminute: rounding once here carries minutes = 60 into degrees.
  constexpr int64_t kUnitsPerMinute = 100000;
  constexpr int64_t kUnitsPerDegree = 60 * kUnitsPerMinute;
  const double scaled = std::fabs(deg) * static_cast<double>(kUnitsPerDegree);
  if (!std::isfinite(scaled) || scaled > kMaxScaled) {
    empty();
    empty();
    return;
  }
  const auto total = static_cast<int64_t>(std::llround(scaled));
  character_raw(',');
  digits(static_cast<uint64_t>(total / kUnitsPerDegree), deg_width);
  const int64_t minute_units = total % kUnitsPerDegree;
  digits(static_cast<uint64_t>(minute_units / kUnitsPerMinute), 2);
  character_raw('.');
  digits(static_cast<uint64_t>(minute_units % kUnitsPerMinute), 5);
  // A value that rounds to zero is printed as N / E.
  character((deg < 0.0 && total != 0) ? neg : pos);
}

void SentenceWriter::latitude(double lat_deg) noexcept { angle(lat_deg, 2, 'N', 'S'); }

void SentenceWriter::longitude(double lon_deg) noexcept { angle(lon_deg, 3, 'E', 'W'); }

void SentenceWriter::time_of_day(int hour, int minute, int second, int centisecond) noexcept {
  character_raw(',');
  digits(static_cast<uint64_t>(hour), 2);
  digits(static_cast<uint64_t>(minute), 2);
  digits(static_cast<uint64_t>(second), 2);
  character_raw('.');
  digits(static_cast<uint64_t>(centisecond), 2);
}

void SentenceWriter::date_ddmmyy(int day, int month, int year) noexcept {
  character_raw(',');
  digits(static_cast<uint64_t>(day), 2);
  digits(static_cast<uint64_t>(month), 2);
  digits(static_cast<uint64_t>(((year % 100) + 100) % 100), 2);
}

std::string_view SentenceWriter::finish() noexcept {
  const uint8_t sum = nmea_checksum(std::string_view(buf_ + 1, len_ - 1));
  // character_raw() always leaves these five bytes free.
  buf_[len_++] = '*';
  buf_[len_++] = kHex[sum >> 4];
  buf_[len_++] = kHex[sum & 0x0F];
  buf_[len_++] = '\r';
  buf_[len_++] = '\n';
  return {buf_, len_};
}

}  // namespace gnssemu::protocol::nmea

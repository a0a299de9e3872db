// SPDX-License-Identifier: Apache-2.0
#pragma once
// NMEA 0183 framing and u-blox number formats (shared/reference/nmea0183.md
// §1, §5). Builds one sentence in a fixed stack buffer: no allocation.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace gnssemu::protocol::nmea {

/// Maximum sentence length including '$' and CR LF (NMEA 0183 §5.3; ref §1).
inline constexpr std::size_t kMaxSentenceLength = 82;

/// XOR of every byte of payload (the bytes between '$' and '*').
uint8_t nmea_checksum(std::string_view payload) noexcept;

/// True if sentence is "$<payload>*hh" with hh (either case) equal to the
/// checksum of payload. A trailing CR, LF or CR LF is ignored.
bool nmea_checksum_ok(std::string_view sentence) noexcept;

/// One sentence under construction. Field appenders write the leading comma;
/// a value that is not finite gives an empty field (never "nan").
class SentenceWriter {
public:
  /// Starts "$" + address, e.g. address "GPGGA".
  explicit SentenceWriter(std::string_view address) noexcept;

  /// ",text".
  void text(std::string_view s) noexcept;
  /// ",c".
  void character(char c) noexcept;
  /// "," (empty field).
  void empty() noexcept { character_raw(','); }
  /// Fixed-point value with `decimals` (0..9) digits after the point,
  /// rounded half away from zero; "-" only when the rounded value is
  /// negative. min_int_digits zero-pads the integer part. Empty if !finite.
  void fixed(double value, int decimals, int min_int_digits = 1) noexcept;
  /// Non-negative integer zero-padded to width digits.
  void integer(int64_t value, int width) noexcept;
  /// Latitude in degrees ([-90, 90]) as ",ddmm.mmmmm,N|S" (1e-5 arcmin,
  /// minutes carried into degrees). Two empty fields if !finite.
  void latitude(double lat_deg) noexcept;
  /// Longitude in degrees ([-180, 180]) as ",dddmm.mmmmm,E|W".
  void longitude(double lon_deg) noexcept;
  /// ",hhmmss.ss".
  void time_of_day(int hour, int minute, int second, int centisecond) noexcept;
  /// ",ddmmyy" (RMC date; year modulo 100).
  void date_ddmmyy(int day, int month, int year) noexcept;

  /// Call once: appends "*hh" CR LF and returns the whole sentence (valid while *this lives).
  std::string_view finish() noexcept;
  /// Length finish() will return (fields so far plus "*hh" CR LF).
  std::size_t finished_size() const noexcept { return len_ + 5; }
  /// True if some field did not fit in the buffer (it was cut).
  bool overflowed() const noexcept { return overflow_; }

private:
  static constexpr std::size_t kCapacity = 160;
  void character_raw(char c) noexcept;
  void digits(uint64_t value, int width) noexcept;
  void angle(double deg, int deg_width, char pos, char neg) noexcept;

  char buf_[kCapacity];
  std::size_t len_ = 0;
  bool overflow_ = false;
};

}  // namespace gnssemu::protocol::nmea

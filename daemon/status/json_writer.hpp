// SPDX-License-Identifier: Apache-2.0
#pragma once
// JsonWriter: appends compact JSON to a caller's string. Commas are placed
// by the writer; numbers are written with a fixed number of decimals and
// non-finite values as null. Once the string has capacity it allocates
// nothing, so the status page can serialise every epoch without allocating.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace gnssemu::daemon {

class JsonWriter {
public:
  /// out: appended to; it must outlive the writer.
  explicit JsonWriter(std::string& out) noexcept : out_(out) {}

  void begin_object() noexcept;
  void end_object() noexcept;
  void begin_array() noexcept;
  void end_array() noexcept;
  /// Object member name; the value follows.
  void key(std::string_view name) noexcept;

  /// decimals: digits after the point [0, 9]; NaN and infinities: null.
  void number(double v, int decimals) noexcept;
  void integer(int64_t v) noexcept;
  void boolean(bool v) noexcept;
  void null() noexcept;
  /// Escaped per RFC 8259 §7 (quotes, backslash, control characters).
  void string(std::string_view s) noexcept;

  // key + value.
  void field(std::string_view name, double v, int decimals) noexcept { key(name); number(v, decimals); }
  void field_int(std::string_view name, int64_t v) noexcept { key(name); integer(v); }
  void field_bool(std::string_view name, bool v) noexcept { key(name); boolean(v); }
  void field_string(std::string_view name, std::string_view v) noexcept { key(name); string(v); }

private:
  void separator() noexcept;
  void raw_string(std::string_view s) noexcept;
  void append(std::string_view s) noexcept;

  std::string& out_;
  static constexpr int kMaxDepth = 16;
  std::array<bool, kMaxDepth> first_{};  ///< no member written yet at this depth
  int depth_ = 0;
  bool after_key_ = false;
};

}  // namespace gnssemu::daemon

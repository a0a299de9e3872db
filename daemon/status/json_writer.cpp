// SPDX-License-Identifier: Apache-2.0
#include "daemon/status/json_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace gnssemu::daemon {

void JsonWriter::append(std::string_view s) noexcept {
  try {
    out_.append(s);
  } catch (...) {
    // Out of memory: the document is cut short; the reader rejects it.
  }
}

void JsonWriter::separator() noexcept {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (depth_ > 0 && depth_ <= kMaxDepth) {
    if (!first_[depth_ - 1]) append(",");
    first_[depth_ - 1] = false;
  }
}

void JsonWriter::begin_object() noexcept {
  separator();
  append("{");
  if (depth_ < kMaxDepth) first_[depth_] = true;
  ++depth_;
}

void JsonWriter::end_object() noexcept {
  --depth_;
  append("}");
}

void JsonWriter::begin_array() noexcept {
  separator();
  append("[");
  if (depth_ < kMaxDepth) first_[depth_] = true;
  ++depth_;
}

void JsonWriter::end_array() noexcept {
  --depth_;
  append("]");
}

void JsonWriter::key(std::string_view name) noexcept {
  separator();
  raw_string(name);
  append(":");
  after_key_ = true;
}

void JsonWriter::number(double v, int decimals) noexcept {
  separator();
  if (!std::isfinite(v)) {
    append("null");
    return;
  }
  if (decimals < 0) decimals = 0;
  if (decimals > 9) decimals = 9;
  std::array<char, 64> buf{};
  // Fixed notation of a huge value would not fit: 17 significant digits.
  const auto r = std::fabs(v) < 1e15 ? fmt::format_to_n(buf.data(), buf.size(), "{:.{}f}", v, decimals)
                                     : fmt::format_to_n(buf.data(), buf.size(), "{:.17g}", v);
  std::string_view text(buf.data(), std::min<std::size_t>(r.size, buf.size()));
  if (text == "-0" || (text.starts_with("-0.") && text.find_first_not_of("0.", 1) == std::string_view::npos)) {
    text.remove_prefix(1);  // "-0.00" reads as a sign where there is none
  }
  append(text);
}

void JsonWriter::integer(int64_t v) noexcept {
  separator();
  std::array<char, 24> buf{};
  const auto r = fmt::format_to_n(buf.data(), buf.size(), "{}", v);
  append(std::string_view(buf.data(), std::min<std::size_t>(r.size, buf.size())));
}

void JsonWriter::boolean(bool v) noexcept {
  separator();
  append(v ? "true" : "false");
}

void JsonWriter::null() noexcept {
  separator();
  append("null");
}

void JsonWriter::string(std::string_view s) noexcept {
  separator();
  raw_string(s);
}

void JsonWriter::raw_string(std::string_view s) noexcept {
  append("\"");
  std::size_t start = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    const char* esc = nullptr;
    std::array<char, 8> hex{};
    switch (c) {
      case '"': esc = "\\\""; break;
      case '\\': esc = "\\\\"; break;
      case '\n': esc = "\\n"; break;
      case '\r': esc = "\\r"; break;
      case '\t': esc = "\\t"; break;
      default:
        if (c < 0x20 || c == 0x7f) {
          fmt::format_to_n(hex.data(), hex.size(), "\\u{:04x}", static_cast<unsigned>(c));
          esc = hex.data();
        }
    }
    if (esc == nullptr) continue;
    append(s.substr(start, i - start));
    append(esc);
    start = i + 1;
  }
  append(s.substr(start));
  append("\"");
}

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#include "config/toml/toml_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "core/common/constants.hpp"

namespace gnssemu::config::detail {

namespace fs = std::filesystem;

std::string number_text(double v) {
  std::string s = format_number(v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string degrees_text(double rad) {
  const double deg = rad * kRadToDeg;
  double candidate = deg;
  for (int i = 0; i < 16; ++i) {
    const double up = std::nextafter(deg, deg + 1.0) - deg;  // one ulp
    for (const double d : {deg + i * up, deg - i * up}) {
      if (d * kDegToRad == rad) return number_text(d);
    }
  }
  return number_text(candidate);
}

std::string string_text(std::string_view s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (u < 0x20 || u == 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", u);
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

std::string strings_text(std::span<const std::string_view> items) {
  std::string out = "[";
  for (const std::string_view item : items) {
    if (out.size() > 1) out += ", ";
    out += string_text(item);
  }
  return out + "]";
}

std::string bool_text(bool v) { return v ? "true" : "false"; }

std::string datetime_text(const time::GpsTime& t) {
  const time::CalendarTime c = t.to_calendar();
  char buf[40];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:", c.year, c.month, c.day, c.hour, c.minute);
  std::string s = buf;
  char sbuf[48];
  const auto res = std::to_chars(sbuf, sbuf + sizeof sbuf, c.second, std::chars_format::fixed);
  std::string sec(sbuf, res.ptr);
  if (c.second < 10.0) sec = "0" + sec;
  return s + sec;
}

TomlWriter::TomlWriter(std::string relative_to, KeyLog* log) : relative_to_(std::move(relative_to)), log_(log) {}

std::string TomlWriter::path_text(const std::string& path) const {
  if (relative_to_.empty()) return path;
  const fs::path base = fs::absolute(relative_to_).lexically_normal();
  const fs::path rel = fs::path(path).lexically_relative(base);
  if (rel.empty() || *rel.begin() == "..") return path;
  return rel.string();
}

void TomlWriter::header(std::string_view note, bool array) {
  out_ += array ? "\n[[" + table_ + "]]" : "\n[" + table_ + "]";
  if (!note.empty()) out_ += "  # " + std::string(note);
  out_ += '\n';
}

void TomlWriter::key(std::string_view key, const std::string& value, std::string_view note) {
  out_ += std::string(key) + " = " + value;
  if (!note.empty()) out_ += "  # " + std::string(note);
  out_ += '\n';
  last_value_ = value;
  if (log_ != nullptr) log_->push_back((table_.empty() ? "" : table_ + ".") + std::string(key) + " = " + value);
}

void TomlWriter::line(std::string_view text) { out_ += std::string(text) + "\n"; }

}  // namespace gnssemu::config::detail

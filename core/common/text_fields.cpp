// SPDX-License-Identifier: Apache-2.0
#include "core/common/text_fields.hpp"

#include <array>
#include <charconv>
#include <cmath>

#include "core/common/error.hpp"

namespace gnssemu::text {

std::string_view trim(std::string_view s) noexcept {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::string_view columns(std::string_view line, std::size_t col, std::size_t width) noexcept {
  if (col >= line.size()) return {};
  return line.substr(col, width);
}

std::optional<double> parse_real(std::string_view field) noexcept {
  std::string_view f = trim(field);
  if (!f.empty() && f.front() == '+') f.remove_prefix(1);
  // Longer than any real a text format here writes: not a number.
  std::array<char, 64> buf{};
  if (f.empty() || f.size() >= buf.size()) return std::nullopt;
  for (std::size_t i = 0; i < f.size(); ++i) buf[i] = (f[i] == 'D' || f[i] == 'd') ? 'E' : f[i];
  double v = 0.0;
  const char* end = buf.data() + f.size();
  const auto [ptr, ec] = std::from_chars(buf.data(), end, v);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return v;
}

std::optional<int> parse_int(std::string_view field) noexcept {
  std::string_view f = trim(field);
  if (!f.empty() && f.front() == '+') f.remove_prefix(1);
  if (f.empty()) return std::nullopt;
  int v = 0;
  const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
  if (ec != std::errc() || ptr != f.data() + f.size()) return std::nullopt;
  return v;
}

void ColumnReader::fail(int line, const std::string& what) const { throw Error(name_, line, what); }

template <class T>
T ColumnReader::field(const Line& l, std::size_t col, std::size_t width, const char* what, const char* kind,
                      std::optional<T> (*parse)(std::string_view) noexcept) const {
  const std::string_view f = trim(columns(l.text, col, width));
  if (f.empty()) return T{};
  const std::optional<T> v = parse(f);
  if (!v) {
    fail(l.number, std::string("unparsable ") + kind + " '" + std::string(f) + "' for " + what + " at column " +
                       std::to_string(col + 1));
  }
  return *v;
}

double ColumnReader::real(const Line& l, std::size_t col, std::size_t width, const char* what) const {
  const double v = field<double>(l, col, width, what, "number", parse_real);
  if (!std::isfinite(v)) fail(l.number, std::string("non-finite value for ") + what);
  return v;
}

int ColumnReader::integer(const Line& l, std::size_t col, std::size_t width, const char* what) const {
  return field<int>(l, col, width, what, "integer", parse_int);
}

std::string rinex_label(std::string_view line) { return std::string(trim(columns(line, 60, 20))); }

RinexVersionLine read_rinex_version(const ColumnReader& r, const std::vector<Line>& lines) {
  if (lines.empty()) r.fail(1, "empty file");
  return read_rinex_version_line(r, lines[0]);
}

RinexVersionLine read_rinex_version_line(const ColumnReader& r, const Line& first) {
  if (rinex_label(first.text) != "RINEX VERSION / TYPE") r.fail(first.number, "first line is not 'RINEX VERSION / TYPE'");
  RinexVersionLine v;
  v.version = r.real(first, 0, 9, "RINEX version");
  if (v.version >= 2.0 && v.version < 2.12) {
    v.major = 2;
  } else if (v.version >= 3.0 && v.version < 3.06) {
    v.major = 3;
  } else {
    r.fail(first.number, "unsupported RINEX version " + std::string(trim(columns(first.text, 0, 9))) +
                             " (2.00-2.11 and 3.00-3.05 are supported)");
  }
  v.type = first.text.size() > 20 ? first.text[20] : ' ';
  v.system = first.text.size() > 40 ? first.text[40] : ' ';
  return v;
}

}  // namespace gnssemu::text

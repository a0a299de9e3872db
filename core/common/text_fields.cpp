#include "core/common/text_fields.hpp"

#include <array>
#include <charconv>

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

}  // namespace gnssemu::text

#include "core/common/range.hpp"

#include <charconv>
#include <cmath>

namespace gnssemu {

std::string format_number(double v) {
  char buf[64];
  // Whole numbers as integers ("100000", not "1e+05"); else the shortest text.
  const bool whole = std::isfinite(v) && std::fabs(v) < 1e15 && v == std::trunc(v);
  const auto res = whole ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed)
                         : std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string format_range(const Range& r) {
  std::string s = r.min_open ? "(" : "[";
  s += format_number(r.min) + ", " + format_number(r.max);
  s += r.max_open ? ")" : "]";
  if (!r.unit.empty()) {
    s += ' ';
    s += r.unit;
  }
  return s;
}

}  // namespace gnssemu

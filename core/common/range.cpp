// SPDX-License-Identifier: Apache-2.0
#include "core/common/range.hpp"

#include <charconv>
#include <cmath>

#include "core/common/error.hpp"

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

void check_range(double v, const Range& r, const std::string& context, std::string_view name) {
  if (r.contains(v)) return;
  throw Error(context, 0, std::string(name) + ": " + format_number(v) + " is out of range " + format_range(r));
}

void check_ranges(const std::string& context, std::initializer_list<RangeCheck> settings) {
  for (const RangeCheck& c : settings) check_range(c.value, c.range, context, c.name);
}

}  // namespace gnssemu

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Range: the valid interval of one configuration number and its unit. The
// core validator of a setting checks against it and the config layer reads,
// writes and documents the key with the same object, so each range is
// written once (next to the setting it bounds).
#include <initializer_list>
#include <string>
#include <string_view>

namespace gnssemu {

struct Range {
  double min;
  double max;
  std::string_view unit;  ///< "m", "s", "dB-Hz"; "" for pure numbers
  bool min_open = false;  ///< true: min itself is outside
  bool max_open = false;  ///< true: max itself is outside

  /// v is finite and inside.
  constexpr bool contains(double v) const noexcept {
    if (!(v == v) || v - v != 0.0) return false;  // NaN or infinite (constexpr-friendly isfinite)
    const bool below = min_open ? v <= min : v < min;
    const bool above = max_open ? v >= max : v > max;
    return !below && !above;
  }
};

/// Shortest text that reads back as v; whole numbers without exponent
/// ("100000", "45", "1e-10", "0.5").
std::string format_number(double v);
/// "[0, 100] m", "(0, 1000000] s", "[0, 1)".
std::string format_range(const Range& r);

/// Throws gnssemu::Error(context, 0, "<name>: <v> is out of range <r>")
/// unless r contains v: what a core validator says of one setting.
void check_range(double v, const Range& r, const std::string& context, std::string_view name);

/// One setting for check_ranges.
struct RangeCheck {
  double value;
  const Range& range;
  std::string_view name;
};
/// check_range of every setting, in order.
void check_ranges(const std::string& context, std::initializer_list<RangeCheck> settings);

}  // namespace gnssemu

#pragma once
// Fields of fixed-column and token-based text formats (RINEX, YUMA, SEM).
// The readers add file:line context to failures; these only parse.
#include <cstddef>
#include <optional>
#include <string_view>

namespace gnssemu::text {

/// s without leading and trailing blanks (space, tab, CR).
std::string_view trim(std::string_view s) noexcept;

/// Columns [col, col + width) of a line (0-based), clipped to the line's end.
std::string_view columns(std::string_view line, std::size_t col, std::size_t width) noexcept;

/// A Fortran-style real: optional sign, D or E exponent (RINEX writes D19.12).
/// Blanks around it are ignored. nullopt when empty or not a number; inf/nan
/// spelled out parse as such (the caller decides whether they are allowed).
std::optional<double> parse_real(std::string_view field) noexcept;

/// A decimal integer with optional sign; nullopt when empty, not an integer
/// or out of int range.
std::optional<int> parse_int(std::string_view field) noexcept;

}  // namespace gnssemu::text

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Fields of fixed-column and token-based text formats (RINEX, YUMA, SEM).
// The parse functions only parse; ColumnReader adds the file:line context
// every reader's errors carry.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

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

/// One line of a text file and where it stands.
struct Line {
  std::string text;  ///< without the line end (LF or CR LF)
  int number = 0;    ///< 1-based
};

/// Fixed-column fields of one named file: a blank field reads as 0, any
/// other must parse; failures throw gnssemu::Error with file:line.
class ColumnReader {
public:
  /// name: the file name errors carry.
  explicit ColumnReader(std::string name) : name_(std::move(name)) {}

  const std::string& name() const noexcept { return name_; }

  /// Throws gnssemu::Error "name:line: what"; line <= 0 omits the line.
  [[noreturn]] void fail(int line, const std::string& what) const;

  /// A finite Fortran-style real in columns [col, col + width) of l
  /// (0-based); what names the field in errors.
  double real(const Line& l, std::size_t col, std::size_t width, const char* what) const;

  /// A decimal integer in columns [col, col + width) of l (0-based); what
  /// names the field in errors.
  int integer(const Line& l, std::size_t col, std::size_t width, const char* what) const;

private:
  template <class T>
  T field(const Line& l, std::size_t col, std::size_t width, const char* what, const char* kind,
          std::optional<T> (*parse)(std::string_view) noexcept) const;

  std::string name_;
};

/// A RINEX header line's label: columns 61-80, trimmed (RINEX 3.05 §5.2).
std::string rinex_label(std::string_view line);

/// The first RINEX header line, "RINEX VERSION / TYPE".
struct RinexVersionLine {
  double version = 0.0;  ///< 2.00 .. 2.11 or 3.00 .. 3.05
  int major = 0;         ///< 2 or 3
  char type = ' ';       ///< column 21: 'N' navigation, 'O' observation, ...
  char system = ' ';     ///< column 41: 'G' GPS, 'M' mixed, ... (blank in RINEX 2 GPS files)
};

/// Reads a file's first line; throws (via r) for a first line that is not
/// "RINEX VERSION / TYPE" and versions outside 2.00-2.11 and 3.00-3.05.
RinexVersionLine read_rinex_version_line(const ColumnReader& r, const Line& first);
/// The same on lines[0]; also throws for an empty file.
RinexVersionLine read_rinex_version(const ColumnReader& r, const std::vector<Line>& lines);

}  // namespace gnssemu::text

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Fixed-column text of RINEX 3.04 files (§5.2: header labels in columns
// 61-80), shared by the observation and navigation writers. Lines are built
// in a caller's buffer: writing an epoch allocates nothing.
#include <array>
#include <cstddef>
#include <ostream>
#include <string_view>

namespace gnssemu::rinex {

/// One output line under construction, at most 128 characters.
class LineBuf {
public:
  /// Append printf-formatted text (clipped at the buffer's end).
  [[gnu::format(printf, 2, 3)]] LineBuf& add(const char* format, ...) noexcept;
  /// Pad with blanks to column col (0-based); nothing when already past it.
  LineBuf& pad_to(std::size_t col) noexcept;
  std::size_t size() const noexcept { return n_; }
  std::string_view text() const noexcept { return {buf_.data(), n_}; }
  void clear() noexcept { n_ = 0; }
  /// Write the line and a line end, then clear it.
  void flush(std::ostream& out) noexcept;

private:
  std::array<char, 160> buf_{};
  std::size_t n_ = 0;
};

/// A header line: content padded to column 60, then the label.
void header_line(std::ostream& out, LineBuf& l, std::string_view label) noexcept;

/// The first header line: version 3.04, the file type field (column 21, its
/// first letter the type: "OBSERVATION DATA", "N: GNSS NAV DATA") and the
/// system field (column 41: "M", "M: MIXED").
void version_line(std::ostream& out, std::string_view type, std::string_view system) noexcept;

/// PGM / RUN BY / DATE with the program name and a fixed date (the output
/// of a seeded run is deterministic, so it does not carry the wall clock).
void program_line(std::ostream& out) noexcept;

}  // namespace gnssemu::rinex

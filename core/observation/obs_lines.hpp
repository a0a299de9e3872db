// SPDX-License-Identifier: Apache-2.0
#pragma once
// Where the observation reader takes its lines from: a RINEX file as it is,
// or a Compact RINEX (Hatanaka) file decoded one epoch at a time, so that
// both go through the same parser and a day of data is never held as text.
#include <memory>
#include <string_view>

#include "core/common/line_source.hpp"
#include "core/common/sat_id.hpp"

namespace gnssemu::observation {

class ObsLines {
public:
  virtual ~ObsLines() = default;
  /// The next RINEX line; false at the end. Its number is the line of the
  /// file it came from (for Compact RINEX, the compact line it was decoded
  /// from), so every error names a line of the file the user has.
  virtual bool next(text::Line& line) = 0;
  /// The last line read from the file (0 before the first).
  virtual int line_number() const noexcept = 0;
  /// The file is Compact RINEX.
  virtual bool compact() const noexcept = 0;
};

/// True for Compact RINEX's first line ("CRINEX VERS   / TYPE").
bool is_compact_rinex(std::string_view first_line);

/// The lines of src: decoded when its first line says Compact RINEX, as
/// they are otherwise. src must outlive the result. A Compact RINEX
/// decoder writes the values of `systems` only (the satellite identifier,
/// or blank lines in RINEX 2, stand for the others, which the reader skips).
std::unique_ptr<ObsLines> open_obs_lines(text::LineSource& src, SystemSet systems = SystemSet::all());

}  // namespace gnssemu::observation

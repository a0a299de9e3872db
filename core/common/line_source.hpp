// SPDX-License-Identifier: Apache-2.0
#pragma once
// Text files read one line at a time, plain or gzip, with limits, so a
// reader checks a file's first line before it has read the rest and a
// hostile file (a gzip of newlines, a line without end) cannot exhaust
// memory: going past a limit is a gnssemu::Error naming file:line.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <memory>
#include <string>

#include "core/common/text_fields.hpp"

namespace gnssemu::text {

struct LineLimits {
  std::size_t max_line_bytes = 4096;      ///< longest line accepted, bytes (without the line end)
  std::uint64_t max_bytes = 256u << 20;   ///< most (decompressed) bytes read from the file
};

class LineSource {
public:
  /// Opens path, plain or gzip (told apart by zlib from the content).
  /// Throws gnssemu::Error "path: cannot open ...".
  LineSource(const std::string& path, LineLimits limits);
  /// Reads in (not owned; must outlive this); name is used in messages.
  LineSource(std::istream& in, std::string name, LineLimits limits);
  ~LineSource();
  LineSource(const LineSource&) = delete;
  LineSource& operator=(const LineSource&) = delete;

  /// The next line (LF or CR LF removed), numbered from 1; false at the end
  /// of the file. Throws gnssemu::Error on a read error or a limit.
  bool next(Line& line);

  const std::string& name() const noexcept { return name_; }
  /// Number of the last line returned (0 before the first).
  int line_number() const noexcept { return number_; }

  /// Where the bytes come from (a gzip or plain file, or a stream).
  class Input;

private:
  /// Refills buf_ from the input; false at the end of the input.
  bool fill();

  std::string name_;
  LineLimits limits_;
  std::unique_ptr<Input> input_;
  std::string buf_;
  std::size_t pos_ = 0;        // next unread byte in buf_
  std::uint64_t total_ = 0;    // bytes taken from the input so far
  int number_ = 0;
  bool eof_ = false;
};

}  // namespace gnssemu::text

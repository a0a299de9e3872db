// SPDX-License-Identifier: Apache-2.0
#include "core/rinex/rinex_format.hpp"

#include <cstdarg>
#include <cstdio>
#include <algorithm>

namespace gnssemu::rinex {

LineBuf& LineBuf::add(const char* format, ...) noexcept {
  if (n_ + 1 >= buf_.size()) return *this;
  va_list args;
  va_start(args, format);
  const int w = std::vsnprintf(buf_.data() + n_, buf_.size() - n_, format, args);
  va_end(args);
  if (w > 0) n_ = std::min(n_ + static_cast<std::size_t>(w), buf_.size() - 1);
  return *this;
}

LineBuf& LineBuf::pad_to(std::size_t col) noexcept {
  while (n_ < col && n_ + 1 < buf_.size()) buf_[n_++] = ' ';
  return *this;
}

void LineBuf::flush(std::ostream& out) noexcept {
  // Trailing blanks are not written (RINEX readers take short lines as blank-padded).
  std::size_t end = n_;
  while (end > 0 && buf_[end - 1] == ' ') --end;
  buf_[end] = '\n';
  out.write(buf_.data(), static_cast<std::streamsize>(end + 1));
  n_ = 0;
}

void header_line(std::ostream& out, LineBuf& l, std::string_view label) noexcept {
  l.pad_to(60);
  l.add("%-20.*s", static_cast<int>(label.size()), label.data());
  l.flush(out);
}

void version_line(std::ostream& out, std::string_view type, std::string_view system) noexcept {
  LineBuf l;
  l.add("%9.2f%11s%-20.*s%-20.*s", 3.04, "", static_cast<int>(type.size()), type.data(),
        static_cast<int>(system.size()), system.data());
  header_line(out, l, "RINEX VERSION / TYPE");
}

void program_line(std::ostream& out) noexcept {
  LineBuf l;
  l.add("%-20s%-20s%-20s", "gnssemu", "", "19800106 000000 GPS");
  header_line(out, l, "PGM / RUN BY / DATE");
}

}  // namespace gnssemu::rinex

// SPDX-License-Identifier: Apache-2.0
#pragma once
// gnssemu::Error — the one exception type, thrown only at load time
// (files, configs, command lines). The per-epoch path never throws.
#include <stdexcept>
#include <string>

namespace gnssemu {

class Error : public std::runtime_error {
public:
  /// A plain error with a message.
  explicit Error(const std::string& what);
  /// An error located in an input: "file:line: what". line <= 0 omits the line.
  Error(const std::string& file, int line, const std::string& what);

  const std::string& file() const noexcept { return file_; }
  /// 1-based line in file(), or 0 if unknown.
  int line() const noexcept { return line_; }

private:
  std::string file_;
  int line_ = 0;
};

}  // namespace gnssemu

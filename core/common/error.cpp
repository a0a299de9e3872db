// SPDX-License-Identifier: Apache-2.0
#include "core/common/error.hpp"

namespace gnssemu {

namespace {
std::string located(const std::string& file, int line, const std::string& what) {
  if (file.empty()) return what;
  if (line <= 0) return file + ": " + what;
  return file + ":" + std::to_string(line) + ": " + what;
}
}  // namespace

Error::Error(const std::string& what) : std::runtime_error(what) {}

Error::Error(const std::string& file, int line, const std::string& what)
    : std::runtime_error(located(file, line, what)), file_(file), line_(line) {}

}  // namespace gnssemu

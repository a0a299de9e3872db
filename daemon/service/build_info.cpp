// SPDX-License-Identifier: Apache-2.0
#include "daemon/service/build_info.hpp"

namespace gnssemu::daemon {

namespace {

// A string literal written at build time by cmake/git_commit.cmake.
constexpr char kGitCommit[] =
#include "git_commit.inc"
    ;

}  // namespace

std::string_view version() { return GNSSEMU_VERSION; }

std::string_view git_commit() { return kGitCommit; }

std::string version_line(std::string_view program) {
  std::string line(program);
  line.append(" ").append(version()).append(" (git ").append(git_commit()).append(")");
  return line;
}

}  // namespace gnssemu::daemon

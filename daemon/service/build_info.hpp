// SPDX-License-Identifier: Apache-2.0
#pragma once
// What was built: the release version and the git commit of the source.
#include <string>
#include <string_view>

namespace gnssemu::daemon {

/// Release version, "MAJOR.MINOR.PATCH" (project() in CMakeLists.txt).
std::string_view version();

/// Git commit of the source that was built: 12 hex digits, "-dirty" appended
/// when tracked files differed from it, or "unknown" when the source was not
/// a git checkout and no commit was recorded (cmake/git_commit.cmake).
std::string_view git_commit();

/// "<program> <version> (git <commit>)", the first line of every --version.
/// @param program  executable name, e.g. "gnssemud"
std::string version_line(std::string_view program);

}  // namespace gnssemu::daemon

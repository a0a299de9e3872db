// SPDX-License-Identifier: Apache-2.0
#pragma once
// Where gnssemud looks for its shipped default.toml when run without
// --config (docs/daemon.md §Default configuration).
#include <string>
#include <vector>

namespace gnssemu::daemon {

/// Candidate paths, in search order, for an executable at exe_path:
/// <exe dir>/default.toml, <exe dir>/config/default.toml,
/// <exe dir>/../share/gnssemu/default.toml, <install prefix>/share/gnssemu/default.toml,
/// <source tree>/config/default.toml (compiled in).
std::vector<std::string> default_config_candidates(const std::string& exe_path);

/// First existing candidate, or "" when none exists.
std::string find_default_config(const std::string& exe_path);

}  // namespace gnssemu::daemon

// SPDX-License-Identifier: Apache-2.0
#pragma once
// A task's configuration: the base config file with the task's overrides
// (dotted keys such as receiver.profile, and the seed axis as receiver.seed)
// set in its TOML before the config reader checks it.
#include <string>
#include <utility>
#include <vector>

#include "config/config.hpp"

namespace gnssemu::cli::sweep {

/// key ("receiver.profile") and value text as tasks.csv carries it.
using Override = std::pair<std::string, std::string>;

/// The base file's TOML with each override set (tables created as needed)
/// and then parsed as the config reader parses files, relative paths against
/// the base file's folder. Throws gnssemu::Error: the base file's own
/// file:line errors, or "KEY = VALUE: reason" for an override the reader
/// rejects (unknown key, wrong type, out of range).
config::Config config_with_overrides(const std::string& base_path, const std::vector<Override>& overrides);

}  // namespace gnssemu::cli::sweep

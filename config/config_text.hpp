// SPDX-License-Identifier: Apache-2.0
#pragma once
// parse_config and to_toml with a log of the keys read or written: the
// tests compare the two logs with each other and with the documented keys.
// Internal to the config module.
#include <string>

#include "config/config.hpp"
#include "config/toml/toml_reader.hpp"

namespace gnssemu::config::detail {

/// parse_config; log (may be null) receives the dotted name of every key asked for.
Config parse_config_text(const std::string& toml_text, const std::string& name, const std::string& base_dir,
                         KeyLog* log);
/// to_toml; log (may be null) receives "dotted.name = value" of every key written.
std::string config_text(const Config& c, const std::string& relative_to, KeyLog* log);

}  // namespace gnssemu::config::detail

// SPDX-License-Identifier: Apache-2.0
#pragma once
// The key tables of a configuration file (fields.hpp): one Section per TOML
// table, each next to the tables it nests. Adding a key is one row in the
// table of its section. Internal to the config module.
#include <vector>

#include "config/config.hpp"
#include "config/fields.hpp"

namespace gnssemu::config::detail {

/// The whole file: [origin], [nav], [time], [receiver], ... (config_keys.cpp).
extern const Section<Config> kConfigKeys;
/// [receiver] and its sub-tables (receiver_keys.cpp).
extern const Section<Config> kReceiverKeys;
/// [atmosphere] and its sub-tables (atmosphere_keys.cpp).
extern const Section<world::AtmosphereConfig> kAtmosphereKeys;
/// [signal] and its sub-tables (signal_keys.cpp).
extern const Section<Config> kSignalKeys;
/// One [[output]] (output_keys.cpp).
extern const Section<OutputPortConfig> kOutputKeys;
/// [scene] (scene_keys.cpp).
extern const Section<SceneConfig> kSceneKeys;

/// What a port claims that another may not: name, path or device, tcp port.
/// Throws at port's line in t when an earlier port (before) has it.
void check_unique_port(TableReader& t, const std::vector<OutputPortConfig>& before, const OutputPortConfig& port);

/// Every port's ubx_messages exist on [receiver] generation (NAV-SVINFO up
/// to the M8, MON-RF and SEC-SIG from the M9). Throws naming the message's
/// line in the [[output]] that lists it.
void check_output_generation(TableReader& t, const Field<Config>& f, Config& c);

/// The key tables of every table, in file order (the rows of docs/configuration.md).
KeyDocs describe_keys();

}  // namespace gnssemu::config::detail

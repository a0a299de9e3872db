// SPDX-License-Identifier: Apache-2.0
#pragma once
// The key tables of a configuration file (fields.hpp): one Section per TOML
// table, each next to the tables it nests. Adding a key is one row in the
// table of its section. Internal to the config module.
#include <vector>

#include "config/config.hpp"
#include "config/keys/fields.hpp"

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
/// One [[fleet.output]] template: [[output]]'s keys, port_base for port (output_keys.cpp).
extern const Section<OutputPortConfig> kFleetOutputKeys;
/// [[base.output]]: name, type and its keys, baud.
extern const Section<OutputPortConfig> kBaseOutputKeys;
/// [scene] (scene_keys.cpp).
extern const Section<SceneConfig> kSceneKeys;

/// What a port claims that another may not: name, path or device, tcp port.
/// Throws at port's line in t when an earlier port (before) has it.
void check_unique_port(TableReader& t, const std::vector<OutputPortConfig>& before, const OutputPortConfig& port);

/// The file or device a port claims for itself ("" for network ports).
std::string claimed_path(const PortTransport& transport);

/// Every port's ubx_messages exist on [receiver] generation (NAV-SVINFO up
/// to the M8, MON-RF and SEC-SIG from the M9). Throws naming the message's
/// line in the [[output]] that lists it. Gives a pty or serial port without
/// `baud` the generation's UART1 factory rate, and a port without
/// `nmea_version` the generation's factory NMEA version.
void check_output_generation(TableReader& t, const Field<Config>& f, Config& c);

/// [[vehicle]] (vehicle_keys.cpp): read after [receiver], [atmosphere] and
/// [signal], whose settings each receiver starts from.
/// An `allow` list of addresses and CIDR blocks at key (replacing out when
/// given; a bad entry fails at its line) and its TOML text ("" when empty).
void read_address_blocks(TableReader& t, std::string_view key, std::vector<AddressBlock>& out);
std::string address_blocks_text(const std::vector<AddressBlock>& blocks);

void read_vehicles(TableReader& t, const Field<Config>& f, Config& c);
void write_vehicles(TomlWriter& w, const Field<Config>& f, const Config& c);
void describe_vehicles(KeyDocs& d, const Field<Config>& f, const Config& c);
/// [fleet] and its [[fleet.output]] templates; after [[vehicle]] (ids).
void read_fleet(TableReader& t, const Field<Config>& f, Config& c);
void write_fleet(TomlWriter& w, const Field<Config>& f, const Config& c);
void describe_fleet(KeyDocs& d, const Field<Config>& f, const Config& c);
/// The rows of [receiver] on table r over a copy of top's receiver settings:
/// what r gives overrides them ([[vehicle.receiver]], [base]).
ReceiverSettings receiver_overrides(TableReader& r, const Config& top);
/// [base] (base_keys.cpp): after [receiver], [atmosphere] and [signal].
void read_base(TableReader& t, const Field<Config>& f, Config& c);
void write_base(TomlWriter& w, const Field<Config>& f, const Config& c);
void describe_base(KeyDocs& d, const Field<Config>& f, const Config& c);
/// The single-vehicle form or vehicles (not both); no path, device, tcp port
/// or udp destination twice among all receivers after template expansion,
/// nor the status page's port. After [status].
void check_vehicles(TableReader& t, const Field<Config>& f, Config& c);

/// The key tables of every table, in file order (the rows of docs/configuration.md).
KeyDocs describe_keys();

}  // namespace gnssemu::config::detail

// SPDX-License-Identifier: Apache-2.0
// TOML <-> Config through the key tables (config_keys.hpp). Schema and
// ranges: docs/configuration.md.
#include "config/config.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "config/keys/config_keys.hpp"
#include "config/config_text.hpp"
#include "config/setup/device_setup.hpp"
#include "config/message_names.hpp"
#include "core/common/error.hpp"

namespace gnssemu::config {

namespace fs = std::filesystem;

std::vector<MessageRate> message_rates(const OutputPortConfig& port) {
  std::vector<MessageRate> out = port.ubx_messages;
  for (const MessageName& m : nmea_sentences()) {
    if (!sentence_on(port.nmea.sentences, m.msg_id)) continue;
    uint8_t rate = 1;
    for (const MessageRate& r : port.nmea_rates) {
      if (r.msg_id == m.msg_id) rate = r.rate;
    }
    out.push_back({m.msg_class, m.msg_id, rate});
  }
  return out;
}

namespace detail {

Config parse_config_text(const std::string& toml_text, const std::string& name, const std::string& base_dir,
                         KeyLog* log) {
  toml::table doc;
  try {
    doc = toml::parse(toml_text, name);
  } catch (const toml::parse_error& e) {
    throw Error(name, static_cast<int>(e.source().begin.line), "TOML syntax error: " + std::string(e.description()));
  }
  Config c;
  c.world.systems = SystemSet{};  // unset until [receiver] constellations, then the chip's set
  TableReader root(doc, "", name, base_dir, log);
  read_section(root, kConfigKeys, c);
  // The generation is known only now.
  if (c.world.systems.empty()) c.world.systems = chip_systems(c);
  c.source = name;
  return c;
}

std::string config_text(const Config& c, const std::string& relative_to, KeyLog* log) {
  TomlWriter w(relative_to, log);
  w.line("# gnssemu configuration. Keys, units and ranges: docs/configuration.md");
  write_rows(w, kConfigKeys, c);
  return std::move(w).text();
}

}  // namespace detail

Config parse_config(const std::string& toml_text, const std::string& name, const std::string& base_dir) {
  return detail::parse_config_text(toml_text, name, base_dir, nullptr);
}

std::string to_toml(const Config& c, const std::string& relative_to) {
  return detail::config_text(c, relative_to, nullptr);
}

Config load_config(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error(path, 0, "is a folder, not a config file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, 0, "cannot open config file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path, 0, "cannot read config file");
  const fs::path parent = fs::path(path).parent_path();
  return parse_config(text.str(), path, parent.empty() ? std::string(".") : parent.string());
}

std::string default_config_dir() { return GNSSEMU_CONFIG_DIR; }

Config default_config(const std::string& base_dir) {
  Config c = parse_config(std::string(default_config_text()), "default.toml (built in)",
                          base_dir.empty() ? default_config_dir() : base_dir);
  c.source.clear();
  return c;
}

}  // namespace gnssemu::config

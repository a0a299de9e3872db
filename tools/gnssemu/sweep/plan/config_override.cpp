// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/plan/config_override.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <sstream>

#include "core/common/error.hpp"
#include "tools/gnssemu/sweep/plan/input_hash.hpp"

namespace gnssemu::cli::sweep {

namespace {

/// The value node of tasks.csv text: TOML when it parses as a value, else a string.
toml::table value_of(const std::string& text) {
  try {
    toml::table t = toml::parse("v = " + text);
    return t;
  } catch (const toml::parse_error&) {
    toml::table t;
    t.insert("v", text);
    return t;
  }
}

}  // namespace

config::Config config_with_overrides(const std::string& base_path, const std::vector<Override>& overrides) {
  const std::string base_dir = std::filesystem::absolute(base_path).parent_path().string();
  if (overrides.empty()) return config::load_config(base_path);
  const std::string text = read_file_bytes(base_path);
  // The base alone first: its errors keep their own line numbers.
  (void)config::parse_config(text, base_path, base_dir);
  toml::table doc = toml::parse(text, base_path);
  for (const auto& [key, value] : overrides) {
    toml::table* t = &doc;
    std::size_t pos = 0;
    for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', pos)) {
      const std::string part = key.substr(pos, dot - pos);
      pos = dot + 1;
      toml::node* n = t->get(part);
      if (n == nullptr) n = &t->insert_or_assign(part, toml::table{}).first->second;
      t = n->as_table();
      if (t == nullptr) throw Error(key + " = " + value + ": '" + part + "' is not a table in " + base_path);
    }
    toml::table v = value_of(value);
    t->insert_or_assign(key.substr(pos), std::move(*v.get("v")));
  }
  std::ostringstream os;
  os << doc;
  try {
    return config::parse_config(os.str(), base_path, base_dir);
  } catch (const Error& e) {
    // The line is of the rewritten text: name the overrides instead.
    std::string what;
    for (const auto& [key, value] : overrides) what += (what.empty() ? "" : ", ") + key + " = " + value;
    const std::string msg = e.what();
    const std::size_t colon = msg.find(": ", msg.find(base_path) == 0 ? base_path.size() : 0);
    throw Error(what + ": " + (colon == std::string::npos ? msg : msg.substr(colon + 2)));
  }
}

}  // namespace gnssemu::cli::sweep

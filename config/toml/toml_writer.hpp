// SPDX-License-Identifier: Apache-2.0
#pragma once
// TOML text of a configuration (to_toml): section headers and key lines,
// and the value texts that read back to exactly the written value.
// Internal to the config module.
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "config/toml/toml_reader.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::config::detail {

/// TOML float text; always has a '.' or exponent so it reads back as a float.
std::string number_text(double v);
/// Degrees text whose reading times kDegToRad gives back rad exactly when a
/// nearby double allows it (deg -> rad is not exactly invertible).
std::string degrees_text(double rad);
/// TOML basic string with escapes (TOML 1.0 section "String").
std::string string_text(std::string_view s);
/// ["a", "b"]: an array of strings.
std::string strings_text(std::span<const std::string_view> items);
/// "true" or "false".
std::string bool_text(bool v);
/// "YYYY-MM-DDTHH:MM:SS.fff" of t's calendar (GPS time scale).
std::string datetime_text(const time::GpsTime& t);

class TomlWriter {
public:
  /// relative_to: folder that paths under it are written relative to ("": none).
  /// log (optional): receives "dotted.name = value" of every key written.
  explicit TomlWriter(std::string relative_to, KeyLog* log = nullptr);

  /// A path as written: relative to relative_to when under it, else as given.
  std::string path_text(const std::string& path) const;

  /// Makes path (dotted) the table the following keys belong to.
  void set_table(std::string path) { table_ = std::move(path); }
  /// Writes the current table's header ([[table]] when array), with a
  /// comment when note is not empty.
  void header(std::string_view note, bool array = false);
  /// key = value, with a comment when note is not empty, in the current table.
  void key(std::string_view key, const std::string& value, std::string_view note = {});
  /// A line as it is (a comment).
  void line(std::string_view text);

  /// The value of the last key written (docs take defaults from it).
  const std::string& last_value() const noexcept { return last_value_; }
  /// Dotted name of the current table ("" at the top).
  const std::string& table() const noexcept { return table_; }

  std::string text() && { return std::move(out_); }

private:
  std::string relative_to_;
  KeyLog* log_;
  std::string out_;
  std::string table_;
  std::string last_value_;
};

}  // namespace gnssemu::config::detail

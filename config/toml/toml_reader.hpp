// SPDX-License-Identifier: Apache-2.0
#pragma once
// Checked access to one TOML table: typed getters with ranges, and a final
// check that every key in the table was asked for (catches typos). Every
// failure is a gnssemu::Error "file:line: reason" with the offending line.
// Internal to the config module.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "core/common/range.hpp"

namespace gnssemu::config::detail {

using gnssemu::format_number;
using gnssemu::Range;
/// "a string", "an integer", ...
std::string_view type_name(const toml::node& n);
/// 1-based line of a node, 0 if toml++ has none.
int line_of(const toml::node& n);

/// Dotted names of the keys readers asked for, in order (tests compare them
/// with the written and the documented keys).
using KeyLog = std::vector<std::string>;

class TableReader {
public:
  /// table: the table; path: its dotted name ("" for the root, "receiver.errors",
  /// "output[0]"); file: name used in messages; base_dir: folder relative
  /// paths resolve against; log (optional): receives every key asked for.
  /// file, base_dir and log must outlive the reader and its sub-readers.
  TableReader(const toml::table& table, std::string path, const std::string& file, const std::string& base_dir,
              KeyLog* log = nullptr);

  /// The node under key or nullptr; marks key as known.
  const toml::node* find(std::string_view key);
  /// The node under key or nullptr, not marked as known nor logged (a key
  /// the table does not take, looked at for a better message).
  const toml::node* peek(std::string_view key) const { return table_->get(key); }

  /// A number (integer or float), finite and inside range. Absent: def, or a
  /// "missing" error when def is empty.
  double number(std::string_view key, std::optional<double> def, const Range& range);
  /// An integer in [min, max] (floats rejected).
  int64_t integer(std::string_view key, std::optional<int64_t> def, int64_t min, int64_t max);
  bool boolean(std::string_view key, std::optional<bool> def);
  std::string string(std::string_view key, std::optional<std::string> def);
  /// A sub-table; nullopt if absent and not required.
  std::optional<TableReader> table(std::string_view key, bool required);
  /// An array of tables ([[key]]); empty if absent.
  std::vector<TableReader> table_array(std::string_view key);
  /// An array of strings: item(element node, its text) for each, in order.
  /// Errors "key: expected <array_what>, got <type>" and "key: expected
  /// <item_what>, got <type>". The array; nullptr when key is absent.
  template <class Item>
  const toml::array* string_array(std::string_view key, std::string_view array_what, std::string_view item_what,
                                  Item&& item) {
    const toml::node* n = find(key);
    if (n == nullptr) return nullptr;
    const toml::array* a = n->as_array();
    if (a == nullptr) fail(*n, full_name(key) + ": expected " + std::string(array_what) + ", got " + std::string(type_name(*n)));
    for (const toml::node& e : *a) {
      const auto* s = e.as_string();
      if (s == nullptr) fail(e, full_name(key) + ": expected " + std::string(item_what) + ", got " + std::string(type_name(e)));
      item(e, s->get());
    }
    return a;
  }

  /// Throws for the first (in file order) key that was never asked for;
  /// note (if any) follows the reason, e.g. what the table takes.
  void finish(std::string_view note = {}) const;

  /// Dotted name of key in this table ("receiver.rate_hz").
  std::string full_name(std::string_view key) const;
  /// Line of this table's header (0 if unknown, e.g. the root).
  int line() const;
  const std::string& file() const noexcept { return *file_; }
  const std::string& path() const noexcept { return path_; }
  const std::string& base_dir() const noexcept { return *base_dir_; }

  [[noreturn]] void fail(const toml::node& at, const std::string& reason) const;
  [[noreturn]] void fail_missing(std::string_view key, std::string_view what) const;

private:
  const toml::table* table_;
  std::string path_;
  const std::string* file_;
  const std::string* base_dir_;
  KeyLog* log_;
  std::vector<std::string> known_;
};

}  // namespace gnssemu::config::detail

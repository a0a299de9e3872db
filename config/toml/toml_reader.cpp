// SPDX-License-Identifier: Apache-2.0
#include "config/toml/toml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "core/common/error.hpp"

namespace gnssemu::config::detail {

namespace {

// Edit distance for "did you mean" hints; keys are short.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string_view type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    case toml::node_type::none: break;
  }
  return "nothing";
}

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

TableReader::TableReader(const toml::table& table, std::string path, const std::string& file,
                         const std::string& base_dir, KeyLog* log)
    : table_(&table), path_(std::move(path)), file_(&file), base_dir_(&base_dir), log_(log) {}

std::string TableReader::full_name(std::string_view key) const {
  if (path_.empty()) return std::string(key);
  return path_ + "." + std::string(key);
}

int TableReader::line() const { return path_.empty() ? 0 : static_cast<int>(table_->source().begin.line); }

void TableReader::fail(const toml::node& at, const std::string& reason) const {
  throw Error(*file_, line_of(at), reason);
}

void TableReader::fail_missing(std::string_view key, std::string_view what) const {
  const std::string where = path_.empty() ? std::string("at top level") : "in [" + path_ + "]";
  throw Error(*file_, line(), "missing required " + std::string(what) + " '" + full_name(key) + "' " + where);
}

const toml::node* TableReader::find(std::string_view key) {
  known_.emplace_back(key);
  if (log_ != nullptr) log_->push_back(full_name(key));
  return table_->get(key);
}

double TableReader::number(std::string_view key, std::optional<double> def, const Range& range) {
  const toml::node* n = find(key);
  if (n == nullptr) {
    if (!def) fail_missing(key, "key");
    return *def;
  }
  double v = 0.0;
  if (const auto* i = n->as_integer()) {
    v = static_cast<double>(i->get());
  } else if (const auto* f = n->as_floating_point()) {
    v = f->get();
  } else {
    fail(*n, full_name(key) + ": expected a number, got " + std::string(type_name(*n)));
  }
  if (!std::isfinite(v)) fail(*n, full_name(key) + ": must be a finite number, got " + format_number(v));
  if (!range.contains(v)) {
    fail(*n, full_name(key) + ": " + format_number(v) + " is out of range " + format_range(range));
  }
  return v;
}

int64_t TableReader::integer(std::string_view key, std::optional<int64_t> def, int64_t min, int64_t max) {
  const toml::node* n = find(key);
  if (n == nullptr) {
    if (!def) fail_missing(key, "key");
    return *def;
  }
  const auto* i = n->as_integer();
  if (i == nullptr) {
    std::string got(type_name(*n));
    if (const auto* f = n->as_floating_point()) got += " (" + format_number(f->get()) + ")";
    fail(*n, full_name(key) + ": expected an integer, got " + got);
  }
  const int64_t v = i->get();
  if (v < min || v > max) {
    fail(*n, full_name(key) + ": " + std::to_string(v) + " is out of range [" + std::to_string(min) + ", " +
                 std::to_string(max) + "]");
  }
  return v;
}

bool TableReader::boolean(std::string_view key, std::optional<bool> def) {
  const toml::node* n = find(key);
  if (n == nullptr) {
    if (!def) fail_missing(key, "key");
    return *def;
  }
  const auto* b = n->as_boolean();
  if (b == nullptr) fail(*n, full_name(key) + ": expected true or false, got " + std::string(type_name(*n)));
  return b->get();
}

std::string TableReader::string(std::string_view key, std::optional<std::string> def) {
  const toml::node* n = find(key);
  if (n == nullptr) {
    if (!def) fail_missing(key, "key");
    return *def;
  }
  const auto* s = n->as_string();
  if (s == nullptr) fail(*n, full_name(key) + ": expected a string, got " + std::string(type_name(*n)));
  return s->get();
}

std::optional<TableReader> TableReader::table(std::string_view key, bool required) {
  const toml::node* n = find(key);
  if (n == nullptr) {
    if (required) fail_missing(key, "table");
    return std::nullopt;
  }
  const auto* t = n->as_table();
  if (t == nullptr) {
    fail(*n, full_name(key) + ": expected a table ([" + full_name(key) + "]), got " + std::string(type_name(*n)));
  }
  return TableReader(*t, full_name(key), *file_, *base_dir_, log_);
}

std::vector<TableReader> TableReader::table_array(std::string_view key) {
  std::vector<TableReader> out;
  const toml::node* n = find(key);
  if (n == nullptr) return out;
  const auto* a = n->as_array();
  if (a == nullptr) {
    fail(*n, full_name(key) + ": expected an array of tables ([[" + full_name(key) + "]]), got " +
                 std::string(type_name(*n)));
  }
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const auto* t = e.as_table();
    const std::string name = full_name(key) + "[" + std::to_string(i) + "]";
    if (t == nullptr) fail(e, name + ": expected a table, got " + std::string(type_name(e)));
    out.emplace_back(*t, name, *file_, *base_dir_, log_);
  }
  return out;
}

void TableReader::finish(std::string_view note) const {
  const toml::key* first = nullptr;
  for (const auto& [k, v] : *table_) {
    if (std::find(known_.begin(), known_.end(), k.str()) != known_.end()) continue;
    if (first == nullptr || k.source().begin < first->source().begin) first = &k;
  }
  if (first == nullptr) return;
  std::string reason = "unknown key '" + full_name(first->str()) + "'";
  std::size_t best = std::numeric_limits<std::size_t>::max();
  std::string_view hint;
  for (const auto& k : known_) {
    const std::size_t d = edit_distance(first->str(), k);
    if (d < best) {
      best = d;
      hint = k;
    }
  }
  if (best <= 3 && best < first->str().size()) reason += " (did you mean '" + std::string(hint) + "'?)";
  if (!note.empty()) reason += "; " + std::string(note);
  throw Error(*file_, static_cast<int>(first->source().begin.line), reason);
}

}  // namespace gnssemu::config::detail

// SPDX-License-Identifier: Apache-2.0
#include "config/keys/fields.hpp"

#include <arpa/inet.h>

#include <filesystem>

namespace gnssemu::config::detail {

void KeyDocs::enter(std::string_view key, std::string_view group) {
  std::string path(key);
  if (!open_.empty() && !tables_[open_.back()].path.empty()) path = tables_[open_.back()].path + "." + path;
  TableDoc t;
  t.path = path;
  t.group = group.empty() ? path : std::string(group);
  tables_.push_back(std::move(t));
  open_.push_back(tables_.size() - 1);
}

void KeyDocs::leave() { open_.pop_back(); }

void KeyDocs::add(KeyDoc row) {
  if (open_.empty()) enter("");
  tables_[open_.back()].keys.push_back(std::move(row));
}

std::string reason_of(const Error& e) {
  const std::string w = e.what();
  if (e.file().empty()) return w;
  const std::size_t p = w.find(": ", e.file().size());
  return p == std::string::npos ? w : w.substr(p + 2);
}

std::string resolve_path(const std::string& path, const std::string& base_dir) {
  std::filesystem::path p(path);
  if (p.is_relative()) p = std::filesystem::path(base_dir.empty() ? "." : base_dir) / p;
  return std::filesystem::absolute(p).lexically_normal().string();
}

bool is_file(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

std::string existing_path(TableReader& t, const toml::node& n, const std::string& name, const std::string& given,
                          PathKind kind) {
  if (given.empty()) t.fail(n, name + ": must not be empty");
  const std::string path = resolve_path(given, t.base_dir());
  if (kind == PathKind::kFile && !is_file(path)) t.fail(n, name + ": '" + given + "' not found (tried " + path + ")");
  std::error_code ec;
  if (kind == PathKind::kFolder && !std::filesystem::is_directory(path, ec)) {
    t.fail(n, name + ": '" + given + "' is not a folder (tried " + path + ")");
  }
  return path;
}

bool is_ip_address(const std::string& text) {
  in6_addr buf{};
  return inet_pton(AF_INET, text.c_str(), &buf) == 1 || inet_pton(AF_INET6, text.c_str(), &buf) == 1;
}

const toml::node* present(TableReader& t, std::string_view key, bool required) {
  const toml::node* n = t.find(key);
  if (n == nullptr && required) t.fail_missing(key, "key");
  return n;
}

std::string sub_table(const TomlWriter& w, std::string_view key) {
  return w.table().empty() ? std::string(key) : w.table() + "." + std::string(key);
}

std::string range_text(const Range& r) {
  const Range bare{r.min, r.max, "", r.min_open, r.max_open};
  return format_range(bare);
}

std::string integer_range_text(int64_t min, int64_t max) {
  return "integer [" + std::to_string(min) + ", " + std::to_string(max) + "]";
}

std::string known_names(std::span<const std::string_view> names, ChoiceStyle style) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += style == ChoiceStyle::kEither ? " or " : ", ";
    out += '"';
    out += names[i];
    out += '"';
  }
  return out;
}

std::string names_doc(std::span<const std::string_view> names) {
  std::string out;
  for (const std::string_view n : names) out += (out.empty() ? "`\"" : ", `\"") + std::string(n) + "\"`";
  return out;
}

void fail_rule(TableReader& t, const Violation& v, RuleScope scope) {
  const toml::node* n = v.field.empty() ? nullptr : t.find(v.field);
  if (n == nullptr && !v.other.empty()) n = t.find(v.other);
  const std::string prefix = scope == RuleScope::kKey ? t.full_name(v.field) : t.path();
  const std::string reason = prefix + ": " + v.reason;
  if (n != nullptr) t.fail(*n, reason);
  throw Error(t.file(), t.line(), reason);
}

}  // namespace gnssemu::config::detail

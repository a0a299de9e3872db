// SPDX-License-Identifier: Apache-2.0
#pragma once
// Field descriptors: one row per TOML key of a configuration table, with
// what the reader, the writer (to_toml) and the key tables of
// docs/configuration.md need, so one row reads, writes and documents a key.
// A Section is a table's rows in file order. Reading runs them in order (the
// first problem in that order is the one reported), then reports unknown
// keys (TableReader::finish), then runs the section's core validator.
// Ranges are the core's ...Ranges objects; cross-field rules are the core's
// check_* functions (core/common/violation.hpp), reported at their key.
// Internal to the config module.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "config/toml/toml_reader.hpp"
#include "config/toml/toml_writer.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/common/violation.hpp"

namespace gnssemu::config::detail {

// --- docs ------------------------------------------------------------------

/// One row of a key table (key | unit | default | range | meaning).
struct KeyDoc {
  std::string key;
  std::string unit;
  std::string default_text;
  std::string range;
  std::string meaning;
  bool alias = false;      ///< read only: written as another key (e.g. a preset)
  bool open_keys = false;  ///< its keys are names from the data (e.g. material names)
  /// Non-empty: the row stands for every key of that table (e.g. "receiver":
  /// [[vehicle.receiver]] takes the keys of [receiver]).
  std::string mirror{};
};

/// The key table of one TOML table.
struct TableDoc {
  std::string path;   ///< dotted name: "receiver.solver", "output" ([[output]]), "atmosphere.shells.troposphere"
  std::string group;  ///< tables documented together share it ("atmosphere.shells.<name>"); else path
  std::vector<KeyDoc> keys;
};

/// Key tables in file order, as a walk over the sections produces them.
class KeyDocs {
public:
  /// Enters table key of the current one (group: see TableDoc; "" = its path).
  void enter(std::string_view key, std::string_view group = {});
  void leave();
  void add(KeyDoc row);
  const std::vector<TableDoc>& tables() const noexcept { return tables_; }

private:
  std::vector<TableDoc> tables_;
  std::vector<std::size_t> open_;  ///< indices into tables_ of the tables entered
};

// --- rows ------------------------------------------------------------------

/// What a row is: a key the writer writes, a sub-table, or a check.
enum class RowKind : uint8_t {
  kKey,    ///< a key of this table
  kTable,  ///< a sub-table or array of tables (writes its own header)
  kCheck,  ///< a cross-field rule or a core validator (no key)
};

template <class T>
struct Field {
  std::string_view key;       ///< TOML key ("" for a check)
  std::string_view meaning;   ///< docs
  RowKind kind = RowKind::kKey;
  bool required = false;
  Range range{0.0, 0.0, ""};  ///< numbers and angles (degrees): a core range, never a copy
  int64_t min = 0;            ///< integers
  int64_t max = 0;
  std::string_view unit;         ///< docs, where range has none
  std::string_view note;         ///< written as a trailing comment (a table: on its header)
  std::string_view doc_default;  ///< docs, where the written default says less
  std::string_view doc_range;    ///< docs, where range, bounds or names say less
  std::string (*doc_range_of)() = nullptr;  ///< docs, where the range text is computed (names of a core table)
  bool open_keys = false;        ///< docs: a table whose keys are names from the data
  /// Plain keys: the member the key holds, of the type its kind reads (one
  /// small function per row; the kind's read, write and docs are shared).
  void* (*at)(T&) = nullptr;
  void (*read)(TableReader&, const Field&, T&) = nullptr;
  /// nullptr: read only, an alias the writer writes as another key.
  void (*write)(TomlWriter&, const Field&, const T&) = nullptr;
  /// Docs rows (sub-tables: their tables) given the default value.
  void (*describe)(KeyDocs&, const Field&, const T&) = nullptr;

  constexpr Field with_note(std::string_view n) const {
    Field f = *this;
    f.note = n;
    return f;
  }
  constexpr Field needed() const {
    Field f = *this;
    f.required = true;
    return f;
  }
  constexpr Field default_doc(std::string_view text) const {
    Field f = *this;
    f.doc_default = text;
    return f;
  }
};

/// A row for key with its docs text, its functions still to be set.
template <class T>
constexpr Field<T> make_field(std::string_view key, std::string_view meaning) {
  Field<T> row{};
  row.key = key;
  row.meaning = meaning;
  return row;
}

/// The rows of one table and the core validator run after them.
template <class T>
struct Section {
  std::span<const Field<T>> fields;
  void (*validate)(const T&) = nullptr;  ///< throws gnssemu::Error; reported at the table's header
};

// --- running a section -----------------------------------------------------

/// The reason of a core error without its "what: " prefix.
std::string reason_of(const Error& e);

/// Runs validate (a core validator); its gnssemu::Error is re-thrown at line
/// (a table's header) of file.
template <class Validate>
void validate_at(const std::string& file, int line, Validate&& validate) {
  try {
    validate();
  } catch (const Error& e) {
    throw Error(file, line, reason_of(e));
  }
}

template <class T>
void read_section(TableReader& t, const Section<T>& s, T& out) {
  for (const Field<T>& f : s.fields) f.read(t, f, out);
  t.finish();
  if (s.validate != nullptr) validate_at(t.file(), t.line(), [&] { s.validate(out); });
}

/// The rows of s (without a header) for value.
template <class T>
void write_rows(TomlWriter& w, const Section<T>& s, const T& value) {
  for (const Field<T>& f : s.fields) {
    if (f.write != nullptr) f.write(w, f, value);
  }
}

/// Table path of value: its header with note (an array's always, a table's
/// when s has keys of its own: [atmosphere.shells] has none), then its rows.
template <class T>
void write_table(TomlWriter& w, const Section<T>& s, const std::string& path, std::string_view note, const T& value,
                 bool array = false) {
  const std::string outer = w.table();
  w.set_table(path);
  bool keys = array;
  for (const Field<T>& f : s.fields) keys = keys || f.kind == RowKind::kKey;
  if (keys) w.header(note, array);
  write_rows(w, s, value);
  w.set_table(outer);
}

template <class T>
void describe_section(KeyDocs& d, const Section<T>& s, const T& defaults) {
  for (const Field<T>& f : s.fields) {
    if (f.describe != nullptr) f.describe(d, f, defaults);
  }
}

/// A sub-table row, its functions still to be set.
template <class T>
constexpr Field<T> table_row(std::string_view key, std::string_view note) {
  Field<T> row = make_field<T>(key, {});
  row.kind = RowKind::kTable;
  row.note = note;
  return row;
}

/// The docs of table key (section Child) given its defaults.
template <const auto& Child, class C>
void describe_table(KeyDocs& d, std::string_view key, const C& defaults) {
  d.enter(key);
  describe_section(d, Child, defaults);
  d.leave();
}

/// The node of key, or nullptr when it is absent and not required (a
/// required one absent is a "missing" error).
const toml::node* present(TableReader& t, std::string_view key, bool required);

/// Dotted name of table key under the writer's current table.
std::string sub_table(const TomlWriter& w, std::string_view key);

// --- members ---------------------------------------------------------------

template <class P>
struct MemberPointer;
template <class C, class V>
struct MemberPointer<V C::*> {
  using Class = C;
  using Value = V;
};

template <auto M, class T>
constexpr auto& step(T& t) {
  if constexpr (std::is_member_object_pointer_v<decltype(M)>) {
    return t.*M;
  } else {
    return M(t);
  }
}

template <auto M, auto... Rest, class T>
constexpr auto& member_of(T& t) {
  if constexpr (sizeof...(Rest) == 0) {
    return step<M>(t);
  } else {
    return member_of<Rest...>(step<M>(t));
  }
}

/// The member reached from t through a path of member pointers
/// (&Config::receiver, &receiver::ReceiverConfig::max_pdop) or accessor
/// objects (the alternative of a variant); t for none.
template <auto... Path, class T>
constexpr auto& member(T& t) {
  if constexpr (sizeof...(Path) == 0) {
    return t;
  } else {
    return member_of<Path...>(t);
  }
}

template <class Fallback, auto... Path>
struct PathOwner {
  using type = Fallback;
};
template <class Fallback, auto M, auto... Rest>
struct PathOwner<Fallback, M, Rest...> {
  using type = typename MemberPointer<decltype(M)>::Class;
};
template <auto... Path>
struct PathStart;
template <auto M, auto... Rest>
struct PathStart<M, Rest...> {
  using type = typename MemberPointer<decltype(M)>::Class;
};
/// The struct a path starts from.
template <auto... Path>
using OwnerOf = typename PathStart<Path...>::type;

template <class S>
struct SectionOf;
template <class T>
struct SectionOf<Section<T>> {
  using Target = T;
};

// --- plain keys ------------------------------------------------------------

/// Docs row of a key from its written default.
template <class T>
KeyDoc key_doc(const Field<T>& f, const T& defaults, std::string unit, std::string range) {
  std::string def = std::string(f.doc_default);
  if (f.required) {
    def = "*required*";
  } else if (def.empty() && f.write != nullptr) {
    TomlWriter w("");
    f.write(w, f, defaults);
    def = "`" + w.last_value() + "`";
  }
  if (f.doc_range_of != nullptr) {
    range = f.doc_range_of();
  } else if (!f.doc_range.empty()) {
    range = std::string(f.doc_range);
  }
  KeyDoc k{std::string(f.key), unit.empty() ? std::string(f.unit) : unit, def, range, std::string(f.meaning)};
  k.alias = f.key.size() > 0 && f.write == nullptr;
  k.open_keys = f.open_keys;
  return k;
}

/// "[0, 100]" of a range (its unit goes in the unit column).
std::string range_text(const Range& r);
/// "integer [min, max]".
std::string integer_range_text(int64_t min, int64_t max);

/// The member a plain key holds (the writer only reads it).
template <class V, class T>
V& value_of(const Field<T>& f, T& o) {
  return *static_cast<V*>(f.at(o));
}
template <class V, class T>
const V& value_of(const Field<T>& f, const T& o) {
  return *static_cast<const V*>(f.at(const_cast<T&>(o)));
}

/// The member at Path is a V (what a kind's functions read and write).
template <class V, auto... Path>
inline constexpr bool kHolds =
    std::is_same_v<std::remove_cvref_t<decltype(member<Path...>(std::declval<OwnerOf<Path...>&>()))>, V>;

/// A plain row of key holding the member at Path, read, written and
/// documented by its kind's functions.
template <auto... Path, class T = OwnerOf<Path...>>
constexpr Field<T> plain_row(std::string_view key, std::string_view meaning,
                             void (*read)(TableReader&, const Field<T>&, T&),
                             void (*write)(TomlWriter&, const Field<T>&, const T&),
                             void (*describe)(KeyDocs&, const Field<T>&, const T&)) {
  Field<T> row = make_field<T>(key, meaning);
  row.at = [](T& o) -> void* { return &member<Path...>(o); };
  row.read = read;
  row.write = write;
  row.describe = describe;
  return row;
}

template <class T>
void read_number(TableReader& t, const Field<T>& f, T& o) {
  double& v = value_of<double>(f, o);
  v = t.number(f.key, f.required ? std::nullopt : std::optional<double>(v), f.range);
}
template <class T>
void write_number(TomlWriter& w, const Field<T>& f, const T& o) {
  w.key(f.key, number_text(value_of<double>(f, o)), f.note);
}
template <class T>
void describe_number(KeyDocs& d, const Field<T>& f, const T& o) {
  d.add(key_doc(f, o, std::string(f.range.unit), range_text(f.range)));
}

/// A number in a core Range.
template <auto... Path>
constexpr Field<OwnerOf<Path...>> number(std::string_view key, const Range& range, std::string_view meaning) {
  using T = OwnerOf<Path...>;
  static_assert(kHolds<double, Path...>);
  Field<T> row = plain_row<Path...>(key, meaning, read_number<T>, write_number<T>, describe_number<T>);
  row.range = range;
  return row;
}

template <class T>
void read_angle(TableReader& t, const Field<T>& f, T& o) {
  double& rad = value_of<double>(f, o);
  rad = t.number(f.key, f.required ? std::nullopt : std::optional<double>(rad * kRadToDeg), f.range) * kDegToRad;
}
template <class T>
void write_angle(TomlWriter& w, const Field<T>& f, const T& o) {
  w.key(f.key, degrees_text(value_of<double>(f, o)), f.note);
}

/// Degrees in the file, radians in the struct; range in degrees.
template <auto... Path>
constexpr Field<OwnerOf<Path...>> angle(std::string_view key, const Range& range_deg, std::string_view meaning) {
  using T = OwnerOf<Path...>;
  Field<T> row = number<Path...>(key, range_deg, meaning);
  row.read = read_angle<T>;
  row.write = write_angle<T>;
  return row;
}

template <class T, class V>
void read_integer(TableReader& t, const Field<T>& f, T& o) {
  V& v = value_of<V>(f, o);
  v = static_cast<V>(
      t.integer(f.key, f.required ? std::nullopt : std::optional<int64_t>(static_cast<int64_t>(v)), f.min, f.max));
}
template <class T, class V>
void write_integer(TomlWriter& w, const Field<T>& f, const T& o) {
  w.key(f.key, std::to_string(value_of<V>(f, o)), f.note);
}
template <class T>
void describe_integer(KeyDocs& d, const Field<T>& f, const T& o) {
  d.add(key_doc(f, o, "", integer_range_text(f.min, f.max)));
}

/// An integer in [min, max] (floats rejected).
template <auto... Path>
constexpr Field<OwnerOf<Path...>> integer(std::string_view key, int64_t min, int64_t max, std::string_view meaning) {
  using T = OwnerOf<Path...>;
  using V = std::remove_cvref_t<decltype(member<Path...>(std::declval<T&>()))>;
  Field<T> row = plain_row<Path...>(key, meaning, read_integer<T, V>, write_integer<T, V>, describe_integer<T>);
  row.min = min;
  row.max = max;
  return row;
}

/// An integer in a core Range of whole numbers.
template <auto... Path>
constexpr Field<OwnerOf<Path...>> integer(std::string_view key, const Range& range, std::string_view meaning) {
  Field<OwnerOf<Path...>> row = integer<Path...>(key, static_cast<int64_t>(range.min), static_cast<int64_t>(range.max),
                                               meaning);
  row.unit = range.unit;
  return row;
}

template <class T>
void read_boolean(TableReader& t, const Field<T>& f, T& o) {
  bool& v = value_of<bool>(f, o);
  v = t.boolean(f.key, f.required ? std::nullopt : std::optional<bool>(v));
}
template <class T>
void write_boolean(TomlWriter& w, const Field<T>& f, const T& o) {
  w.key(f.key, bool_text(value_of<bool>(f, o)), f.note);
}
template <class T>
void describe_boolean(KeyDocs& d, const Field<T>& f, const T& o) {
  d.add(key_doc(f, o, "bool", "—"));
}

template <auto... Path>
constexpr Field<OwnerOf<Path...>> boolean(std::string_view key, std::string_view meaning) {
  using T = OwnerOf<Path...>;
  static_assert(kHolds<bool, Path...>);
  Field<T> row = plain_row<Path...>(key, meaning, read_boolean<T>, write_boolean<T>, describe_boolean<T>);
  return row;
}

// --- names -----------------------------------------------------------------

/// One value of a choice key and its name in the file.
template <class E>
struct Choice {
  std::string_view name;
  E value;
};

/// How an unknown name is reported.
enum class ChoiceStyle : uint8_t {
  kOneOf,   ///< 'x' is not one of "a", "b", "c"
  kEither,  ///< 'x' is not "a" or "b"
};

/// The known names as a message lists them: "a", "b", "c" (kEither: "a" or "b").
std::string known_names(std::span<const std::string_view> names, ChoiceStyle style);
/// The names as the docs list them: `"a"`, `"b"`.
std::string names_doc(std::span<const std::string_view> names);

/// The names of a Choice table.
template <const auto& Names>
inline constexpr auto kChoiceNames = [] {
  std::array<std::string_view, std::size(Names)> n{};
  for (std::size_t i = 0; i < n.size(); ++i) n[i] = Names[i].name;
  return n;
}();

template <class T, const auto& Names, ChoiceStyle Style>
void read_choice(TableReader& t, const Field<T>& f, T& o) {
  using E = decltype(Names[0].value);
  const toml::node* n = present(t, f.key, f.required);
  if (n == nullptr) return;
  const std::string v = t.string(f.key, std::nullopt);
  for (const auto& c : Names) {
    if (c.name == v) {
      value_of<E>(f, o) = c.value;
      return;
    }
  }
  t.fail(*n, t.full_name(f.key) + ": '" + v + "' is not " + (Style == ChoiceStyle::kOneOf ? "one of " : "") +
                 known_names(kChoiceNames<Names>, Style));
}
template <class T, const auto& Names>
void write_choice(TomlWriter& w, const Field<T>& f, const T& o) {
  using E = decltype(Names[0].value);
  std::string_view name = Names[0].name;
  for (const auto& c : Names) {
    if (c.value == value_of<E>(f, o)) {
      name = c.name;
      break;
    }
  }
  w.key(f.key, string_text(name), f.note);
}
template <class T, const auto& Names>
void describe_choice(KeyDocs& d, const Field<T>& f, const T& o) {
  d.add(key_doc(f, o, "", names_doc(kChoiceNames<Names>)));
}

template <const auto& Names, ChoiceStyle Style, auto... Path>
constexpr Field<OwnerOf<Path...>> choice_field(std::string_view key, std::string_view meaning) {
  using T = OwnerOf<Path...>;
  static_assert(kHolds<std::remove_cv_t<decltype(Names[0].value)>, Path...>);
  Field<T> row =
      plain_row<Path...>(key, meaning, read_choice<T, Names, Style>, write_choice<T, Names>, describe_choice<T, Names>);
  return row;
}

/// One name of the table Names (an array of Choice): 'x' is not one of "a", "b", "c".
template <const auto& Names, auto... Path>
constexpr Field<OwnerOf<Path...>> choice(std::string_view key, std::string_view meaning) {
  return choice_field<Names, ChoiceStyle::kOneOf, Path...>(key, meaning);
}

/// One of the two names of Names: 'x' is not "a" or "b".
template <const auto& Names, auto... Path>
constexpr Field<OwnerOf<Path...>> either(std::string_view key, std::string_view meaning) {
  static_assert(std::size(Names) == 2);
  return choice_field<Names, ChoiceStyle::kEither, Path...>(key, meaning);
}

// --- strings ---------------------------------------------------------------

/// path resolved against base_dir (when relative), absolute and normalised.
std::string resolve_path(const std::string& path, const std::string& base_dir);
/// path names a regular file (or a link to one).
bool is_file(const std::string& path);
/// text is an IPv4 or IPv6 address.
bool is_ip_address(const std::string& text);

/// What a path key must name.
enum class PathKind : uint8_t { kFile, kFolder };

/// given (the text of node n, key name) resolved against t's folder and
/// normalised; a file:line error at n when it is empty or names no existing
/// file (kFolder: folder), naming the path tried.
std::string existing_path(TableReader& t, const toml::node& n, const std::string& name, const std::string& given,
                          PathKind kind);

template <class T, PathKind K>
void read_existing_path(TableReader& t, const Field<T>& f, T& o) {
  const toml::node* node = present(t, f.key, f.required);
  if (node == nullptr) return;
  value_of<std::string>(f, o) = existing_path(t, *node, t.full_name(f.key), t.string(f.key, std::nullopt), K);
}
template <class T>
void write_path(TomlWriter& w, const Field<T>& f, const T& o) {
  const std::string& path = value_of<std::string>(f, o);
  if (path.empty() && !f.required) return;  // an optional path left unset
  w.key(f.key, string_text(w.path_text(path)), f.note);
}
template <class T>
void describe_text(KeyDocs& d, const Field<T>& f, const T& o) {
  d.add(key_doc(f, o, "", ""));
}

/// An existing file (kFolder: folder), relative to the config file's folder;
/// stored absolute, written relative to the folder to_toml is given when
/// under it. Optional unless .needed(): unset is "".
template <PathKind K, auto... Path>
constexpr Field<OwnerOf<Path...>> existing_path_row(std::string_view key, std::string_view meaning) {
  using T = OwnerOf<Path...>;
  static_assert(kHolds<std::string, Path...>);
  Field<T> row = plain_row<Path...>(key, meaning, read_existing_path<T, K>, write_path<T>, describe_text<T>);
  row.unit = "path";
  row.doc_range = K == PathKind::kFile ? "an existing file" : "an existing folder";
  row.doc_default = "unset";
  return row;
}

/// A required existing file (existing_path_row).
template <auto... Path>
constexpr Field<OwnerOf<Path...>> existing_file(std::string_view key, std::string_view meaning) {
  return existing_path_row<PathKind::kFile, Path...>(key, meaning).needed();
}

template <class T>
void read_address(TableReader& t, const Field<T>& f, T& o) {
  const toml::node* n = present(t, f.key, f.required);
  if (n == nullptr) return;
  const std::string a = t.string(f.key, std::nullopt);
  if (!is_ip_address(a)) t.fail(*n, t.full_name(f.key) + ": '" + a + "' is not an IPv4 or IPv6 address");
  value_of<std::string>(f, o) = a;
}
template <class T>
void write_string(TomlWriter& w, const Field<T>& f, const T& o) {
  w.key(f.key, string_text(value_of<std::string>(f, o)), f.note);
}

/// An IPv4 or IPv6 address (no host names).
template <auto... Path>
constexpr Field<OwnerOf<Path...>> address(std::string_view key, std::string_view meaning) {
  using T = OwnerOf<Path...>;
  static_assert(kHolds<std::string, Path...>);
  Field<T> row = plain_row<Path...>(key, meaning, read_address<T>, write_string<T>, describe_text<T>);
  row.doc_range = "IPv4 or IPv6 address";
  return row;
}

// --- custom keys -----------------------------------------------------------

/// A key with its own read, write (nullptr: read only) and docs texts.
template <class T>
constexpr Field<T> custom(std::string_view key, std::string_view unit, std::string_view range_text,
                          std::string_view meaning, void (*read)(TableReader&, const Field<T>&, T&),
                          void (*write)(TomlWriter&, const Field<T>&, const T&)) {
  Field<T> row = make_field<T>(key, meaning);
  row.unit = unit;
  row.doc_range = range_text;
  row.read = read;
  row.write = write;
  row.describe = describe_text<T>;
  return row;
}

/// custom() whose docs range text is computed (the names of a core table).
template <class T>
constexpr Field<T> custom(std::string_view key, std::string_view unit, std::string (*range_text)(),
                          std::string_view meaning, void (*read)(TableReader&, const Field<T>&, T&),
                          void (*write)(TomlWriter&, const Field<T>&, const T&)) {
  Field<T> row = custom<T>(key, unit, std::string_view{}, meaning, read, write);
  row.doc_range_of = range_text;
  return row;
}

/// A sub-table row with its own read, write and docs (several tables, an
/// array of tables in a fixed array ...).
template <class T>
constexpr Field<T> custom_table(std::string_view key, void (*read)(TableReader&, const Field<T>&, T&),
                                void (*write)(TomlWriter&, const Field<T>&, const T&),
                                void (*describe)(KeyDocs&, const Field<T>&, const T&)) {
  Field<T> row = table_row<T>(key, {});
  row.read = read;
  row.write = write;
  row.describe = describe;
  return row;
}

// --- checks ----------------------------------------------------------------

/// What a broken rule's message starts with.
enum class RuleScope : uint8_t {
  kTable,  ///< "receiver.solver: <reason>"
  kKey,    ///< "truth.max_extrapolation_s: <reason>" (the violation's field)
};

/// Throws v at the line of its field (else its other field, else the
/// table's header), prefixed as scope says.
[[noreturn]] void fail_rule(TableReader& t, const Violation& v, RuleScope scope);

/// A cross-field rule (a check_* function next to the struct it constrains)
/// on the member at Path (none: the section's target T), run where it
/// stands in the rows: after the keys it relates are read.
template <class T, auto Check, RuleScope Scope = RuleScope::kTable, auto... Path>
constexpr Field<T> rule() {
  Field<T> row{};
  row.kind = RowKind::kCheck;
  row.read = [](TableReader& t, const Field<T>&, T& o) {
    if (const std::optional<Violation> v = Check(member<Path...>(o))) fail_rule(t, *v, Scope);
  };
  return row;
}

/// A check of the whole target T with its own read (no key, no docs).
template <class T>
constexpr Field<T> check(void (*read)(TableReader&, const Field<T>&, T&)) {
  Field<T> row{};
  row.kind = RowKind::kCheck;
  row.read = read;
  return row;
}

// --- sub-tables ------------------------------------------------------------

/// Sub-table key read into the member at Path (none: the same target) by
/// the section Child; required: a missing table is an error.
template <const auto& Child, auto... Path>
constexpr auto table(std::string_view key, std::string_view note = {}) {
  using C = typename SectionOf<std::remove_cvref_t<decltype(Child)>>::Target;
  using T = typename PathOwner<C, Path...>::type;
  Field<T> row = table_row<T>(key, note);
  row.read = [](TableReader& t, const Field<T>& f, T& o) {
    if (std::optional<TableReader> s = t.table(f.key, f.required)) read_section(*s, Child, member<Path...>(o));
  };
  row.write = [](TomlWriter& w, const Field<T>& f, const T& o) {
    const std::string path = sub_table(w, f.key);
    write_table(w, Child, path, f.note, member<Path...>(o));
  };
  row.describe = [](KeyDocs& d, const Field<T>& f, const T& o) { describe_table<Child>(d, f.key, member<Path...>(o)); };
  return row;
}

/// An array of tables ([[key]]) into the std::vector member at Path; check
/// (may be nullptr) sees each element after it is read, with the ones before.
template <const auto& Child, auto Check, auto... Path>
constexpr auto table_array(std::string_view key, std::string_view note = {}) {
  using C = typename SectionOf<std::remove_cvref_t<decltype(Child)>>::Target;
  using T = OwnerOf<Path...>;
  Field<T> row = table_row<T>(key, note);
  row.read = [](TableReader& t, const Field<T>& f, T& o) {
    std::vector<C>& out = member<Path...>(o);
    out.clear();
    for (TableReader& e : t.table_array(f.key)) {
      C value;
      read_section(e, Child, value);
      // On the type, not the address: GCC's -fsanitize=undefined makes
      // `function != nullptr` no constant expression (no null-check deletion).
      if constexpr (!std::is_null_pointer_v<decltype(Check)>) Check(e, out, value);
      out.push_back(std::move(value));
    }
  };
  row.write = [](TomlWriter& w, const Field<T>& f, const T& o) {
    const std::string path = sub_table(w, f.key);
    for (const C& e : member<Path...>(o)) write_table(w, Child, path, f.note, e, true);
  };
  row.describe = [](KeyDocs& d, const Field<T>& f, const T&) { describe_table<Child>(d, f.key, C{}); };
  return row;
}

/// An optional sub-table: the std::optional member at Path is set when the
/// table is present, and written when it holds a value.
template <const auto& Child, auto... Path>
constexpr auto optional_table(std::string_view key, std::string_view note = {}) {
  using C = typename SectionOf<std::remove_cvref_t<decltype(Child)>>::Target;
  using T = OwnerOf<Path...>;
  Field<T> row = table_row<T>(key, note);
  row.read = [](TableReader& t, const Field<T>& f, T& o) {
    if (std::optional<TableReader> s = t.table(f.key, false)) {
      C value;
      read_section(*s, Child, value);
      member<Path...>(o) = std::move(value);
    }
  };
  row.write = [](TomlWriter& w, const Field<T>& f, const T& o) {
    if (const std::optional<C>& v = member<Path...>(o)) {
      const std::string path = sub_table(w, f.key);
      write_table(w, Child, path, f.note, *v);
    }
  };
  row.describe = [](KeyDocs& d, const Field<T>& f, const T&) { describe_table<Child>(d, f.key, C{}); };
  return row;
}

}  // namespace gnssemu::config::detail

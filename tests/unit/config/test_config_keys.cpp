// The key tables (config/config_keys.hpp) against what the reader reads,
// what to_toml writes and what docs/configuration.md documents: a key that
// is readable but not writable, writable but not readable, readable but
// undocumented, or documented but never read fails here, and so does a
// stale key table in the docs (GNSSEMU_REBUILD_DOCS=1 rewrites them).
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "config/config_keys.hpp"
#include "config/config_text.hpp"
#include "every_key.hpp"
#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

using detail::KeyDoc;
using detail::TableDoc;

const std::string kDocs = kSource + "/docs/configuration.md";
constexpr std::string_view kBegin = "<!-- keys: ";
constexpr std::string_view kEnd = "<!-- /keys -->";

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// "output[3].path" -> "output.path".
std::string without_indices(const std::string& name) {
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name[i] == '[') {
      i = name.find(']', i);
      continue;
    }
    out += name[i];
  }
  return out;
}

struct Documented {
  std::set<std::string> keys;
  std::set<std::string> tables;
  std::set<std::string> aliases;    ///< read as other keys
  std::set<std::string> open_keys;  ///< tables whose keys are names from the data
  std::map<std::string, std::set<std::string>> defaults;

  bool under_open(const std::string& name) const {
    for (const std::string& o : open_keys) {
      if (name.rfind(o + ".", 0) == 0) return true;
    }
    return false;
  }
};

std::string name_of(const TableDoc& t, const KeyDoc& k) { return t.path.empty() ? k.key : t.path + "." + k.key; }

Documented documented() {
  Documented d;
  const detail::KeyDocs docs = detail::describe_keys();
  for (const TableDoc& t : docs.tables()) {
    d.tables.insert(t.path);
    for (const KeyDoc& k : t.keys) {
      const std::string name = name_of(t, k);
      d.keys.insert(name);
      if (k.alias) d.aliases.insert(name);
      if (k.open_keys) d.open_keys.insert(name);
      std::string def = k.default_text;
      if (def.size() > 2 && def.front() == '`' && def.back() == '`') def = def.substr(1, def.size() - 2);
      d.defaults[name].insert(def);
    }
  }
  return d;
}

// The keys parsing text asks for (tables and the names under open keys left out).
std::set<std::string> keys_read(const std::string& text, const Documented& d) {
  detail::KeyLog log;
  detail::parse_config_text(text, "t.toml", kData, &log);
  std::set<std::string> out;
  for (const std::string& n : log) {
    const std::string name = without_indices(n);
    if (d.tables.count(name) == 0 && !d.under_open(name)) out.insert(name);
  }
  return out;
}

// key -> the values to_toml writes for it (a key under an open key counts as that key).
std::map<std::string, std::set<std::string>> keys_written(const std::string& text, const Documented& d) {
  detail::KeyLog log;
  detail::config_text(parse(text), kData, &log);
  std::map<std::string, std::set<std::string>> out;
  for (const std::string& entry : log) {
    const std::size_t eq = entry.find(" = ");
    std::string name = without_indices(entry.substr(0, eq));
    for (const std::string& o : d.open_keys) {
      if (name.rfind(o + ".", 0) == 0) name = o;
    }
    out[name].insert(entry.substr(eq + 3));
  }
  return out;
}

std::string listed(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += " " + n;
  return out;
}

// --- every key table ------------------------------------------------------

TEST(ConfigKeys, EveryKeyIsReadWrittenAndDocumented) {
  const Documented d = documented();
  std::set<std::string> read = keys_read(kEveryKey, d);
  const std::set<std::string> read_other = keys_read(kOtherKeys, d);
  read.insert(read_other.begin(), read_other.end());
  std::map<std::string, std::set<std::string>> written = keys_written(kEveryKey, d);
  for (const auto& [k, v] : keys_written(kOtherKeys, d)) written[k].insert(v.begin(), v.end());

  std::set<std::string> undocumented, unread, unwritable, unreadable;
  for (const std::string& k : read) {
    if (d.keys.count(k) == 0) undocumented.insert(k);
    if (written.count(k) == 0 && d.aliases.count(k) == 0) unwritable.insert(k);
  }
  for (const std::string& k : d.keys) {
    if (read.count(k) == 0) unread.insert(k);
  }
  for (const auto& [k, values] : written) {
    if (read.count(k) == 0) unreadable.insert(k);
  }
  EXPECT_TRUE(undocumented.empty()) << "readable but undocumented:" << listed(undocumented);
  EXPECT_TRUE(unread.empty()) << "documented but never read (unknown to the reader):" << listed(unread);
  EXPECT_TRUE(unwritable.empty()) << "readable but not written by to_toml:" << listed(unwritable);
  EXPECT_TRUE(unreadable.empty()) << "written by to_toml but not readable:" << listed(unreadable);
  EXPECT_GT(read.size(), 150u);
}

TEST(ConfigKeys, EveryKeyConfigSetsEveryKeyOffItsDefault) {
  const Documented d = documented();
  std::map<std::string, std::set<std::string>> written = keys_written(kEveryKey, d);
  for (const auto& [k, v] : keys_written(kOtherKeys, d)) written[k].insert(v.begin(), v.end());
  for (const auto& [key, values] : written) {
    bool off_default = false;
    for (const std::string& v : values) off_default = off_default || d.defaults.at(key).count(v) == 0;
    EXPECT_TRUE(off_default) << key << " is only ever its default " << *values.begin();
  }
}

// --- docs/configuration.md -------------------------------------------------

// One markdown table for the tables of a group (the five shells share one:
// where their defaults differ, they are listed in table order).
std::string markdown(const std::vector<const TableDoc*>& tables) {
  std::string out = "| key | unit | default | range | meaning |\n|---|---|---|---|---|\n";
  const TableDoc& first = *tables.front();
  for (std::size_t i = 0; i < first.keys.size(); ++i) {
    const KeyDoc& k = first.keys[i];
    std::string def = k.default_text;
    for (std::size_t t = 1; t < tables.size(); ++t) {
      if (tables[t]->keys.at(i).default_text != k.default_text) {
        def.clear();
        for (const TableDoc* each : tables) def += (def.empty() ? "" : " / ") + each->keys.at(i).default_text;
        break;
      }
    }
    out += "| `" + k.key + "` | " + (k.unit.empty() ? "—" : k.unit) + " | " + def + " | " +
           (k.range.empty() ? "—" : k.range) + " | " + k.meaning + " |\n";
  }
  return out;
}

// group -> its tables, in file order; groups without keys left out.
std::map<std::string, std::vector<const TableDoc*>> groups(const std::vector<TableDoc>& tables) {
  std::map<std::string, std::vector<const TableDoc*>> out;
  for (const TableDoc& t : tables) {
    if (!t.keys.empty()) out[t.group].push_back(&t);
  }
  return out;
}

// The docs with every key table block regenerated; problems lists blocks
// naming no table, tables without a block and key rows outside the blocks.
std::string regenerated(const std::string& doc, std::vector<std::string>& problems) {
  const std::vector<TableDoc> tables = detail::describe_keys().tables();
  const std::map<std::string, std::vector<const TableDoc*>> all = groups(tables);
  std::set<std::string> done;
  std::string out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t b = doc.find(kBegin, pos);
    const std::string outside = doc.substr(pos, b == std::string::npos ? std::string::npos : b - pos);
    if (outside.find("\n| `") != std::string::npos) problems.push_back("a key table outside the generated blocks");
    out += outside;
    if (b == std::string::npos) break;
    const std::size_t name_end = doc.find(" -->", b);
    const std::string group = doc.substr(b + kBegin.size(), name_end - b - kBegin.size());
    const std::size_t e = doc.find(kEnd, name_end);
    if (e == std::string::npos) {
      problems.push_back("block '" + group + "' has no end");
      return doc;
    }
    const auto it = all.find(group);
    if (it == all.end()) problems.push_back("block '" + group + "' names no key table");
    done.insert(group);
    out += std::string(kBegin) + group + " -->\n" + (it == all.end() ? "" : markdown(it->second)) + std::string(kEnd);
    pos = e + kEnd.size();
  }
  for (const auto& [group, t] : all) {
    if (done.count(group) == 0) problems.push_back("no block for the keys of [" + group + "]");
  }
  return out;
}

TEST(ConfigKeys, DocsKeyTablesAreTheKeyTables) {
  const std::string doc = read_file(kDocs);
  ASSERT_FALSE(doc.empty()) << kDocs;
  std::vector<std::string> problems;
  const std::string fresh = regenerated(doc, problems);
  for (const std::string& p : problems) ADD_FAILURE() << kDocs << ": " << p;
  if (problems.empty() && fresh != doc && std::getenv("GNSSEMU_REBUILD_DOCS") != nullptr) {
    std::ofstream(kDocs, std::ios::binary | std::ios::trunc) << fresh;
    return;
  }
  EXPECT_TRUE(fresh == doc) << kDocs << " has stale key tables; after reviewing the change of the tables, run\n"
                            << "  GNSSEMU_REBUILD_DOCS=1 build/tests/test_config --gtest_filter='ConfigKeys.Docs*'";
}

}  // namespace
}  // namespace gnssemu::config::test

// SPDX-License-Identifier: Apache-2.0
// config/config_keys: the tables of the configuration's own settings
// ([origin], [nav], [time], [truth], [demo], [log]), and every key table
// against what the reader reads, what to_toml writes and what
// docs/configuration.md documents: a key that is readable but not writable,
// writable but not readable, readable but undocumented, or documented but
// never read fails here, and so does a stale key table in the docs
// (GNSSEMU_REBUILD_DOCS=1 rewrites them).
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "config/keys/config_keys.hpp"
#include "config/config_text.hpp"
#include "every_key.hpp"
#include "test_helpers.hpp"

namespace gnssemu::config::test::config_keys_test {
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
  /// "vehicle.receiver." -> "receiver.": a table that takes another's keys
  /// (a mirror row, or a table documented in another table's group).
  std::map<std::string, std::string> mirrors;

  /// name as the table it mirrors names it ("vehicle.receiver.seed" -> "receiver.seed").
  std::string canonical(const std::string& name) const {
    std::string best_from;
    for (const auto& [from, to] : mirrors) {
      if (name.rfind(from, 0) == 0 && from.size() > best_from.size()) best_from = from;
    }
    if (best_from.empty()) return name;
    const std::string mapped = mirrors.at(best_from) + name.substr(best_from.size());
    return keys.count(mapped) != 0 || tables.count(mapped) != 0 || under_open(mapped) ? mapped : name;
  }

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
  std::set<std::string> paths;
  for (const TableDoc& t : docs.tables()) paths.insert(t.path);
  for (const TableDoc& t : docs.tables()) {
    d.tables.insert(t.path);
    if (t.group != t.path && paths.count(t.group) != 0) {
      d.mirrors[t.path + "."] = t.group + ".";  // the keys of the group's table
      continue;
    }
    for (const KeyDoc& k : t.keys) {
      if (!k.mirror.empty()) {
        d.mirrors[t.path + "."] = k.mirror + ".";
        continue;
      }
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
    const std::string name = d.canonical(without_indices(n));
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
    std::string name = d.canonical(without_indices(entry.substr(0, eq)));
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

// --- [origin], [nav] ------------------------------------------------------

TEST(ConfigValidation, LatitudeOutsidePlusMinus90) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 90.5\nlon_deg = 2\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:2: origin.lat_deg: 90.5 is out of range [-90, 90] deg");
  EXPECT_EQ(error_of("[origin]\nlat_deg = -91\nlon_deg = 2\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:2: origin.lat_deg: -91 is out of range [-90, 90] deg");
  const Config pole = parse("[origin]\nlat_deg = -90\nlon_deg = 0\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n");
  EXPECT_EQ(pole.origin.lat_rad, -kPi / 2.0);
}

TEST(ConfigValidation, LongitudeOutsidePlusMinus180) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 180.25\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:3: origin.lon_deg: 180.25 is out of range [-180, 180] deg");
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = -181\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:3: origin.lon_deg: -181 is out of range [-180, 180] deg");
  // -180 is the antimeridian; Lla keeps longitude in (-pi, pi].
  const Config c = parse("[origin]\nlat_deg = 1\nlon_deg = -180\nheight_m = 0\n[nav]\nfile = \"nav/brdc0010.22n\"\n");
  EXPECT_EQ(c.origin.lon_rad, kPi);
}

TEST(ConfigValidation, HeightOutOfRange) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 6378137\n[nav]\nfile = \"nav/brdc0010.22n\"\n"),
            "t.toml:4: origin.height_m: 6378137 is out of range [-1000, 50000] m");
}

TEST(ConfigValidation, NavFileNotFoundSaysWhereItLooked) {
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\n[nav]\nfile = \"nav/missing.22n\"\n"),
            "t.toml:6: nav.file: 'nav/missing.22n' not found (tried " + kData + "/nav/missing.22n)");
  // A folder is not a nav file.
  EXPECT_EQ(error_of("[origin]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\n[nav]\nfile = \"nav\"\n"),
            "t.toml:6: nav.file: 'nav' not found (tried " + kData + "/nav)");
}

// --- [time] ----------------------------------------------------------------

TEST(ConfigValidation, BadDateStrings) {
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-13-01T00:00:00\"\n"),
            "t.toml:8: time.start: bad date-time: month 13 is not 1..12");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-02-29T00:00:00\"\n"),
            "t.toml:8: time.start: bad date-time: day 29 does not exist in 2022-02");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-01-01T24:00:00\"\n"),
            "t.toml:8: time.start: bad date-time: hour 24 is not 0..23");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"1979-12-31T00:00:00\"\n"),
            "t.toml:8: time.start: bad date-time: before the GPS epoch 1980-01-06");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"yesterday\"\n"),
            "t.toml:8: time.start: 'yesterday' is not a GPS date-time YYYY-MM-DDTHH:MM:SS[.fff] (no time zone)");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-01-01T12:00:00Z\"\n"),
            "t.toml:8: time.start: '2022-01-01T12:00:00Z' is not a GPS date-time YYYY-MM-DDTHH:MM:SS[.fff] "
            "(no time zone)");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-01-01T12:00:00.\"\n"),
            "t.toml:8: time.start: '2022-01-01T12:00:00.' is not a GPS date-time YYYY-MM-DDTHH:MM:SS[.fff] "
            "(no time zone)");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = 2022-01-01T12:00:00+01:00\n"),
            "t.toml:8: time.start: GPS time has no time zone; drop the offset");
  EXPECT_EQ(error_of(kBase + "[time]\nstart = 2022-01-01\n"),
            "t.toml:8: time.start: expected a date-time string \"YYYY-MM-DDTHH:MM:SS\", got a date");
}

TEST(ConfigValidation, GoodDates) {
  const time::GpsTime noon = time::GpsTime::from_calendar({2022, 1, 1, 12, 0, 0.0});
  EXPECT_EQ(parse(kBase + "[time]\nstart = \"2022-01-01T12:00:00\"\n").time.start, noon);
  EXPECT_EQ(parse(kBase + "[time]\nstart = \"2022-01-01 12:00:00\"\n").time.start, noon);
  EXPECT_EQ(parse(kBase + "[time]\nstart = 2022-01-01T12:00:00\n").time.start, noon);  // TOML local date-time
  const auto frac = parse(kBase + "[time]\nstart = \"2022-01-01T12:00:00.25\"\n").time.start;
  ASSERT_TRUE(frac.has_value());
  EXPECT_EQ(frac->week(), 2190);
  EXPECT_EQ(frac->tow_s(), 6 * 86400.0 + 12 * 3600.0 + 0.25);
  EXPECT_EQ(parse(kBase + "[time]\nstart = \"2024-02-29T00:00:00\"\n").time.start,
            time::GpsTime::from_calendar({2024, 2, 29, 0, 0, 0.0}));
}

TEST(ConfigValidation, BadTimeMode) {
  EXPECT_EQ(error_of(kBase + "[time]\nmode = \"fast\"\n"),
            "t.toml:8: time.mode: 'fast' is not \"realtime\" or \"lockstep\"");
}

TEST(ConfigValidation, NavFilesFolderAlmanacAndMode) {
  const Config c = parse(kBase + "files = [\"nav/ab422100.18n\"]\nfolder = \"nav\"\nmode = \"relabel\"\n");
  ASSERT_EQ(c.nav.files.size(), 1u);
  EXPECT_EQ(c.nav.files[0], kData + "/nav/ab422100.18n");
  EXPECT_EQ(c.nav.folder, kData + "/nav");
  EXPECT_EQ(c.nav.mode, orbit::NavMode::kRelabel);
  EXPECT_EQ(parse(kBase).nav.mode, orbit::NavMode::kAuto);
  EXPECT_EQ(error_of(kBase + "files = [\"nav/none.22n\"]\n"),
            "t.toml:7: nav.files: 'nav/none.22n' not found (tried " + kData + "/nav/none.22n)");
  EXPECT_EQ(error_of(kBase + "files = \"nav/ab422100.18n\"\n"),
            "t.toml:7: nav.files: expected an array of file names, got a string");
  EXPECT_EQ(error_of(kBase + "files = [1]\n"), "t.toml:7: nav.files: expected a file name string, got an integer");
  EXPECT_EQ(error_of(kBase + "folder = \"nav/brdc0010.22n\"\n"),
            "t.toml:7: nav.folder: 'nav/brdc0010.22n' is not a folder (tried " + kData + "/nav/brdc0010.22n)");
  EXPECT_EQ(error_of(kBase + "mode = \"today\"\n"),
            "t.toml:7: nav.mode: 'today' is not one of \"auto\", \"as_is\", \"relabel\", \"almanac\"");
  EXPECT_EQ(error_of(kBase + "mode = \"almanac\"\n"), "t.toml:7: nav.mode: \"almanac\" needs nav.almanac");
  EXPECT_EQ(error_of(kBase + "almanac = \"almanac/yuma_week862_toa319488.alm\"\n"),
            "t.toml:7: nav.almanac: needs mode = \"almanac\"");
}

TEST(ConfigValidation, StartTurnsTheWallClockDateOff) {
  EXPECT_TRUE(parse(kBase).time.use_wall_clock_date);
  const Config c = parse(kBase + "[time]\nstart = \"2022-01-01T12:00:00\"\n");
  EXPECT_FALSE(c.time.use_wall_clock_date);
  EXPECT_DOUBLE_EQ(parse(kBase).time.output_delay_s, 0.1);
  EXPECT_EQ(error_of(kBase + "[time]\noutput_delay_s = 0.6\n"),
            "t.toml:8: time.output_delay_s: 0.6 is out of range [0, 0.5] s");
}

TEST(ConfigValidation, StartAndWallClockExclusive) {
  EXPECT_EQ(error_of(kBase + "[time]\nstart = \"2022-01-01T12:00:00\"\nuse_wall_clock_date = true\n"),
            "t.toml:9: time.use_wall_clock_date: cannot be true together with time.start");
}

// --- [truth], [demo], [log] ------------------------------------------------

TEST(ConfigValidation, PortOutside16Bits) {
  EXPECT_EQ(error_of(kBase + "[truth]\nport = 65536\n"), "t.toml:8: truth.port: 65536 is out of range [0, 65535]");
  EXPECT_EQ(error_of(kBase + "[truth]\nport = -1\n"), "t.toml:8: truth.port: -1 is out of range [0, 65535]");
  EXPECT_EQ(parse(kBase + "[truth]\nport = 0\n").truth.port, 0);
  EXPECT_EQ(parse(kBase + "[truth]\nport = 65535\n").truth.port, 65535);
}

TEST(ConfigValidation, TruthTimes) {
  EXPECT_EQ(error_of(kBase + "[truth]\ntimeout_s = 0\n"), "t.toml:8: truth.timeout_s: 0 is out of range (0, 60] s");
  EXPECT_EQ(error_of(kBase + "[truth]\ntimeout_s = 1\nmax_extrapolation_s = 1.5\n"),
            "t.toml:9: truth.max_extrapolation_s: 1.5 s exceeds truth.timeout_s (1 s)");
}

TEST(ConfigValidation, TimeoutBelowTheDefaultExtrapolation) {
  // Only timeout_s given: the rule points at it (the other key is absent).
  EXPECT_EQ(error_of(kBase + "[truth]\ntimeout_s = 0.25\n"),
            "t.toml:8: truth.max_extrapolation_s: 0.5 s exceeds truth.timeout_s (0.25 s)");
  EXPECT_EQ(error_of(kBase + "[truth]\n\nmax_extrapolation_s = 0.4\ntimeout_s = 0.25\n"),
            "t.toml:9: truth.max_extrapolation_s: 0.4 s exceeds truth.timeout_s (0.25 s)");
  EXPECT_EQ(parse(kBase + "[truth]\ntimeout_s = 0.5\n").truth.timeout_s, 0.5);
}

TEST(ConfigValidation, BindNotAnAddress) {
  EXPECT_EQ(error_of(kBase + "[truth]\nbind = \"localhost\"\n"),
            "t.toml:8: truth.bind: 'localhost' is not an IPv4 or IPv6 address");
  EXPECT_EQ(parse(kBase + "[truth]\nbind = \"::1\"\n").truth.bind_address, "::1");
  EXPECT_EQ(parse(kBase + "[truth]\nbind = \"0.0.0.0\"\n").truth.bind_address, "0.0.0.0");
}

TEST(ConfigValidation, DemoRanges) {
  EXPECT_EQ(error_of(kBase + "[demo]\nradius_m = 0\n"), "t.toml:8: demo.radius_m: 0 is out of range (0, 100000] m");
  EXPECT_EQ(error_of(kBase + "[demo]\nspeed_m_s = -1\n"), "t.toml:8: demo.speed_m_s: -1 is out of range [0, 500] m/s");
}

TEST(ConfigValidation, UnknownLogLevel) {
  EXPECT_EQ(error_of(kBase + "[log]\nlevel = \"verbose\"\n"),
            "t.toml:8: log.level: 'verbose' is not one of trace, debug, info, warn, error, critical, off");
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


// --- [truth] allow, vehicle --------------------------------------------------

TEST(ConfigValidation, TruthAllowListAndVehicle) {
  const Config c = parse(kBase + "[truth]\nallow = [\"127.0.0.1\", \"10.0.0.0/8\", \"::1\"]\nvehicle = \"ego\"\n");
  ASSERT_EQ(c.truth.allow.size(), 3u);
  EXPECT_EQ(c.truth.allow[1].text(), "10.0.0.0/8");
  EXPECT_EQ(c.truth.vehicle, "ego");
  EXPECT_TRUE(parse(kBase).truth.allow.empty());
  EXPECT_EQ(error_of(kBase + "[truth]\nallow = [\"127.0.0.1\",\n  \"gateway\"]\n"),
            "t.toml:9: truth.allow: 'gateway' is not an IPv4 or IPv6 address (host names are not accepted)");
  EXPECT_EQ(error_of(kBase + "[truth]\nallow = [\"10.0.0.0/40\"]\n"),
            "t.toml:8: truth.allow: prefix length '40' is not an integer in [0, 32]");
  EXPECT_EQ(error_of(kBase + "[truth]\nallow = \"10.0.0.0/8\"\n"),
            "t.toml:8: truth.allow: expected an array of addresses, got a string");
  EXPECT_EQ(error_of(kBase + "[truth]\nvehicle = \"\"\n"),
            "t.toml:8: truth.vehicle: must not be empty (leave it out: the first vehicle)");
}

}  // namespace
}  // namespace gnssemu::config::test::config_keys_test

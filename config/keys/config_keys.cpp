// SPDX-License-Identifier: Apache-2.0
// The whole file: the root table, and [origin], [nav], [time], [truth],
// [demo] and [log], whose settings are the configuration's own.
#include "config/keys/config_keys.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <string>
#include <variant>

namespace gnssemu::config {

std::optional<Violation> check_start(const TimeConfig& t) {
  if (!(t.use_wall_clock_date && t.start)) return std::nullopt;
  return Violation{"use_wall_clock_date", "", "cannot be true together with time.start"};
}

std::optional<Violation> check_nav(const NavConfig& n) {
  const bool almanac_mode = n.mode == orbit::NavMode::kAlmanac;
  if (almanac_mode && n.almanac_file.empty()) return Violation{"mode", "", "\"almanac\" needs nav.almanac"};
  if (!almanac_mode && !n.almanac_file.empty()) return Violation{"almanac", "mode", "needs mode = \"almanac\""};
  return std::nullopt;
}

std::optional<Violation> check_extrapolation(const TruthInputConfig& t) {
  if (!(t.max_extrapolation_s > t.timeout_s)) return std::nullopt;
  return Violation{"max_extrapolation_s", "timeout_s",
                   format_number(t.max_extrapolation_s) + " s exceeds truth.timeout_s (" + format_number(t.timeout_s) +
                       " s)"};
}

std::optional<Violation> check_status(const StatusConfig& s) {
  if (!(s.free_port && s.port == 0)) return std::nullopt;
  return Violation{"free_port", "port", "true needs status.port above 0 (port = 0 turns the page off)"};
}

namespace detail {

namespace {

// Heights of the origin and of the demo circle, m.
constexpr Range kHeight{-1000.0, 50000.0, "m"};

// --- [origin] --------------------------------------------------------------

// Lla keeps the longitude in (-pi, pi]: -180 is stored as +180.
constexpr Field<Lla> longitude_field() {
  Field<Lla> row = angle<&Lla::lon_rad>("lon_deg", Range{-180.0, 180.0, "deg"},
                                      "longitude, east positive; -180 is stored as +180")
                     .needed();
  row.read = [](TableReader& t, const Field<Lla>& f, Lla& o) {
    double lon_deg = t.number(f.key, std::nullopt, f.range);
    if (lon_deg == -180.0) lon_deg = 180.0;
    o.lon_rad = lon_deg * kDegToRad;
  };
  return row;
}

constexpr Field<Lla> kOriginFields[] = {
    angle<&Lla::lat_rad>("lat_deg", Range{-90.0, 90.0, "deg"}, "geodetic latitude, WGS-84").needed(),
    longitude_field(),
    number<&Lla::height_m>("height_m", kHeight,
                           "height above the WGS-84 ellipsoid (not above sea level: add the geoid undulation, ~45 m "
                           "in Paris)")
        .needed()
        .with_note("above the ellipsoid"),
};
constexpr Section<Lla> kOrigin{kOriginFields};

// --- [nav] -----------------------------------------------------------------

// Each path relative to the config file's folder, stored absolute.
void read_nav_files(TableReader& t, const Field<Config>& f, Config& c) {
  if (t.find(f.key) != nullptr) c.nav.files.clear();
  const std::string name = t.full_name(f.key);
  t.string_array(f.key, "an array of file names", "a file name string", [&](const toml::node& e, const std::string& s) {
    if (s.empty()) t.fail(e, name + ": a file name must not be empty");
    c.nav.files.push_back(existing_path(t, e, name, s, PathKind::kFile));
  });
}

void write_nav_files(TomlWriter& w, const Field<Config>& f, const Config& c) {
  if (c.nav.files.empty()) return;
  std::string list = "[";
  for (const std::string& p : c.nav.files) list += (list.size() > 1 ? ", " : "") + string_text(w.path_text(p));
  w.key(f.key, list + "]", f.note);
}

constexpr Field<Config> nav_files_field() {
  Field<Config> row = custom<Config>(
      "files", "paths", "existing files",
      "more RINEX nav files merged with `file` into one ephemeris store (a set broadcast in two files is kept once, "
      "as RTKLIB's tie rule); relative to the config file's folder",
      read_nav_files, write_nav_files);
  row.doc_default = "unset";
  return row;
}

constexpr Choice<orbit::NavMode> kNavModes[] = {{"auto", orbit::NavMode::kAuto},
                                                {"as_is", orbit::NavMode::kAsIs},
                                                {"relabel", orbit::NavMode::kRelabel},
                                                {"almanac", orbit::NavMode::kAlmanac}};

constexpr Field<Config> kNavFields[] = {
    existing_file<&Config::nav_file>(
        "file", "RINEX 2.11 / 3.x GPS navigation file, plain or gzip; relative to the config file's folder. The "
                "error says which path was tried. toe's week is taken from the record's epoch (toc, a full date): "
                "the one within half a week of toc; the file's GPS week (BROADCAST ORBIT 5) may be 10-bit (mod 1024) "
                "or the week of transmission (±1), anything else is an error naming file:line"),
    nav_files_field(),
    existing_path_row<PathKind::kFolder, &Config::nav, &NavConfig::folder>(
        "folder", "every RINEX nav file in this folder (`*.yyn`, `*_GN.rnx`, also `.gz`) is merged too; an error when "
                  "it holds none"),
    existing_path_row<PathKind::kFile, &Config::nav, &NavConfig::almanac_file>(
        "almanac", "YUMA or SEM GPS almanac for `mode = \"almanac\"` (needs it, and only it may name one)"),
    choice<kNavModes, &Config::nav, &NavConfig::mode>(
        "mode", "how the data are dated for the run: `auto` uses them as they are when they cover the start, else "
                "as `relabel`; `as_is` only their own dates (a start outside their coverage is an error naming it); "
                "`relabel` moves them by whole days to the start's date (same geometry, Ω0 corrected); `almanac` "
                "propagates `almanac` from the start's date. Past the data's end each satellite continues on its "
                "last orbit"),
    rule<Config, check_nav, RuleScope::kKey, &Config::nav>(),
};
constexpr Section<Config> kNav{kNavFields};

// --- [time] ----------------------------------------------------------------

bool is_leap(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

int days_in_month(int y, int m) {
  static constexpr std::array<int, 12> kDays{31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && is_leap(y) ? 29 : kDays[static_cast<std::size_t>(m - 1)];
}

// Checks a calendar time; returns "" or the reason it is invalid.
std::string calendar_problem(const time::CalendarTime& c) {
  if (c.month < 1 || c.month > 12) return "month " + std::to_string(c.month) + " is not 1..12";
  if (c.day < 1 || c.day > days_in_month(c.year, c.month)) {
    return "day " + std::to_string(c.day) + " does not exist in " + std::to_string(c.year) + "-" +
           (c.month < 10 ? "0" : "") + std::to_string(c.month);
  }
  if (c.hour > 23) return "hour " + std::to_string(c.hour) + " is not 0..23";
  if (c.minute > 59) return "minute " + std::to_string(c.minute) + " is not 0..59";
  if (!(c.second >= 0.0 && c.second < 60.0)) return "second " + format_number(c.second) + " is not in [0, 60)";
  if (c.year < 1980 || (c.year == 1980 && c.month == 1 && c.day < 6)) return "before the GPS epoch 1980-01-06";
  if (c.year > 2200) return "year " + std::to_string(c.year) + " is after 2200";
  return {};
}

bool parse_int(std::string_view s, int& out) {
  if (s.empty()) return false;
  for (const char ch : s) {
    if (ch < '0' || ch > '9') return false;
  }
  return std::from_chars(s.data(), s.data() + s.size(), out).ec == std::errc{};
}

// "YYYY-MM-DDTHH:MM:SS[.fff]" (T, t or space). Returns false on bad syntax.
bool parse_datetime(std::string_view s, time::CalendarTime& c) {
  if (s.size() < 19 || s[4] != '-' || s[7] != '-' || (s[10] != 'T' && s[10] != 't' && s[10] != ' ') ||
      s[13] != ':' || s[16] != ':') {
    return false;
  }
  if (!parse_int(s.substr(0, 4), c.year) || !parse_int(s.substr(5, 2), c.month) ||
      !parse_int(s.substr(8, 2), c.day) || !parse_int(s.substr(11, 2), c.hour) ||
      !parse_int(s.substr(14, 2), c.minute)) {
    return false;
  }
  const std::string_view sec = s.substr(17);
  if (sec.size() < 2 || sec[0] < '0' || sec[0] > '9' || sec[1] < '0' || sec[1] > '9') return false;
  if (sec.size() > 2 && (sec[2] != '.' || sec.size() == 3)) return false;
  for (std::size_t i = 3; i < sec.size(); ++i) {
    if (sec[i] < '0' || sec[i] > '9') return false;
  }
  return std::from_chars(sec.data(), sec.data() + sec.size(), c.second).ec == std::errc{};
}

// A GPS date-time: a string, or a TOML local date-time.
void read_start(TableReader& t, const Field<TimeConfig>& f, TimeConfig& out) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) return;
  const std::string name = t.full_name(f.key);
  time::CalendarTime c;
  if (const auto* s = n->as_string()) {
    if (!parse_datetime(s->get(), c)) {
      t.fail(*n, name + ": '" + s->get() + "' is not a GPS date-time YYYY-MM-DDTHH:MM:SS[.fff] (no time zone)");
    }
  } else if (const auto* dt = n->as_date_time()) {
    const toml::date_time& v = dt->get();
    if (v.offset) t.fail(*n, name + ": GPS time has no time zone; drop the offset");
    c = {v.date.year, v.date.month, v.date.day, v.time.hour, v.time.minute,
         v.time.second + static_cast<double>(v.time.nanosecond) * 1e-9};
  } else {
    t.fail(*n, name + ": expected a date-time string \"YYYY-MM-DDTHH:MM:SS\", got " + std::string(type_name(*n)));
  }
  if (const std::string why = calendar_problem(c); !why.empty()) t.fail(*n, name + ": bad date-time: " + why);
  out.start = time::GpsTime::from_calendar(c);
  out.use_wall_clock_date = false;  // its default with a start (check_start)
}

void write_start(TomlWriter& w, const Field<TimeConfig>& f, const TimeConfig& t) {
  if (t.start) w.key(f.key, string_text(datetime_text(*t.start)), f.note);
}

constexpr Field<TimeConfig> start_field() {
  Field<TimeConfig> row = custom<TimeConfig>(
      "start", "GPS time", "1980-01-06 .. 2200",
      "GPS time of the first epoch, `\"YYYY-MM-DDTHH:MM:SS[.fff]\"` (`T` or space), or a TOML local date-time "
      "`2022-01-01T12:00:00`. GPS time scale: no time zone, no `Z`, no leap seconds. Month, day (leap years), hour, "
      "minute and second are checked. Unset: today (`use_wall_clock_date`). The daemon checks it against the nav "
      "data's coverage in the configured `[nav] mode`: with `as_is` a start outside it is an error at `--check-config` and start-up "
      "naming the coverage; `auto` moves the data to it",
      read_start, write_start);
  row.note = "GPS time scale";
  row.doc_default = "unset";
  return row;
}

constexpr Choice<TimeMode> kTimeModes[] = {{"realtime", TimeMode::kRealtime}, {"lockstep", TimeMode::kLockstep}};

constexpr Field<TimeConfig> kTimeFields[] = {
    either<kTimeModes, &TimeConfig::mode>("mode", "realtime: epochs follow the wall clock; lockstep: epochs follow "
                                                  "the simulation time carried by truth packets"),
    start_field(),
    boolean<&TimeConfig::use_wall_clock_date>(
        "use_wall_clock_date",
        "true: GPS time is the system clock, today's date (the nav data are moved to it unless they cover it); "
        "cannot be true together with `start`. false without `start`: the nav data's own first day (first toe + 1 h)")
        .default_doc("`true` without `start`, `false` with it"),
    rule<TimeConfig, check_start, RuleScope::kKey>(),
    number<&TimeConfig::output_delay_s>("output_delay_s", TimeRanges::output_delay_s,
                                        "realtime: measurement epoch to the first byte on the wire (a u-blox M8 "
                                        "starts its output about 0.1 s after the epoch, docs/daemon.md)"),
};
constexpr Section<TimeConfig> kTime{kTimeFields};

// --- [truth], [demo], [status], [log] --------------------------------------

void read_allow(TableReader& t, const Field<TruthInputConfig>& f, TruthInputConfig& truth) {
  read_address_blocks(t, f.key, truth.allow);
}

void write_allow(TomlWriter& w, const Field<TruthInputConfig>& f, const TruthInputConfig& truth) {
  if (!truth.allow.empty()) w.key(f.key, address_blocks_text(truth.allow), f.note);
}

void read_vehicle(TableReader& t, const Field<TruthInputConfig>& f, TruthInputConfig& truth) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) return;
  truth.vehicle = t.string(f.key, std::nullopt);
  if (truth.vehicle.empty()) t.fail(*n, t.full_name(f.key) + ": must not be empty (leave it out: the first vehicle)");
  if (truth.vehicle.size() > 64) t.fail(*n, t.full_name(f.key) + ": longer than a packet's vehicle id (64 bytes)");
}

void write_vehicle(TomlWriter& w, const Field<TruthInputConfig>& f, const TruthInputConfig& truth) {
  if (!truth.vehicle.empty()) w.key(f.key, string_text(truth.vehicle), f.note);
}

constexpr Field<TruthInputConfig> kTruthFields[] = {
    address<&TruthInputConfig::bind_address>("bind", "address to listen on (`\"0.0.0.0\"`: all interfaces); host "
                                                     "names are not accepted"),
    integer<&TruthInputConfig::port>("port", 0, 65535, "UDP port; 0 picks a free port (logged)"),
    number<&TruthInputConfig::timeout_s>("timeout_s", Range{0.0, 60.0, "s", true},
                                         "no truth for this long → no fix, as a receiver without antenna"),
    number<&TruthInputConfig::max_extrapolation_s>(
        "max_extrapolation_s", Range{0.0, 10.0, "s"},
        "how far truth is extrapolated past its last sample; ≤ `timeout_s`"),
    rule<TruthInputConfig, check_extrapolation, RuleScope::kKey>(),
    custom<TruthInputConfig>("allow", "", "addresses, CIDR blocks",
                             "senders accepted, e.g. `[\"127.0.0.1\", \"10.0.0.0/8\", \"::1\"]`; packets from "
                             "others are dropped and counted as `not_allowed`. Unset: any sender",
                             read_allow, write_allow)
        .default_doc("unset"),
    custom<TruthInputConfig>("vehicle", "", "a vehicle id",
                             "the vehicle that drives the receiver; truth of other vehicles is tracked, logged once "
                             "and does not move the fix. Unset: the first vehicle heard",
                             read_vehicle, write_vehicle)
        .default_doc("unset"),
};
constexpr Section<TruthInputConfig> kTruth{kTruthFields};

constexpr Field<DemoConfig> kDemoFields[] = {
    boolean<&DemoConfig::enabled>("enabled", "drive a circle around the origin until truth arrives"),
    number<&DemoConfig::radius_m>("radius_m", Range{0.0, 100000.0, "m", true}, "circle radius"),
    number<&DemoConfig::speed_m_s>("speed_m_s", Range{0.0, 500.0, "m/s"}, "ground speed (u-blox airborne limit)"),
    number<&DemoConfig::height_m>("height_m", kHeight, "height above the origin"),
};
constexpr Section<DemoConfig> kDemo{kDemoFields};

constexpr Field<StatusConfig> kStatusFields[] = {
    address<&StatusConfig::bind>("bind", "address of the status page (docs/status.md); anything but loopback "
                                         "(`127.0.0.0/8`, `::1`) makes the vehicle's position reachable from other "
                                         "machines and is logged as a warning; host names are not accepted"),
    integer<&StatusConfig::port>("port", 0, 65535,
                                 "TCP port of the page; 0: no page. A port already taken at start-up moves the "
                                 "page to a free one (logged as a warning, the URL is printed)"),
    boolean<&StatusConfig::free_port>("free_port", "true: any free port instead of `port` (the URL is printed at "
                                                   "start-up), e.g. for several daemons on one machine"),
    rule<StatusConfig, check_status, RuleScope::kKey>(),
};
constexpr Section<StatusConfig> kStatus{kStatusFields};

void read_socket(TableReader& t, const Field<ControlConfig>& f, ControlConfig& c) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) return;
  c.socket = t.string(f.key, std::nullopt);
  const std::string name = t.full_name(f.key);
  if (c.socket.empty()) t.fail(*n, name + ": must not be empty (leave it out: no control socket)");
  if (c.socket.front() != '/') t.fail(*n, name + ": '" + c.socket + "' must be an absolute path");
  if (c.socket.size() > kMaxSocketPathBytes) {
    t.fail(*n, name + ": " + std::to_string(c.socket.size()) + " bytes; a Unix socket path holds at most " +
                   std::to_string(kMaxSocketPathBytes));
  }
}

void write_socket(TomlWriter& w, const Field<ControlConfig>& f, const ControlConfig& c) {
  if (!c.socket.empty()) w.key(f.key, string_text(c.socket), f.note);
}

constexpr Field<ControlConfig> kControlFields[] = {
    custom<ControlConfig>("socket", "path", "absolute, at most 107 bytes",
                          "Unix socket for `gnssemu ctl` (status, fault injection; docs/daemon.md), created 0600 "
                          "and removed at exit. Unset: no control socket",
                          read_socket, write_socket)
        .default_doc("unset"),
};
constexpr Section<ControlConfig> kControl{kControlFields};

constexpr std::array<std::string_view, 7> kLogLevels{"trace", "debug", "info", "warn", "error", "critical", "off"};

std::string log_levels_text() {
  std::string out;
  for (const std::string_view l : kLogLevels) out += (out.empty() ? "" : ", ") + std::string(l);
  return out;
}

void read_level(TableReader& t, const Field<LogConfig>& f, LogConfig& log) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) return;
  log.level = t.string(f.key, std::nullopt);
  if (std::find(kLogLevels.begin(), kLogLevels.end(), log.level) == kLogLevels.end()) {
    t.fail(*n, t.full_name(f.key) + ": '" + log.level + "' is not one of " + log_levels_text());
  }
}

void write_level(TomlWriter& w, const Field<LogConfig>& f, const LogConfig& log) {
  w.key(f.key, string_text(log.level));
}

std::string level_names() { return names_doc(kLogLevels); }

constexpr Field<LogConfig> kLogFields[] = {
    custom<LogConfig>("level", "", level_names, "daemon log level", read_level, write_level),
};
constexpr Section<LogConfig> kLog{kLogFields};

// --- the file --------------------------------------------------------------

// The page and a tcp [[output]] cannot listen on one port: reported at
// status.port when the file sets it, else at the output's port.
void check_status_port(TableReader& t, const Field<Config>&, Config& c) {
  if (c.status.port == 0 || c.status.free_port) return;
  for (std::size_t i = 0; i < c.outputs.size(); ++i) {
    const auto* tcp = std::get_if<TcpPortConfig>(&c.outputs[i].transport);
    if (tcp == nullptr || tcp->port != c.status.port) continue;
    const std::string reason = "status.port: " + std::to_string(c.status.port) + " is also the tcp port of [[output]] '" +
                               c.outputs[i].name + "'";
    const toml::node* at = nullptr;
    if (const toml::node* st = t.find("status"); st != nullptr && st->is_table()) at = st->as_table()->get("port");
    if (at == nullptr) {
      const toml::node* outs = t.find("output");
      const toml::array* a = outs != nullptr ? outs->as_array() : nullptr;
      const toml::table* o = a != nullptr && i < a->size() ? a->get(i)->as_table() : nullptr;
      at = o != nullptr ? o->get("port") : nullptr;
    }
    throw Error(t.file(), at != nullptr ? line_of(*at) : t.line(), reason);
  }
}

// The world's and the receiver's validators on the assembled models, reported
// at [atmosphere] (else [signal], else the file).
void check_models(TableReader& t, const Field<Config>&, Config& c) {
  const toml::node* at = t.find("atmosphere");
  if (at == nullptr) at = t.find("signal");
  validate_at(t.file(), at != nullptr ? line_of(*at) : t.line(), [&] {
    world::validate(c.world);
    receiver::validate(c.receiver);
  });
}

constexpr Field<Config> kConfigFields[] = {
    table<kOrigin, &Config::origin>("origin", "local frame origin, WGS-84").needed(),
    table<kNav>("nav").needed(),
    table<kTime, &Config::time>("time"),
    table<kReceiverKeys>("receiver"),
    table<kAtmosphereKeys, &Config::world, &world::WorldConfig::atmosphere>("atmosphere",
                                                                             "what the world does to the signal"),
    table<kSignalKeys>("signal", "link budget -> C/N0, tracking"),
    check<Config>(check_models),
    table<kTruth, &Config::truth>("truth", "UDP truth input"),
    table<kDemo, &Config::demo>("demo", "circle around the origin while no truth arrives"),
    table_array<kOutputKeys, check_unique_port, &Config::outputs>("output"),
    check<Config>(check_output_generation),
    custom_table<Config>("vehicle", read_vehicles, write_vehicles, describe_vehicles),
    custom_table<Config>("fleet", read_fleet, write_fleet, describe_fleet),
    custom_table<Config>("base", read_base, write_base, describe_base),
    optional_table<kSceneKeys, &Config::scene>("scene", "buildings, docs/scene.md"),
    table<kStatus, &Config::status>("status", "live status page, docs/status.md"),
    check<Config>(check_status_port),
    check<Config>(check_vehicles),
    table<kControl, &Config::control>("control", "control socket, docs/daemon.md"),
    table<kLog, &Config::log>("log"),
};

}  // namespace

constexpr Section<Config> kConfigKeys{kConfigFields};

void read_address_blocks(TableReader& t, std::string_view key, std::vector<AddressBlock>& out) {
  if (t.find(key) != nullptr) out.clear();
  t.string_array(key, "an array of addresses", "an address string", [&](const toml::node& e, const std::string& s) {
    std::string why;
    const std::optional<AddressBlock> b = parse_address_block(s, why);
    if (!b) t.fail(e, t.full_name(key) + ": " + why);
    out.push_back(*b);
  });
}

std::string address_blocks_text(const std::vector<AddressBlock>& blocks) {
  if (blocks.empty()) return "";
  std::string list = "[";
  for (const AddressBlock& b : blocks) list += (list.size() > 1 ? ", " : "") + string_text(b.text());
  return list + "]";
}

KeyDocs describe_keys() {
  KeyDocs d;
  describe_section(d, kConfigKeys, Config{});
  return d;
}

}  // namespace detail

}  // namespace gnssemu::config

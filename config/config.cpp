// TOML -> Config with validation. Schema and ranges: docs/configuration.md.
#include "config/config.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <toml++/toml.h>

#include "config/config_atmosphere.hpp"
#include "config/message_names.hpp"
#include "config/toml_reader.hpp"
#include "core/common/error.hpp"

namespace gnssemu::config {

namespace {

namespace fs = std::filesystem;
using detail::Range;
using detail::TableReader;

constexpr std::array<std::string_view, 7> kLogLevels{"trace", "debug", "info", "warn", "error", "critical", "off"};

fs::path resolve(const std::string& path, const std::string& base_dir) {
  fs::path p(path);
  if (p.is_relative()) p = fs::path(base_dir.empty() ? "." : base_dir) / p;
  return fs::absolute(p).lexically_normal();
}

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
  if (!(c.second >= 0.0 && c.second < 60.0)) return "second " + detail::format_number(c.second) + " is not in [0, 60)";
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

std::optional<time::GpsTime> read_start(TableReader& t) {
  const toml::node* n = t.find("start");
  if (n == nullptr) return std::nullopt;
  const std::string name = t.full_name("start");
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
    t.fail(*n, name + ": expected a date-time string \"YYYY-MM-DDTHH:MM:SS\", got " +
                   std::string(detail::type_name(*n)));
  }
  if (const std::string why = calendar_problem(c); !why.empty()) t.fail(*n, name + ": bad date-time: " + why);
  return time::GpsTime::from_calendar(c);
}

TimeConfig read_time(TableReader& t) {
  TimeConfig out;
  if (const toml::node* n = t.find("mode")) {
    const std::string mode = t.string("mode", std::nullopt);
    if (mode == "realtime") {
      out.mode = TimeMode::kRealtime;
    } else if (mode == "lockstep") {
      out.mode = TimeMode::kLockstep;
    } else {
      t.fail(*n, t.full_name("mode") + ": '" + mode + "' is not \"realtime\" or \"lockstep\"");
    }
  }
  out.start = read_start(t);
  out.use_wall_clock_date = t.boolean("use_wall_clock_date", !out.start.has_value());
  if (out.use_wall_clock_date && out.start) {
    t.fail(*t.find("use_wall_clock_date"),
           t.full_name("use_wall_clock_date") + ": cannot be true together with time.start");
  }
  t.finish();
  return out;
}

// An integer key whose range is a core Range of whole numbers.
int integer_in(TableReader& t, std::string_view key, int def, const gnssemu::Range& r) {
  return static_cast<int>(t.integer(key, def, static_cast<int64_t>(r.min), static_cast<int64_t>(r.max)));
}

void read_solver(TableReader& t, receiver::SolverConfig& s) {
  using R = receiver::SolverRanges;
  s.sigma_a_m = t.number("sigma_a_m", s.sigma_a_m, R::sigma_a_m);
  s.sigma_b_m = t.number("sigma_b_m", s.sigma_b_m, R::sigma_b_m);
  if (s.sigma_a_m == 0.0 && s.sigma_b_m == 0.0) {
    const toml::node* n = t.find("sigma_a_m");
    if (n == nullptr) n = t.find("sigma_b_m");
    t.fail(*n, t.path() + ": sigma_a_m and sigma_b_m are both 0 (the solver's weights would be infinite)");
  }
  s.sigma_c_m_sqrt_hz = t.number("sigma_c_m_sqrt_hz", s.sigma_c_m_sqrt_hz, R::sigma_c_m_sqrt_hz);
  s.iono_model_fraction = t.number("iono_model_fraction", s.iono_model_fraction, R::iono_model_fraction);
  s.tropo_model_sigma_m = t.number("tropo_model_sigma_m", s.tropo_model_sigma_m, R::tropo_model_sigma_m);
  s.sigma_range_rate_m_s = t.number("sigma_range_rate_m_s", s.sigma_range_rate_m_s, R::sigma_range_rate_m_s);
  s.height_hold_sigma_m = t.number("height_hold_sigma_m", s.height_hold_sigma_m, R::height_hold_sigma_m);
  s.residual_test_pfa = t.number("residual_test_pfa", s.residual_test_pfa, R::residual_test_pfa);
  s.max_exclusions = integer_in(t, "max_exclusions", s.max_exclusions, R::max_exclusions);
  s.max_iterations = integer_in(t, "max_iterations", s.max_iterations, R::max_iterations);
  t.finish();
  detail::validate_at(t, [&] { receiver::validate(s); });
}

void read_errors(TableReader& t, world::ErrorModelConfig& em) {
  using R = world::ErrorModelRanges;
  using Gm = world::GaussMarkovRanges;
  detail::read_thermal_model(t, em);
  em.thermal_sigma_m = t.number("thermal_sigma_m", em.thermal_sigma_m, R::thermal_sigma_m);
  em.doppler_sigma_m_s = t.number("doppler_sigma_m_s", em.doppler_sigma_m_s, R::doppler_sigma_m_s);
  if (auto oc = t.table("orbit_clock", false)) {
    detail::read_gauss_markov(*oc, em.orbit_clock, "sigma_m", Gm::sigma_m, Gm::tau_s);
  }
  if (auto mp = t.table("multipath", false)) detail::read_gauss_markov(*mp, em.multipath, "sigma_m", Gm::sigma_m, Gm::tau_s);
  if (auto g = t.table("gradient", false)) {
    world::ErrorModelConfig::Gradient& gr = em.gradient;
    gr.north_m = g->number("north_m", gr.north_m, R::gradient_north_m);
    gr.east_m = g->number("east_m", gr.east_m, R::gradient_east_m);
    gr.north_diurnal_m = g->number("north_diurnal_m", gr.north_diurnal_m, R::gradient_north_diurnal_m);
    gr.north_peak_h = g->number("north_peak_h", gr.north_peak_h, R::gradient_north_peak_h);
    gr.east_diurnal_m = g->number("east_diurnal_m", gr.east_diurnal_m, R::gradient_east_diurnal_m);
    gr.east_peak_h = g->number("east_peak_h", gr.east_peak_h, R::gradient_east_peak_h);
    detail::read_gauss_markov(*g, gr.process, "sigma_m", Gm::sigma_m, Gm::tau_s);
  }
  t.finish();
}

void read_clock(TableReader& t, world::ClockConfig& ck) {
  using R = world::ClockRanges;
  ck.bias_s = t.number("bias_s", ck.bias_s, R::bias_s);
  ck.drift_s_s = t.number("drift_s_s", ck.drift_s_s, R::drift_s_s);
  ck.drift_noise_s_s_sqrt_s = t.number("drift_noise_s_s_sqrt_s", ck.drift_noise_s_s_sqrt_s, R::drift_noise_s_s_sqrt_s);
  ck.jump_threshold_s = t.number("jump_threshold_s", ck.jump_threshold_s, R::jump_threshold_s);
  t.finish();
}

void read_receiver(TableReader& t, Config& c) {
  using R = receiver::ReceiverRanges;
  receiver::ReceiverConfig& r = c.receiver;
  world::WorldConfig& w = c.world;
  c.rate_hz = t.number("rate_hz", c.rate_hz, Range{1.0, 10.0, "Hz"});
  r.elevation_mask_rad = t.number("elevation_mask_deg", r.elevation_mask_rad * kRadToDeg, R::elevation_mask_deg) * kDegToRad;
  // Any 64-bit seed is valid; TOML integers stop at 2^63 - 1.
  w.seed = static_cast<uint64_t>(
      t.integer("seed", static_cast<int64_t>(w.seed), 0, std::numeric_limits<int64_t>::max()));
  w.nominal_cn0_dbhz = t.number("nominal_cn0_dbhz", w.nominal_cn0_dbhz, world::WorldRanges::nominal_cn0_dbhz);
  r.max_pdop = t.number("max_pdop", r.max_pdop, R::max_pdop);
  r.max_channels = integer_in(t, "max_channels", r.max_channels, R::max_channels);
  if (auto e = t.table("errors", false)) read_errors(*e, w.errors);
  if (auto k = t.table("clock", false)) read_clock(*k, w.clock);
  if (auto s = t.table("solver", false)) read_solver(*s, r.solver);
  if (auto s = t.table("corrections", false)) detail::read_corrections(*s, r.solver);
  t.finish();
  detail::validate_at(t, [&] { receiver::validate(r); });
}

TruthInputConfig read_truth(TableReader& t) {
  TruthInputConfig out;
  if (const toml::node* n = t.find("bind")) {
    out.bind_address = t.string("bind", std::nullopt);
    in6_addr buf{};
    if (inet_pton(AF_INET, out.bind_address.c_str(), &buf) != 1 &&
        inet_pton(AF_INET6, out.bind_address.c_str(), &buf) != 1) {
      t.fail(*n, t.full_name("bind") + ": '" + out.bind_address + "' is not an IPv4 or IPv6 address");
    }
  }
  out.port = static_cast<uint16_t>(t.integer("port", out.port, 0, 65535));
  out.timeout_s = t.number("timeout_s", out.timeout_s, Range{0.0, 60.0, "s", true});
  out.max_extrapolation_s = t.number("max_extrapolation_s", out.max_extrapolation_s, Range{0.0, 10.0, "s"});
  if (out.max_extrapolation_s > out.timeout_s) {
    t.fail(*t.find("max_extrapolation_s"), t.full_name("max_extrapolation_s") + ": " +
                                               detail::format_number(out.max_extrapolation_s) +
                                               " s exceeds truth.timeout_s (" +
                                               detail::format_number(out.timeout_s) + " s)");
  }
  t.finish();
  return out;
}

DemoConfig read_demo(TableReader& t) {
  DemoConfig out;
  out.enabled = t.boolean("enabled", out.enabled);
  out.radius_m = t.number("radius_m", out.radius_m, Range{0.0, 100000.0, "m", true});
  // u-blox airborne limit 500 m/s.
  out.speed_m_s = t.number("speed_m_s", out.speed_m_s, Range{0.0, 500.0, "m/s"});
  out.height_m = t.number("height_m", out.height_m, Range{-1000.0, 50000.0, "m"});
  t.finish();
  return out;
}

protocol::nmea::NmeaVersion read_nmea_version(TableReader& t, protocol::nmea::NmeaVersion def) {
  using protocol::nmea::NmeaVersion;
  const toml::node* n = t.find("nmea_version");
  if (n == nullptr) return def;
  const std::string v = t.string("nmea_version", std::nullopt);
  if (v == "2.3") return NmeaVersion::k23;
  if (v == "4.10") return NmeaVersion::k410;
  if (v == "4.11") return NmeaVersion::k411;
  t.fail(*n, t.full_name("nmea_version") + ": '" + v + "' is not one of \"2.3\", \"4.10\", \"4.11\"");
}

protocol::nmea::SentenceSet read_sentences(TableReader& t, const protocol::nmea::SentenceSet& def) {
  const toml::node* n = t.find("sentences");
  if (n == nullptr) return def;
  const std::string name = t.full_name("sentences");
  const auto* a = n->as_array();
  if (a == nullptr) t.fail(*n, name + ": expected an array of strings, got " + std::string(detail::type_name(*n)));
  if (a->empty()) t.fail(*n, name + ": must name at least one sentence");
  protocol::nmea::SentenceSet out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const auto* s = e.as_string();
    if (s == nullptr) t.fail(e, name + ": expected sentence names (strings), got " + std::string(detail::type_name(e)));
    const std::optional<protocol::nmea::Sentence> sentence = protocol::nmea::sentence_by_name(s->get());
    if (!sentence) {
      t.fail(e, name + ": unknown sentence '" + s->get() + "' (known: GGA RMC GSA GSV VTG GLL GST ZDA)");
    }
    if (out.has(*sentence)) t.fail(e, name + ": '" + s->get() + "' listed twice");
    out.set(*sentence);
  }
  return out;
}

bool is_line(PortType type) { return type == PortType::kPty || type == PortType::kSerial; }

// Keys that belong to one port type only.
struct TypedKey {
  std::string_view key;
  std::initializer_list<PortType> types;
};

void reject_foreign_keys(TableReader& t, PortType type) {
  static const std::array<TypedKey, 5> kKeys{{
      {"path", {PortType::kPty, PortType::kFile}},
      {"device", {PortType::kSerial}},
      {"bind", {PortType::kTcp}},
      {"address", {PortType::kUdp}},
      {"port", {PortType::kTcp, PortType::kUdp}},
  }};
  for (const TypedKey& k : kKeys) {
    const toml::node* n = t.find(k.key);
    if (n == nullptr || std::find(k.types.begin(), k.types.end(), type) != k.types.end()) continue;
    std::string owners;
    for (const PortType o : k.types) {
      owners += owners.empty() ? "\"" : " or \"";
      owners += port_type_name(o);
      owners += '"';
    }
    t.fail(*n, t.full_name(k.key) + ": not used by a port of type \"" + std::string(port_type_name(type)) +
                   "\" (only " + owners + ")");
  }
}

uint16_t read_protocols(TableReader& t, std::string_view key, uint16_t def) {
  const toml::node* n = t.find(key);
  if (n == nullptr) return def;
  const std::string name = t.full_name(key);
  const auto* a = n->as_array();
  if (a == nullptr) t.fail(*n, name + ": expected an array of strings, got " + std::string(detail::type_name(*n)));
  uint16_t mask = 0;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const auto* s = e.as_string();
    if (s == nullptr) t.fail(e, name + ": expected protocol names (strings), got " + std::string(detail::type_name(e)));
    const uint16_t bit = s->get() == "ubx" ? protocol::ubx::proto::kUbx : s->get() == "nmea" ? protocol::ubx::proto::kNmea : 0;
    if (bit == 0) t.fail(e, name + ": unknown protocol '" + s->get() + "' (known: \"ubx\", \"nmea\")");
    if ((mask & bit) != 0) t.fail(e, name + ": '" + s->get() + "' listed twice");
    mask |= bit;
  }
  return mask;
}

std::vector<MessageRate> read_ubx_messages(TableReader& t) {
  std::vector<MessageRate> out;
  const toml::node* n = t.find("ubx_messages");
  if (n == nullptr) return out;
  const std::string name = t.full_name("ubx_messages");
  const auto* a = n->as_array();
  if (a == nullptr) t.fail(*n, name + ": expected an array of strings, got " + std::string(detail::type_name(*n)));
  std::string known;
  for (const MessageName& m : ubx_periodic_messages()) {
    if (!known.empty()) known += ' ';
    known += m.name;
  }
  std::vector<bool> seen(ubx_periodic_messages().size(), false);
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const auto* s = e.as_string();
    if (s == nullptr) t.fail(e, name + ": expected message names (strings), got " + std::string(detail::type_name(e)));
    const auto table = ubx_periodic_messages();
    const auto it = std::find_if(table.begin(), table.end(), [&](const MessageName& m) { return m.name == s->get(); });
    if (it == table.end()) t.fail(e, name + ": unknown UBX message '" + s->get() + "' (known: " + known + ")");
    const auto k = static_cast<std::size_t>(it - table.begin());
    if (seen[k]) t.fail(e, name + ": '" + s->get() + "' listed twice");
    seen[k] = true;
  }
  // Stored in epoch order, whatever the order in the file.
  for (std::size_t k = 0; k < seen.size(); ++k) {
    if (seen[k]) out.push_back({ubx_periodic_messages()[k].msg_class, ubx_periodic_messages()[k].msg_id, 1});
  }
  return out;
}

bool sentence_on(const protocol::nmea::SentenceSet& s, uint8_t id) {
  const std::optional<protocol::nmea::Sentence> sentence = protocol::nmea::sentence_by_msg_id(id);
  return sentence && s.has(*sentence);
}

// rates = { NAV-SAT = 5, GSV = 2 }: rates other than 1 for listed messages.
void read_rates(TableReader& t, OutputPortConfig& out) {
  const toml::node* n = t.find("rates");
  if (n == nullptr) return;
  const std::string name = t.full_name("rates");
  const auto* tbl = n->as_table();
  if (tbl == nullptr) {
    t.fail(*n, name + ": expected a table of message = rate (e.g. { NAV-SAT = 5 }), got " +
                   std::string(detail::type_name(*n)));
  }
  for (const auto& [key, value] : *tbl) {
    const std::string msg(key.str());
    const std::string what = name + "." + msg;
    const std::optional<MessageName> m = message_by_name(msg);
    if (!m) t.fail(value, what + ": unknown message '" + msg + "'");
    const auto* v = value.as_integer();
    if (v == nullptr) t.fail(value, what + ": expected an integer, got " + std::string(detail::type_name(value)));
    const int64_t rate = v->get();
    if (rate < 1 || rate > 255) {
      t.fail(value, what + ": " + std::to_string(rate) +
                        " is out of range [1, 255] (epochs per message; leave a message out to turn it off)");
    }
    const auto r = static_cast<uint8_t>(rate);
    if (m->msg_class == kNmeaClass) {
      if (!sentence_on(out.nmea.sentences, m->msg_id)) t.fail(value, what + ": '" + msg + "' is not in sentences");
      if (r != 1) out.nmea_rates.push_back({m->msg_class, m->msg_id, r});
    } else {
      auto it = std::find_if(out.ubx_messages.begin(), out.ubx_messages.end(), [&](const MessageRate& x) {
        return x.msg_class == m->msg_class && x.msg_id == m->msg_id;
      });
      if (it == out.ubx_messages.end()) t.fail(value, what + ": '" + msg + "' is not in ubx_messages");
      it->rate = r;
    }
  }
  // u-blox order, whatever the order in the file.
  std::vector<MessageRate> sorted;
  for (const MessageName& s : nmea_sentences()) {
    for (const MessageRate& r : out.nmea_rates) {
      if (r.msg_id == s.msg_id) sorted.push_back(r);
    }
  }
  out.nmea_rates = std::move(sorted);
}

PtyPortConfig read_pty(TableReader& t) {
  PtyPortConfig pty{t.string("path", std::nullopt)};
  const toml::node* node = t.find("path");
  if (pty.path.empty()) t.fail(*node, t.full_name("path") + ": must not be empty");
  if (fs::path(pty.path).is_relative()) t.fail(*node, t.full_name("path") + ": pty path '" + pty.path + "' must be absolute");
  return pty;
}

FilePortConfig read_file(TableReader& t, const std::string& base_dir) {
  FilePortConfig file{t.string("path", std::nullopt)};
  if (file.path.empty()) t.fail(*t.find("path"), t.full_name("path") + ": must not be empty");
  file.path = resolve(file.path, base_dir).string();
  return file;
}

SerialPortConfig read_serial(TableReader& t) {
  SerialPortConfig serial{t.string("device", std::nullopt)};
  if (serial.device.empty() || fs::path(serial.device).is_relative()) {
    t.fail(*t.find("device"), t.full_name("device") + ": serial device '" + serial.device +
                                  "' must be an absolute path (e.g. /dev/ttyUSB0)");
  }
  return serial;
}

// An IPv4 or IPv6 address at key, or def when the key is absent.
std::string read_address(TableReader& t, std::string_view key, std::optional<std::string> def) {
  const toml::node* n = t.find(key);
  if (n == nullptr) {
    if (!def) t.fail_missing(key, "key");
    return *def;
  }
  std::string address = t.string(key, std::nullopt);
  in6_addr buf{};
  if (inet_pton(AF_INET, address.c_str(), &buf) != 1 && inet_pton(AF_INET6, address.c_str(), &buf) != 1) {
    t.fail(*n, t.full_name(key) + ": '" + address + "' is not an IPv4 or IPv6 address");
  }
  return address;
}

TcpPortConfig read_tcp(TableReader& t) {
  TcpPortConfig tcp;
  tcp.bind = read_address(t, "bind", tcp.bind);
  tcp.port = static_cast<uint16_t>(t.integer("port", 0, 0, 65535));
  return tcp;
}

UdpPortConfig read_udp(TableReader& t) {
  UdpPortConfig udp;
  udp.address = read_address(t, "address", std::nullopt);
  udp.port = static_cast<uint16_t>(t.integer("port", std::nullopt, 1, 65535));
  return udp;
}

// The file or device a port claims for itself ("" for network ports).
std::string claimed_path(const PortTransport& transport) {
  if (const auto* pty = std::get_if<PtyPortConfig>(&transport)) return pty->path;
  if (const auto* file = std::get_if<FilePortConfig>(&transport)) return file->path;
  if (const auto* serial = std::get_if<SerialPortConfig>(&transport)) return serial->device;
  return {};
}

OutputPortConfig read_output(TableReader& t, const std::string& base_dir) {
  OutputPortConfig out;
  out.name = t.string("name", std::nullopt);
  if (out.name.empty()) t.fail(*t.find("name"), t.full_name("name") + ": must not be empty");
  for (const char ch : out.name) {
    if (static_cast<unsigned char>(ch) <= ' ') {
      t.fail(*t.find("name"), t.full_name("name") + ": '" + out.name + "' contains a space or control character");
    }
  }
  PortType type = PortType::kPty;
  if (const toml::node* n = t.find("type")) {
    const std::string name = t.string("type", std::nullopt);
    const std::optional<PortType> known = port_type_from_name(name);
    if (known) type = *known;
    if (!known) t.fail(*n, t.full_name("type") + ": '" + name + "' is not one of \"pty\", \"serial\", \"tcp\", \"udp\", \"file\"");
  }
  reject_foreign_keys(t, type);
  switch (type) {
    case PortType::kPty: out.transport = read_pty(t); break;
    case PortType::kFile: out.transport = read_file(t, base_dir); break;
    case PortType::kSerial: out.transport = read_serial(t); break;
    case PortType::kTcp: out.transport = read_tcp(t); break;
    case PortType::kUdp: out.transport = read_udp(t); break;
  }
  const bool line = is_line(out.type());
  out.baud = line ? 9600 : 0;
  const int64_t baud = t.integer("baud", out.baud, line ? 1 : 0, std::numeric_limits<uint32_t>::max());
  if (baud != 0 && !protocol::ubx::is_ubx_baud(static_cast<uint32_t>(baud))) {
    std::string rates;
    for (const uint32_t b : protocol::ubx::kUartBauds) {
      if (!rates.empty()) rates += ' ';
      rates += std::to_string(b);
    }
    t.fail(*t.find("baud"), t.full_name("baud") + ": " + std::to_string(baud) + " is not a standard rate (" + rates +
                                ")" + (line ? "" : " or 0 (no line budget)"));
  }
  out.baud = static_cast<uint32_t>(baud);

  const bool has_input = out.type() != PortType::kFile && out.type() != PortType::kUdp;
  out.protocols_in = read_protocols(t, "protocols_in", has_input ? protocol::ubx::proto::kUbx | protocol::ubx::proto::kNmea : 0);
  if (!has_input && out.protocols_in != 0) {
    t.fail(*t.find("protocols_in"), t.full_name("protocols_in") + ": a port of type \"" +
                                        std::string(port_type_name(out.type())) + "\" has no input; use []");
  }
  out.protocols_out = read_protocols(t, "protocols_out", protocol::ubx::proto::kUbx | protocol::ubx::proto::kNmea);
  out.ubx_messages = read_ubx_messages(t);
  out.nmea.version = read_nmea_version(t, out.nmea.version);
  out.nmea.sentences = read_sentences(t, out.nmea.sentences);
  out.nmea.course_min_speed_m_s =
      t.number("course_min_speed_m_s", out.nmea.course_min_speed_m_s, Range{0.0, 10.0, "m/s"});
  read_rates(t, out);
  t.finish();
  return out;
}

std::vector<OutputPortConfig> read_outputs(TableReader& root, const std::string& base_dir) {
  std::vector<OutputPortConfig> out;
  for (TableReader& t : root.table_array("output")) {
    OutputPortConfig port = read_output(t, base_dir);
    for (const OutputPortConfig& prev : out) {
      if (prev.name == port.name) t.fail(*t.find("name"), t.full_name("name") + ": '" + port.name + "' is used twice");
      const std::string path = claimed_path(port.transport);
      if (!path.empty() && claimed_path(prev.transport) == path) {
        const std::string_view key = port.type() == PortType::kSerial ? "device" : "path";
        t.fail(*t.find(key), t.full_name(key) + ": '" + path + "' is already used by output '" + prev.name + "'");
      }
      const auto* tcp = std::get_if<TcpPortConfig>(&port.transport);
      const auto* prev_tcp = std::get_if<TcpPortConfig>(&prev.transport);
      if (tcp != nullptr && prev_tcp != nullptr && tcp->port != 0 && prev_tcp->port == tcp->port) {
        t.fail(*t.find("port"), t.full_name("port") + ": tcp port " + std::to_string(tcp->port) +
                                    " is already used by output '" + prev.name + "'");
      }
    }
    out.push_back(std::move(port));
  }
  return out;
}

Enu read_offset(TableReader& t) {
  const toml::node* n = t.find("offset_m");
  if (n == nullptr) return {};
  const std::string name = t.full_name("offset_m");
  const auto* a = n->as_array();
  if (a == nullptr || a->size() != 3) t.fail(*n, name + ": expected [east_m, north_m, up_m]");
  double v[3];
  for (std::size_t i = 0; i < 3; ++i) {
    const auto x = a->get(i)->value<double>();
    if (!x || !std::isfinite(*x) || std::fabs(*x) > 1.0e6) {
      t.fail(*a->get(i), name + ": components must be finite numbers within 1000 km");
    }
    v[i] = *x;
  }
  return Enu(v[0], v[1], v[2]);
}

SceneConfig read_scene(TableReader& t, const std::string& base_dir) {
  SceneConfig s;
  const std::string mesh = t.string("mesh", std::nullopt);
  const toml::node* mesh_node = t.find("mesh");
  if (mesh.empty()) t.fail(*mesh_node, "scene.mesh: must not be empty");
  const fs::path mesh_path = resolve(mesh, base_dir);
  std::error_code ec;
  if (!fs::is_regular_file(mesh_path, ec)) {
    t.fail(*mesh_node, "scene.mesh: '" + mesh + "' not found (tried " + mesh_path.string() + ")");
  }
  s.mesh_file = mesh_path.string();
  s.placement.offset_m = read_offset(t);
  s.placement.yaw_rad = t.number("yaw_deg", 0.0, Range{-360.0, 360.0, "deg"}) * kDegToRad;
  s.placement.scale = t.number("scale", 1.0, Range{0.0, 1.0e6, "", true});
  if (const toml::node* n = t.find("up_axis")) {
    const std::string up = t.string("up_axis", std::nullopt);
    if (up != "z" && up != "y") t.fail(*n, t.full_name("up_axis") + ": '" + up + "' is not \"z\" or \"y\"");
    s.placement.y_up = up == "y";
  }
  scene::SearchConfig& q = s.search;
  q.rays = static_cast<int>(t.integer("rays", q.rays, 16, 4'000'000));
  q.azimuth_rays = static_cast<int>(t.integer("azimuth_rays", q.azimuth_rays, 0, 100000));
  q.max_bounces = static_cast<int>(t.integer("max_bounces", q.max_bounces, 1, scene::Propagator::kMaxBounces));
  q.match_factor = t.number("match_factor", q.match_factor, Range{0.0, 20.0, "", true});
  q.reuse_distance_m = t.number("reuse_distance_m", q.reuse_distance_m, Range{0.0, 1000.0, "m"});
  q.reuse_angle_rad = t.number("reuse_angle_deg", q.reuse_angle_rad * kRadToDeg, Range{0.0, 90.0, "deg"}) * kDegToRad;
  q.min_arrival_el_rad =
      t.number("min_arrival_elevation_deg", q.min_arrival_el_rad * kRadToDeg, Range{-89.0, 89.0, "deg"}) * kDegToRad;
  q.max_loss_db = t.number("max_loss_db", q.max_loss_db, Range{0.0, 1000.0, "dB", true});
  s.reflection_loss_db = t.number("reflection_loss_db", s.reflection_loss_db, Range{0.0, 100.0, "dB"});
  if (auto m = t.table("material_loss_db", false)) {
    const toml::node* tn = t.find("material_loss_db");
    for (const auto& [k, v] : *tn->as_table()) {
      const std::string key(k.str());
      s.material_loss_db.push_back({key, m->number(key, std::nullopt, Range{0.0, 100.0, "dB"}), detail::line_of(v)});
    }
    m->finish();
  }
  t.finish();
  return s;
}

Config read_config(const toml::table& doc, const std::string& name, const std::string& base_dir) {
  Config c;
  TableReader root(doc, "", name);

  TableReader origin = *root.table("origin", true);
  const double lat_deg = origin.number("lat_deg", std::nullopt, Range{-90.0, 90.0, "deg"});
  double lon_deg = origin.number("lon_deg", std::nullopt, Range{-180.0, 180.0, "deg"});
  if (lon_deg == -180.0) lon_deg = 180.0;  // Lla keeps lon in (-pi, pi]
  c.origin.lat_rad = lat_deg * kDegToRad;
  c.origin.lon_rad = lon_deg * kDegToRad;
  c.origin.height_m = origin.number("height_m", std::nullopt, Range{-1000.0, 50000.0, "m"});
  origin.finish();

  TableReader nav = *root.table("nav", true);
  const std::string nav_file = nav.string("file", std::nullopt);
  const toml::node* nav_node = nav.find("file");
  if (nav_file.empty()) nav.fail(*nav_node, "nav.file: must not be empty");
  const fs::path nav_path = resolve(nav_file, base_dir);
  std::error_code ec;
  if (!fs::is_regular_file(nav_path, ec)) {
    nav.fail(*nav_node, "nav.file: '" + nav_file + "' not found (tried " + nav_path.string() + ")");
  }
  c.nav_file = nav_path.string();
  nav.finish();

  if (auto t = root.table("time", false)) c.time = read_time(*t);
  if (auto t = root.table("receiver", false)) read_receiver(*t, c);
  {
    std::optional<TableReader> atm = root.table("atmosphere", false);
    if (atm) detail::read_atmosphere(*atm, c.world);
    std::optional<TableReader> sig = root.table("signal", false);
    if (sig) detail::read_signal(*sig, c.world, c.receiver);
    detail::check_models(atm ? *atm : sig ? *sig : root, c.world, c.receiver);
  }
  if (auto t = root.table("truth", false)) c.truth = read_truth(*t);
  if (auto t = root.table("demo", false)) c.demo = read_demo(*t);
  c.outputs = read_outputs(root, base_dir);
  if (auto t = root.table("scene", false)) c.scene = read_scene(*t, base_dir);
  if (auto t = root.table("log", false)) {
    if (const toml::node* n = t->find("level")) {
      c.log.level = t->string("level", std::nullopt);
      if (std::find(kLogLevels.begin(), kLogLevels.end(), c.log.level) == kLogLevels.end()) {
        t->fail(*n, "log.level: '" + c.log.level + "' is not one of trace, debug, info, warn, error, critical, off");
      }
    }
    t->finish();
  }
  root.finish();
  return c;
}

}  // namespace

namespace {
constexpr std::array<std::string_view, 5> kPortTypeNames{"pty", "file", "serial", "tcp", "udp"};  // by PortType
}  // namespace

std::string_view port_type_name(PortType type) noexcept { return kPortTypeNames[static_cast<std::size_t>(type)]; }

std::optional<PortType> port_type_from_name(std::string_view name) noexcept {
  for (std::size_t i = 0; i < kPortTypeNames.size(); ++i) {
    if (kPortTypeNames[i] == name) return static_cast<PortType>(i);
  }
  return std::nullopt;
}

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

Config parse_config(const std::string& toml_text, const std::string& name, const std::string& base_dir) {
  toml::table doc;
  try {
    doc = toml::parse(toml_text, name);
  } catch (const toml::parse_error& e) {
    throw Error(name, static_cast<int>(e.source().begin.line), "TOML syntax error: " + std::string(e.description()));
  }
  Config c = read_config(doc, name, base_dir);
  c.source = name;
  return c;
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

// SPDX-License-Identifier: Apache-2.0
// [[output]]: one port of the emulated u-blox (docs/ports.md): its type
// with the type's own keys, line rate, protocols and message set.
#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>

#include "config/keys/config_keys.hpp"
#include "config/message_names.hpp"
#include "core/common/error.hpp"
#include "core/protocol/ubx/config/ubx_device_config.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"

namespace gnssemu::config {

namespace {

// The TOML names of the port types, in the order messages list them.
constexpr detail::Choice<PortType> kPortTypes[] = {{"pty", PortType::kPty},
                                                   {"serial", PortType::kSerial},
                                                   {"tcp", PortType::kTcp},
                                                   {"udp", PortType::kUdp},
                                                   {"file", PortType::kFile}};

}  // namespace

std::string_view port_type_name(PortType type) noexcept {
  for (const auto& t : kPortTypes) {
    if (t.value == type) return t.name;
  }
  return {};
}

std::optional<PortType> port_type_from_name(std::string_view name) noexcept {
  for (const auto& t : kPortTypes) {
    if (t.name == name) return t.value;
  }
  return std::nullopt;
}

namespace detail {

namespace {

namespace fs = std::filesystem;
namespace proto = protocol::ubx::proto;

/// A line carries bytes at a baud rate (pty: recorded); the others do not.
bool is_line(PortType type) { return type == PortType::kPty || type == PortType::kSerial; }
/// File and udp ports only send.
bool has_input(PortType type) { return type != PortType::kFile && type != PortType::kUdp; }

// The settings of a port type, defaulted.
PortTransport transport_of(PortType type) {
  switch (type) {
    case PortType::kPty: return PtyPortConfig{};
    case PortType::kFile: return FilePortConfig{};
    case PortType::kSerial: return SerialPortConfig{};
    case PortType::kTcp: return TcpPortConfig{};
    case PortType::kUdp: return UdpPortConfig{};
  }
  return {};
}

/// Path element of member(): the alternative A of a std::variant.
template <class A>
struct As {
  template <class V>
  constexpr auto& operator()(V& v) const {
    return std::get<A>(v);
  }
};

std::vector<std::string_view> names_of(std::span<const MessageName> messages) {
  std::vector<std::string_view> names;
  for (const MessageName& m : messages) names.push_back(m.name);
  return names;
}

// --- keys of one port type -------------------------------------------------

void read_pty_path(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  PtyPortConfig pty{t.string(f.key, std::nullopt)};
  const toml::node* node = t.find(f.key);
  if (pty.path.empty()) t.fail(*node, t.full_name(f.key) + ": must not be empty");
  if (fs::path(pty.path).is_relative()) {
    t.fail(*node, t.full_name(f.key) + ": pty path '" + pty.path + "' must be absolute");
  }
  port.transport = pty;
}

void write_pty_path(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  w.key(f.key, string_text(std::get<PtyPortConfig>(port.transport).path));
}

void read_file_path(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  FilePortConfig file{t.string(f.key, std::nullopt)};
  if (file.path.empty()) t.fail(*t.find(f.key), t.full_name(f.key) + ": must not be empty");
  file.path = resolve_path(file.path, t.base_dir());
  port.transport = file;
}

void write_file_path(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  w.key(f.key, string_text(w.path_text(std::get<FilePortConfig>(port.transport).path)));
}

void read_device(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  SerialPortConfig serial{t.string(f.key, std::nullopt)};
  if (serial.device.empty() || fs::path(serial.device).is_relative()) {
    t.fail(*t.find(f.key), t.full_name(f.key) + ": serial device '" + serial.device +
                               "' must be an absolute path (e.g. /dev/ttyUSB0)");
  }
  port.transport = serial;
}

void write_device(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  w.key(f.key, string_text(std::get<SerialPortConfig>(port.transport).device));
}

/// One key of one port type.
struct TransportKey {
  PortType type;
  Field<OutputPortConfig> field;
};

// In the order the keys of another type are reported; a type's own keys
// are read and written in this order.
constexpr TransportKey kTransportKeys[] = {
    {PortType::kPty,
     custom<OutputPortConfig>("path", "path", "non-empty, absolute",
                              "pty: stable symlink the daemon creates to the pty (point gpsd here)", read_pty_path,
                              write_pty_path)
         .needed()},
    {PortType::kFile,
     custom<OutputPortConfig>("path", "path", "non-empty",
                              "file: file to write (truncated at start), relative to the config file's folder",
                              read_file_path, write_file_path)
         .needed()},
    {PortType::kSerial,
     custom<OutputPortConfig>("device", "path", "absolute",
                              "serial: device, e.g. `/dev/ttyUSB0`; may be absent at start (the daemon retries)",
                              read_device, write_device)
         .needed()},
    {PortType::kTcp, address<&OutputPortConfig::transport, As<TcpPortConfig>{}, &TcpPortConfig::bind>(
                         "bind", "tcp: listen address")},
    {PortType::kUdp, address<&OutputPortConfig::transport, As<UdpPortConfig>{}, &UdpPortConfig::address>(
                         "address", "udp: destination")
                         .needed()},
    {PortType::kTcp, integer<&OutputPortConfig::transport, As<TcpPortConfig>{}, &TcpPortConfig::port>(
                         "port", 0, 65535, "tcp: listen port (0: any free port, printed at start)")},
    {PortType::kUdp, integer<&OutputPortConfig::transport, As<UdpPortConfig>{}, &UdpPortConfig::port>(
                         "port", 1, 65535, "udp: destination port")
                         .needed()},
};

// The keys of a [[fleet.output]] template: a tcp/udp port is port_base,
// the port of index 0 (port = port_base + index); the others as [[output]].
constexpr auto kTemplateTransportKeys = [] {
  std::array<TransportKey, std::size(kTransportKeys)> keys{};
  for (std::size_t i = 0; i < keys.size(); ++i) {
    keys[i] = kTransportKeys[i];
    if (keys[i].field.key != "port") continue;
    keys[i].field.key = "port_base";
    keys[i].field.meaning = keys[i].type == PortType::kTcp
                                ? "tcp: listen port of index 0; vehicle `index` listens on `port_base + index` (0: any free "
                                  "port each)"
                                : "udp: destination port of index 0; vehicle `index` sends to `port_base + index`";
  }
  return keys;
}();

// A key of another port type is an error naming the types that have it.
template <const auto& Keys>
void reject_foreign_keys(TableReader& t, PortType type) {
  std::vector<std::string_view> seen;
  for (const TransportKey& k : Keys) {
    const std::string_view key = k.field.key;
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    std::string owners;
    bool own = false;
    for (const TransportKey& o : Keys) {
      if (o.field.key != key) continue;
      own = own || o.type == type;
      owners += owners.empty() ? "\"" : " or \"";
      owners += port_type_name(o.type);
      owners += '"';
    }
    const toml::node* n = t.find(key);
    if (n == nullptr || own) continue;
    t.fail(*n, t.full_name(key) + ": not used by a port of type \"" + std::string(port_type_name(type)) +
                   "\" (only " + owners + ")");
  }
}

template <const auto& Keys>
void read_type(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  PortType type = PortType::kPty;
  if (const toml::node* n = t.find(f.key)) {
    const std::string name = t.string(f.key, std::nullopt);
    const std::optional<PortType> known = port_type_from_name(name);
    if (!known) {
      t.fail(*n, t.full_name(f.key) + ": '" + name + "' is not one of " +
                     known_names(kChoiceNames<kPortTypes>, ChoiceStyle::kOneOf));
    }
    type = *known;
  }
  reject_foreign_keys<Keys>(t, type);
  port.transport = transport_of(type);
  for (const TransportKey& k : Keys) {
    if (k.type == type) k.field.read(t, k.field, port);
  }
}

template <const auto& Keys>
void write_type(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  w.key(f.key, string_text(port_type_name(port.type())));
  for (const TransportKey& k : Keys) {
    if (k.type == port.type()) k.field.write(w, k.field, port);
  }
}

template <const auto& Keys>
void describe_type(KeyDocs& d, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  KeyDoc type = key_doc(f, port, "", names_doc(kChoiceNames<kPortTypes>));
  type.default_text = "`" + string_text(port_type_name(port.type())) + "`";
  d.add(std::move(type));
  for (const TransportKey& k : Keys) {
    OutputPortConfig typed;
    typed.transport = transport_of(k.type);
    k.field.describe(d, k.field, typed);
  }
}

template <const auto& Keys>
constexpr Field<OutputPortConfig> type_field() {
  Field<OutputPortConfig> row = make_field<OutputPortConfig>(
      "type",
      "pty: pseudo-terminal; serial: a real UART (libserialport, 8N1); tcp: server, every "
      "client gets the stream; udp: datagrams to one destination; file: log of what is sent. "
      "See [ports.md](ports.md). The keys of one type follow (`path` (pty) ... `port` (udp)); "
      "those of another type are errors");
  row.read = read_type<Keys>;
  row.write = write_type<Keys>;
  row.describe = describe_type<Keys>;
  return row;
}

// --- settings of every port ------------------------------------------------

void read_name(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  port.name = t.string(f.key, std::nullopt);
  if (port.name.empty()) t.fail(*t.find(f.key), t.full_name(f.key) + ": must not be empty");
  for (const char ch : port.name) {
    if (static_cast<unsigned char>(ch) <= ' ') {
      t.fail(*t.find(f.key), t.full_name(f.key) + ": '" + port.name + "' contains a space or control character");
    }
  }
}

void write_name(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  w.key(f.key, string_text(port.name));
}

std::string bauds_text() {
  std::string rates;
  for (const uint32_t b : protocol::ubx::kUartBauds) {
    if (!rates.empty()) rates += ' ';
    rates += std::to_string(b);
  }
  return rates;
}

void read_baud(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  const bool line = is_line(port.type());
  port.baud = line ? 9600 : 0;
  const int64_t baud = t.integer(f.key, port.baud, line ? 1 : 0, std::numeric_limits<uint32_t>::max());
  if (baud != 0 && !protocol::ubx::is_ubx_baud(static_cast<uint32_t>(baud))) {
    t.fail(*t.find(f.key), t.full_name(f.key) + ": " + std::to_string(baud) + " is not a standard rate (" +
                               bauds_text() + ")" + (line ? "" : " or 0 (no line budget)"));
  }
  port.baud = static_cast<uint32_t>(baud);
  port.baud_given = t.find(f.key) != nullptr;
}

void write_baud(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  w.key(f.key, std::to_string(port.baud));
}

std::string baud_range() { return bauds_text() + "; 0 only for tcp, udp, file"; }

constexpr Choice<uint16_t> kProtocols[] = {{"ubx", proto::kUbx}, {"nmea", proto::kNmea}};
/// Input may also be RTCM 3 corrections (inProtoMask bit 5).
constexpr Choice<uint16_t> kInProtocols[] = {{"ubx", proto::kUbx}, {"nmea", proto::kNmea}, {"rtcm3", proto::kRtcm3}};

template <const auto& kTable>
uint16_t read_protocols(TableReader& t, std::string_view key, uint16_t def) {
  const std::string name = t.full_name(key);
  uint16_t mask = 0;
  const toml::array* a = t.string_array(
      key, "an array of strings", "protocol names (strings)", [&](const toml::node& e, const std::string& s) {
        uint16_t bit = 0;
        for (const auto& p : kTable) bit = p.name == s ? p.value : bit;
        if (bit == 0) {
          t.fail(e, name + ": unknown protocol '" + s + "' (known: " +
                        known_names(kChoiceNames<kTable>, ChoiceStyle::kOneOf) + ")");
        }
        if ((mask & bit) != 0) t.fail(e, name + ": '" + s + "' listed twice");
        mask = static_cast<uint16_t>(mask | bit);
      });
  return a == nullptr ? def : mask;
}

std::string protocols_text(uint16_t mask) {
  std::vector<std::string_view> names;
  for (const auto& p : kInProtocols) {
    if ((mask & p.value) != 0) names.push_back(p.name);
  }
  return strings_text(names);
}

void read_protocols_in(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  const bool input = has_input(port.type());
  port.protocols_in = read_protocols<kInProtocols>(t, f.key, input ? proto::kUbx | proto::kNmea : 0);
  if (!input && port.protocols_in != 0) {
    t.fail(*t.find(f.key), t.full_name(f.key) + ": a port of type \"" + std::string(port_type_name(port.type())) +
                               "\" has no input; use []");
  }
}

void write_protocols_in(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  w.key(f.key, protocols_text(port.protocols_in));
}

void read_protocols_out(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  port.protocols_out = read_protocols<kProtocols>(t, f.key, proto::kUbx | proto::kNmea);
}

void write_protocols_out(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  w.key(f.key, protocols_text(port.protocols_out));
}

constexpr Field<OutputPortConfig> protocols_in_field() {
  Field<OutputPortConfig> row = custom<OutputPortConfig>(
      "protocols_in", "", "subset of `\"ubx\"`, `\"nmea\"`, `\"rtcm3\"`",
      "input the port accepts (UBX CFG messages and polls, `$PUBX` commands, RTCM 3 corrections: docs/rtk.md); "
      "`\"rtcm3\"` is added to the chip's own (a ZED-F9P takes RTCM 3 on UART1 and UART2 from the factory); "
      "file and udp ports have no input",
      read_protocols_in, write_protocols_in);
  row.doc_default = "pty, serial, tcp: `[\"ubx\", \"nmea\"]`; file, udp: `[]`";
  return row;
}

// --- message set -----------------------------------------------------------

void read_ubx_messages(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  port.ubx_messages.clear();
  const std::string name = t.full_name(f.key);
  const std::span<const MessageName> table = ubx_periodic_messages();
  std::vector<bool> seen(table.size(), false);
  t.string_array(f.key, "an array of strings", "message names (strings)", [&](const toml::node& e, const std::string& s) {
    const auto it = std::find_if(table.begin(), table.end(), [&](const MessageName& m) { return m.name == s; });
    if (it == table.end()) {
      std::string known;
      for (const std::string_view m : names_of(table)) {
        if (!known.empty()) known += ' ';
        known += m;
      }
      t.fail(e, name + ": unknown UBX message '" + s + "' (known: " + known + ")");
    }
    const auto k = static_cast<std::size_t>(it - table.begin());
    if (seen[k]) t.fail(e, name + ": '" + s + "' listed twice");
    seen[k] = true;
  });
  // Stored in epoch order, whatever the order in the file.
  for (std::size_t k = 0; k < seen.size(); ++k) {
    if (seen[k]) port.ubx_messages.push_back({table[k].msg_class, table[k].msg_id, 1});
  }
}

void write_ubx_messages(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  std::vector<std::string_view> names;
  for (const MessageRate& m : port.ubx_messages) names.push_back(message_name(m.msg_class, m.msg_id));
  w.key(f.key, strings_text(names));
}

std::string ubx_message_names() {
  return names_doc(names_of(ubx_periodic_messages())) +
         ", no repeats; MON-RF and SEC-SIG only with `[receiver] generation = \"m9\"` or `\"f9p\"`, NAV-HPPOSECEF, NAV-HPPOSLLH and NAV-RELPOSNED only with `\"f9p\"`, NAV-SVINFO only with `\"m8\"`, "
         "RXM-RAWX and RXM-SFRBX only with `[receiver] raw_data = true`";
}

constexpr Choice<protocol::nmea::NmeaVersion> kNmeaVersions[] = {{"2.1", protocol::nmea::NmeaVersion::k21},
                                                                 {"2.3", protocol::nmea::NmeaVersion::k23},
                                                                 {"4.0", protocol::nmea::NmeaVersion::k40},
                                                                 {"4.10", protocol::nmea::NmeaVersion::k410},
                                                                 {"4.11", protocol::nmea::NmeaVersion::k411}};

void read_sentences(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  const std::string name = t.full_name(f.key);
  protocol::nmea::SentenceSet out;
  const toml::array* a = t.string_array(
      f.key, "an array of strings", "sentence names (strings)", [&](const toml::node& e, const std::string& s) {
        const std::optional<protocol::nmea::Sentence> sentence = protocol::nmea::sentence_by_name(s);
        if (!sentence) t.fail(e, name + ": unknown sentence '" + s + "' (known: GGA RMC GSA GSV VTG GLL GST ZDA GNS GBS)");
        if (out.has(*sentence)) t.fail(e, name + ": '" + s + "' listed twice");
        out.set(*sentence);
      });
  if (a == nullptr) return;
  if (a->empty()) t.fail(*t.find(f.key), name + ": must name at least one sentence");
  port.nmea.sentences = out;
}

void write_sentences(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& port) {
  std::vector<std::string_view> names;
  for (const protocol::nmea::SentenceInfo& info : protocol::nmea::kSentences) {
    if (port.nmea.sentences.has(info.sentence)) names.push_back(info.name);
  }
  w.key(f.key, strings_text(names));
}

std::string sentence_names() {
  return "non-empty subset of " + names_doc(names_of(nmea_sentences())) + ", no repeats";
}

// rates = { NAV-SAT = 5, GSV = 2 }: rates other than 1 for listed messages.
void read_rates(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& out) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) return;
  const std::string name = t.full_name(f.key);
  const auto* tbl = n->as_table();
  if (tbl == nullptr) {
    t.fail(*n, name + ": expected a table of message = rate (e.g. { NAV-SAT = 5 }), got " +
                   std::string(type_name(*n)));
  }
  for (const auto& [key, value] : *tbl) {
    const std::string msg(key.str());
    const std::string what = name + "." + msg;
    const std::optional<MessageName> m = message_by_name(msg);
    if (!m) t.fail(value, what + ": unknown message '" + msg + "'");
    const auto* v = value.as_integer();
    if (v == nullptr) t.fail(value, what + ": expected an integer, got " + std::string(type_name(value)));
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

// An inline table of the rates other than 1; none: no key.
void write_rates(TomlWriter& w, const Field<OutputPortConfig>& f, const OutputPortConfig& p) {
  std::string out;
  const auto add = [&out](const MessageRate& m) {
    if (m.rate == 1) return;
    out += out.empty() ? "{ " : ", ";
    out += std::string(message_name(m.msg_class, m.msg_id)) + " = " + std::to_string(m.rate);
  };
  for (const MessageRate& m : p.ubx_messages) add(m);
  for (const MessageRate& m : p.nmea_rates) add(m);
  if (!out.empty()) w.key(f.key, out + " }", f.note);
}

constexpr Field<OutputPortConfig> rates_field() {
  Field<OutputPortConfig> row = custom<OutputPortConfig>(
      "rates", "epochs", "inline table, values integer [1, 255]",
      "send a message only every N navigation epochs (u-blox CFG-MSG rate), e.g. `rates = { NAV-SAT = 5, GSV = 5 }`; "
      "each key must be in `ubx_messages` or `sentences`",
      read_rates, write_rates);
  row.note = "epochs per message";
  row.doc_default = "all 1";
  return row;
}

void read_nmea_version(TableReader& t, const Field<OutputPortConfig>& f, OutputPortConfig& port) {
  read_choice<OutputPortConfig, kNmeaVersions, ChoiceStyle::kOneOf>(t, f, port);
  port.nmea_version_given = t.find(f.key) != nullptr;
}

constexpr Field<OutputPortConfig> nmea_version_field(std::string_view meaning) {
  Field<OutputPortConfig> row =
      choice<kNmeaVersions, &OutputPortConfig::nmea, &protocol::nmea::NmeaConfig::version>("nmea_version", meaning);
  row.read = read_nmea_version;
  return row.default_doc("the chip's factory version: `4.0` for `m8`, `4.10` for `m9` and `f9p` (as the real logs)");
}

constexpr Field<OutputPortConfig> kOutputFields[] = {
    custom<OutputPortConfig>("name", "", "non-empty, no spaces", "name in logs; unique", read_name, write_name)
        .needed(),
    type_field<kTransportKeys>(),
    custom<OutputPortConfig>("baud", "bit/s", baud_range,
                             "line rate: applied on a serial port, recorded on a pty; sets the per-epoch byte budget "
                             "(10 bits per byte); 0 = no line, no budget",
                             read_baud, write_baud)
        .default_doc("pty, serial: the chip's UART1 factory rate, `9600` (`m8`) or `38400` (`m9`, `f9p`); others `0`"),
    protocols_in_field(),
    custom<OutputPortConfig>("protocols_out", "", "subset of `\"ubx\"`, `\"nmea\"`",
                             "protocols the port may send (u-blox outProtoMask); hosts change it with CFG-PRT or "
                             "`$PUBX,41`",
                             read_protocols_out, write_protocols_out),
    custom<OutputPortConfig>("ubx_messages", "", ubx_message_names,
                             "periodic UBX messages at rate 1 (u-blox factory default: none); hosts change them with "
                             "CFG-MSG",
                             read_ubx_messages, write_ubx_messages),
    nmea_version_field(
        "NMEA 0183 version of the sentences (must be a string: `4.11` unquoted is a float and "
                        "rejected); the chip's CFG-NMEA (one per chip) reports the first output's, and a host's "
                        "CFG-NMEA changes every output's"),
    custom<OutputPortConfig>("sentences", "", sentence_names,
                             "sentences sent each epoch; the order in the file does not matter, they go out in "
                             "u-blox order",
                             read_sentences, write_sentences),
    number<&OutputPortConfig::nmea, &protocol::nmea::NmeaConfig::course_min_speed_m_s>(
        "course_min_speed_m_s", Range{0.0, 10.0, "m/s"},
        "below this horizontal speed the RMC/VTG course is left empty, as u-blox does; 0 always prints it"),
    rates_field(),
};

}  // namespace

// The file or device a port claims for itself ("" for network ports).
std::string claimed_path(const PortTransport& transport) {
  if (const auto* pty = std::get_if<PtyPortConfig>(&transport)) return pty->path;
  if (const auto* file = std::get_if<FilePortConfig>(&transport)) return file->path;
  if (const auto* serial = std::get_if<SerialPortConfig>(&transport)) return serial->device;
  return {};
}

// [[fleet.output]]: the rows of [[output]] with the template's port keys.
constexpr auto kFleetOutputFields = [] {
  std::array<Field<OutputPortConfig>, std::size(kOutputFields)> rows{};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i] = kOutputFields[i].key == "type" ? type_field<kTemplateTransportKeys>() : kOutputFields[i];
  }
  return rows;
}();

// [[base.output]]: the rows of [[output]] a port carrying the base's RTCM
// stream has (it takes no input and has no message set of its own).
constexpr auto kBaseOutputFields = [] {
  std::array<Field<OutputPortConfig>, 3> rows{};
  std::size_t n = 0;
  for (const Field<OutputPortConfig>& f : kOutputFields) {
    if (f.key == "name" || f.key == "type" || f.key == "baud") rows[n++] = f;
  }
  return rows;
}();

constexpr Section<OutputPortConfig> kOutputKeys{kOutputFields};
constexpr Section<OutputPortConfig> kFleetOutputKeys{kFleetOutputFields};
constexpr Section<OutputPortConfig> kBaseOutputKeys{kBaseOutputFields};

void check_unique_port(TableReader& t, const std::vector<OutputPortConfig>& before, const OutputPortConfig& port) {
  for (const OutputPortConfig& prev : before) {
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
}

void check_output_generation(TableReader& t, const Field<Config>&, Config& c) {
  for (OutputPortConfig& p : c.outputs) {
    if (!p.baud_given && is_line(p.type())) p.baud = protocol::ubx::DeviceConfig::factory_uart1_baud(c.generation);
    if (!p.nmea_version_given) {
      p.nmea.version = protocol::nmea::factory_settings(protocol::ubx::nmea_device(c.generation)).version;
    }
  }
  for (std::size_t i = 0; i < c.outputs.size(); ++i) {
    for (const MessageRate& m : c.outputs[i].ubx_messages) {
      const protocol::ubx::MsgId id{m.msg_class, m.msg_id};
      const auto row = protocol::ubx::periodic_message(id);
      const bool raw_missing = row && row->raw && !c.raw_data;
      if (protocol::ubx::message_exists(id, c.generation) && !raw_missing) continue;
      const std::string_view g = protocol::ubx::generation_name(c.generation);
      const std::string_view name = message_name(m.msg_class, m.msg_id);
      const std::string reason =
          "output[" + std::to_string(i) + "].ubx_messages: a u-blox " + std::string(g) + " has no " +
          std::string(name) +
          (raw_missing ? " without raw-data firmware ([receiver] raw_data = true; docs/raw-output.md)"
                       : " ([receiver] generation = \"" + std::string(g) + "\"; docs/ubx.md \"Generations\")");
      // At the array element naming it, through the readers that read it (only on
      // this error path, so the key log of a good file stays as read).
      std::vector<TableReader> outs = t.table_array("output");
      if (i >= outs.size()) throw Error(t.file(), t.line(), reason);
      outs[i].string_array("ubx_messages", "", "", [&](const toml::node& e, const std::string& s) {
        if (s == name) outs[i].fail(e, reason);
      });
      throw Error(t.file(), outs[i].line(), reason);
    }
  }
}

}  // namespace detail

}  // namespace gnssemu::config

// SPDX-License-Identifier: Apache-2.0
// [[vehicle]], [[vehicle.receiver]] and [fleet]: the vehicles one daemon
// runs, their receivers (the keys of [receiver] merged over the top level's)
// and their ports, with the checks that need all of them at once: unique
// ids and names, and no path or port claimed twice after the fleet's
// templates are expanded.
#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <variant>

#include "config/keys/config_keys.hpp"
#include "config/setup/device_setup.hpp"
#include "config/receiver_config.hpp"

namespace gnssemu::config {

ReceiverSettings receiver_settings(const Config& c) {
  return {c.rate_hz, c.world, c.receiver, c.generation, c.raw_data, c.state_file, c.profile};
}

Config receiver_config(const Config& top, const VehicleConfig& v, const VehicleReceiverConfig& r) {
  Config rc = with_receiver_settings(top, r.settings);
  rc.outputs = r.outputs;
  rc.truth.vehicle = v.id;
  rc.vehicles.clear();
  rc.fleet.reset();
  return rc;
}

Config with_receiver_settings(Config c, const ReceiverSettings& settings) {
  c.rate_hz = settings.rate_hz;
  c.world = settings.world;
  c.receiver = settings.receiver;
  c.generation = settings.generation;
  c.raw_data = settings.raw_data;
  c.state_file = settings.state_file;
  c.profile = settings.profile;
  return c;
}

namespace {

constexpr std::string_view kVehicleToken = "{vehicle}";
constexpr std::string_view kReceiverToken = "{receiver}";
constexpr std::string_view kIndexToken = "{index}";

void replace_all(std::string& text, std::string_view token, const std::string& value) {
  for (std::size_t at = text.find(token); at != std::string::npos; at = text.find(token, at + value.size())) {
    text.replace(at, token.size(), value);
  }
}

std::string expanded(std::string text, const std::string& vehicle, const std::string& receiver, int index) {
  replace_all(text, kVehicleToken, vehicle);
  replace_all(text, kReceiverToken, receiver);
  replace_all(text, kIndexToken, std::to_string(index));
  return text;
}

// Vehicle `index` of the fleet's port from template t.
OutputPortConfig expand_port(const OutputPortConfig& t, const std::string& vehicle, const std::string& receiver,
                             int index) {
  OutputPortConfig p = t;
  p.name = expanded(t.name, vehicle, receiver, index);
  std::visit(
      [&](auto& tr) {
        using T = std::decay_t<decltype(tr)>;
        if constexpr (std::is_same_v<T, PtyPortConfig> || std::is_same_v<T, FilePortConfig>) {
          tr.path = expanded(tr.path, vehicle, receiver, index);
        } else if constexpr (std::is_same_v<T, SerialPortConfig>) {
          tr.device = expanded(tr.device, vehicle, receiver, index);
        } else if constexpr (std::is_same_v<T, TcpPortConfig>) {
          if (tr.port != 0) tr.port = static_cast<uint16_t>(tr.port + index);  // 0: any free port each
        } else {
          tr.port = static_cast<uint16_t>(tr.port + index);
        }
      },
      p.transport);
  return p;
}

std::string fleet_vehicle_id(int index) { return "v" + std::to_string(index); }

}  // namespace

std::vector<VehicleConfig> resolve_vehicles(const Config& c) {
  if (c.vehicles.empty() && !c.fleet) {
    VehicleReceiverConfig r{std::string(kDefaultReceiverName), Vec3{}, receiver_settings(c), c.outputs};
    return {VehicleConfig{c.truth.vehicle, {std::move(r)}, {}}};
  }
  std::vector<VehicleConfig> out = c.vehicles;
  if (c.fleet) {
    const ReceiverSettings settings = receiver_settings(c);
    const std::string receiver(kDefaultReceiverName);
    for (int i = 0; i < c.fleet->count; ++i) {
      VehicleReceiverConfig r{receiver, Vec3{}, settings, {}};
      // One sky (the top level's seed) over receivers with their own noise,
      // multipath and clock: vehicle i's are seed + i.
      r.settings.world.sky_seed = world::sky_seed(settings.world);
      r.settings.world.seed = settings.world.seed + static_cast<uint64_t>(i);
      const std::string id = fleet_vehicle_id(i);
      for (const OutputPortConfig& t : c.fleet->outputs) r.outputs.push_back(expand_port(t, id, receiver, i));
      out.push_back(VehicleConfig{id, {std::move(r)}, {}});
    }
  }
  return out;
}

namespace detail {

namespace {

// A vehicle id or receiver name: it is a packet's id and appears in paths,
// port names and control targets ("v3/gps2").
std::string name_problem(const std::string& s) {
  if (s.empty()) return "must not be empty";
  if (s.size() > 64) return "longer than a packet's vehicle id (64 bytes)";
  for (const char ch : s) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_' ||
                    ch == '-' || ch == '.';
    if (!ok) return "'" + s + "' may hold only letters, digits, '_', '-' and '.'";
  }
  return {};
}

constexpr std::string_view kNameRange = "1..64 letters, digits, `_`, `-`, `.`";

std::string read_name_key(TableReader& t, std::string_view key) {
  const toml::node* n = t.find(key);
  if (n == nullptr) t.fail_missing(key, "key");
  const std::string s = t.string(key, std::nullopt);
  if (const std::string why = name_problem(s); !why.empty()) t.fail(*n, t.full_name(key) + ": " + why);
  return s;
}

// --- [[vehicle]] -------------------------------------------------------------

void read_vehicle_id(TableReader& t, const Field<VehicleConfig>& f, VehicleConfig& v) { v.id = read_name_key(t, f.key); }
void write_vehicle_id(TomlWriter& w, const Field<VehicleConfig>& f, const VehicleConfig& v) {
  w.key(f.key, string_text(v.id));
}

void read_vehicle_allow(TableReader& t, const Field<VehicleConfig>& f, VehicleConfig& v) {
  read_address_blocks(t, f.key, v.allow);
}
void write_vehicle_allow(TomlWriter& w, const Field<VehicleConfig>& f, const VehicleConfig& v) {
  if (!v.allow.empty()) w.key(f.key, address_blocks_text(v.allow), f.note);
}

constexpr Field<VehicleConfig> kVehicleFields[] = {
    custom<VehicleConfig>("id", "", kNameRange,
                          "the `vehicle` of its truth packets (docs/truth-protocol.md); unique among `[[vehicle]]` "
                          "and the fleet's `v0` ..",
                          read_vehicle_id, write_vehicle_id)
        .needed(),
    custom<VehicleConfig>("allow", "", "addresses, CIDR blocks",
                          "senders whose packets may drive this vehicle, e.g. `[\"10.0.0.7\"]` (its simulator), "
                          "checked after `[truth] allow`; packets for it from others are dropped and counted as "
                          "`not_allowed` in its drops. Unset: any sender `[truth] allow` accepts",
                          read_vehicle_allow, write_vehicle_allow)
        .default_doc("unset"),
};
constexpr Section<VehicleConfig> kVehicle{kVehicleFields};

// --- [[vehicle.receiver]] ----------------------------------------------------

void read_receiver_name(TableReader& t, const Field<VehicleReceiverConfig>& f, VehicleReceiverConfig& r) {
  r.name = read_name_key(t, f.key);
}
void write_receiver_name(TomlWriter& w, const Field<VehicleReceiverConfig>& f, const VehicleReceiverConfig& r) {
  w.key(f.key, string_text(r.name));
}

void read_lever_arm(TableReader& t, const Field<VehicleReceiverConfig>& f, VehicleReceiverConfig& r) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) return;
  const std::string name = t.full_name(f.key);
  const auto* a = n->as_array();
  if (a == nullptr || a->size() != 3) t.fail(*n, name + ": expected [forward_m, right_m, down_m]");
  std::array<double, 3> v{};
  for (std::size_t i = 0; i < 3; ++i) {
    const auto x = a->get(i)->value<double>();
    if (!x || !(*x >= -kMaxLeverArmM && *x <= kMaxLeverArmM)) {
      t.fail(*a->get(i), name + ": components must be numbers within ±" + format_number(kMaxLeverArmM) + " m");
    }
    v[i] = *x;
  }
  r.lever_arm_m = Vec3(v[0], v[1], v[2]);
}

void write_lever_arm(TomlWriter& w, const Field<VehicleReceiverConfig>& f, const VehicleReceiverConfig& r) {
  const Vec3& a = r.lever_arm_m;
  w.key(f.key, "[" + number_text(a.x) + ", " + number_text(a.y) + ", " + number_text(a.z) + "]", f.note);
}

constexpr Field<VehicleReceiverConfig> kVehicleReceiverFields[] = {
    custom<VehicleReceiverConfig>("name", "", kNameRange,
                                  "the receiver's name on its vehicle (unique there): logs, status, `{receiver}` in "
                                  "templates",
                                  read_receiver_name, write_receiver_name)
        .needed(),
    custom<VehicleReceiverConfig>("lever_arm_m", "m", "[forward, right, down], each in [-100, 100]",
                                  "antenna in the body frame (forward, right, down), applied with the truth's "
                                  "attitude",
                                  read_lever_arm, write_lever_arm)
        .default_doc("`[0.0, 0.0, 0.0]`"),
};
constexpr Section<VehicleReceiverConfig> kVehicleReceiver{kVehicleReceiverFields};

constexpr std::string_view kReceiverTakes =
    "a [[vehicle.receiver]] takes name, lever_arm_m, [[vehicle.receiver.output]] and the keys of [receiver]";

// The rows of [receiver] on this table, over a copy of the top level's
// settings: what it gives overrides them, the rest stays.
ReceiverSettings read_overrides(TableReader& r, const Config& top) {
  Config own = with_receiver_settings(Config{}, receiver_settings(top));
  own.origin = top.origin;  // a profile's models depend on the latitude
  // The sky's processes (satellites, atmosphere) keep the top level's seed;
  // a seed here is the receiver's own noise, multipath and clock.
  own.world.sky_seed = world::sky_seed(top.world);
  for (const Field<Config>& f : kReceiverKeys.fields) f.read(r, f, own);
  if (own.world.systems.empty()) own.world.systems = chip_systems(own);  // constellations unset: this chip's set
  validate_at(r.file(), r.line(), [&] {
    world::validate(own.world);
    receiver::validate(own.receiver);
  });
  return receiver_settings(own);
}

VehicleReceiverConfig read_receiver(TableReader& r, const Config& top) {
  VehicleReceiverConfig out;
  for (const Field<VehicleReceiverConfig>& f : kVehicleReceiver.fields) f.read(r, f, out);
  out.settings = read_overrides(r, top);
  for (TableReader& o : r.table_array("output")) {
    OutputPortConfig port;
    read_section(o, kOutputKeys, port);
    check_unique_port(o, out.outputs, port);
    out.outputs.push_back(std::move(port));
  }
  Config ports = with_receiver_settings(Config{}, out.settings);
  ports.outputs = out.outputs;
  check_output_generation(r, Field<Config>{}, ports);
  out.outputs = std::move(ports.outputs);  // with the generation's line rates
  r.finish(kReceiverTakes);
  return out;
}

}  // namespace

void read_vehicles(TableReader& t, const Field<Config>& f, Config& c) {
  c.vehicles.clear();
  for (TableReader& v : t.table_array(f.key)) {
    VehicleConfig vehicle;
    for (const Field<VehicleConfig>& row : kVehicle.fields) row.read(v, row, vehicle);
    for (const VehicleConfig& before : c.vehicles) {
      if (before.id == vehicle.id) v.fail(*v.find("id"), v.full_name("id") + ": '" + vehicle.id + "' is used twice");
    }
    std::vector<TableReader> receivers = v.table_array("receiver");
    if (receivers.empty()) v.fail_missing("receiver", "table");
    for (TableReader& r : receivers) {
      VehicleReceiverConfig rc = read_receiver(r, c);
      for (const VehicleReceiverConfig& before : vehicle.receivers) {
        if (before.name == rc.name) {
          r.fail(*r.find("name"), r.full_name("name") + ": '" + rc.name + "' is used twice on vehicle '" +
                                      vehicle.id + "'");
        }
      }
      vehicle.receivers.push_back(std::move(rc));
    }
    v.finish("a [[vehicle]] takes id and [[vehicle.receiver]]");
    c.vehicles.push_back(std::move(vehicle));
  }
}

void write_vehicles(TomlWriter& w, const Field<Config>& f, const Config& c) {
  const std::string outer = w.table();
  const std::string vehicle = sub_table(w, f.key);
  const std::string receiver = vehicle + ".receiver";
  for (const VehicleConfig& v : c.vehicles) {
    w.set_table(vehicle);
    w.header({}, true);
    write_rows(w, kVehicle, v);
    for (const VehicleReceiverConfig& r : v.receivers) {
      w.set_table(receiver);
      w.header({}, true);
      write_rows(w, kVehicleReceiver, r);
      Config own = with_receiver_settings(Config{}, r.settings);
      write_rows(w, kReceiverKeys, own);  // every key: a reader needs no top level to know them
      for (const OutputPortConfig& o : r.outputs) write_table(w, kOutputKeys, receiver + ".output", {}, o, true);
    }
  }
  w.set_table(outer);
}

void describe_vehicles(KeyDocs& d, const Field<Config>& f, const Config&) {
  d.enter(f.key);
  describe_section(d, kVehicle, VehicleConfig{});
  d.enter("receiver");
  describe_section(d, kVehicleReceiver, VehicleReceiverConfig{});
  KeyDoc any{"<receiver key>", "", "the top level's", "as in `[receiver]`",
             "any key or sub-table of `[receiver]` (`profile`, `generation`, `seed`, `constellations`, "
             "`[vehicle.receiver.errors]` ...) overrides the top level's value for this receiver; a `profile` here "
             "applies over the top level's settings"};
  any.mirror = "receiver";
  d.add(std::move(any));
  d.enter("output", "output");  // the keys of [[output]]
  describe_section(d, kOutputKeys, OutputPortConfig{});
  d.leave();
  d.leave();
  d.leave();
}

namespace {

// --- [fleet] -------------------------------------------------------------------

constexpr Field<FleetConfig> kFleetFields[] = {
    integer<&FleetConfig::count>("count", 1, kMaxFleetCount,
                                 "vehicles `v0` .. `v{count-1}`, one receiver `gps1` each with the top level's "
                                 "`[receiver]`")
        .needed(),
};
constexpr Section<FleetConfig> kFleet{kFleetFields};

// A template's text holds no placeholder but {vehicle}, {receiver}, {index}.
void check_placeholders(TableReader& o, std::string_view key, const std::string& text) {
  for (std::size_t at = text.find('{'); at != std::string::npos; at = text.find('{', at + 1)) {
    const std::size_t end = text.find('}', at);
    const std::string token = text.substr(at, end == std::string::npos ? std::string::npos : end - at + 1);
    if (token == kVehicleToken || token == kReceiverToken || token == kIndexToken) continue;
    o.fail(*o.find(key), o.full_name(key) + ": unknown placeholder '" + token +
                             "' (known: {vehicle}, {receiver}, {index})");
  }
}

// The last vehicle's port stays a port.
void check_port_range(TableReader& o, const OutputPortConfig& port, int count) {
  uint16_t base = 0;
  if (const auto* tcp = std::get_if<TcpPortConfig>(&port.transport)) base = tcp->port;
  if (const auto* udp = std::get_if<UdpPortConfig>(&port.transport)) base = udp->port;
  if (base == 0 || base + count - 1 <= 65535) return;
  o.fail(*o.find("port_base"), o.full_name("port_base") + ": " + std::to_string(base) + " + " +
                                   std::to_string(count - 1) + " (the last vehicle's index) is above 65535");
}

}  // namespace

void read_fleet(TableReader& t, const Field<Config>& f, Config& c) {
  c.fleet.reset();
  std::optional<TableReader> ft = t.table(f.key, false);
  if (!ft) return;
  FleetConfig fleet;
  for (const Field<FleetConfig>& row : kFleet.fields) row.read(*ft, row, fleet);
  for (TableReader& o : ft->table_array("output")) {
    if (const toml::node* n = o.peek("port")) {
      o.fail(*n, o.full_name("port") + ": a template has port_base (vehicle index gets port_base + index)");
    }
    OutputPortConfig port;
    read_section(o, kFleetOutputKeys, port);
    check_placeholders(o, "name", port.name);
    const std::string path = claimed_path(port.transport);
    if (!path.empty()) check_placeholders(o, port.type() == PortType::kSerial ? "device" : "path", path);
    check_port_range(o, port, fleet.count);
    check_unique_port(o, fleet.outputs, port);
    fleet.outputs.push_back(std::move(port));
  }
  Config ports = c;
  ports.outputs = fleet.outputs;
  check_output_generation(*ft, Field<Config>{}, ports);
  fleet.outputs = std::move(ports.outputs);  // with the generation's line rates
  ft->finish("[fleet] takes count and [[fleet.output]]");
  for (int i = 0; i < fleet.count; ++i) {
    for (const VehicleConfig& v : c.vehicles) {
      if (v.id != fleet_vehicle_id(i)) continue;
      ft->fail(*ft->find("count"), ft->full_name("count") + ": the fleet's vehicle '" + v.id +
                                       "' is also a [[vehicle]] id");
    }
  }
  c.fleet = std::move(fleet);
}

void write_fleet(TomlWriter& w, const Field<Config>& f, const Config& c) {
  if (!c.fleet) return;
  const std::string outer = w.table();
  const std::string path = sub_table(w, f.key);
  write_table(w, kFleet, path, f.note, *c.fleet);
  for (const OutputPortConfig& o : c.fleet->outputs) write_table(w, kFleetOutputKeys, path + ".output", {}, o, true);
  w.set_table(outer);
}

void describe_fleet(KeyDocs& d, const Field<Config>& f, const Config&) {
  d.enter(f.key);
  describe_section(d, kFleet, FleetConfig{});
  d.enter("output");
  describe_section(d, kFleetOutputKeys, OutputPortConfig{});
  d.leave();
  d.leave();
}

namespace {

// --- what they claim together --------------------------------------------------

const toml::node* child(const toml::node* n, std::string_view key) {
  const toml::table* t = n != nullptr ? n->as_table() : nullptr;
  return t != nullptr ? t->get(key) : nullptr;
}

const toml::node* item(const toml::node* n, std::size_t i) {
  const toml::array* a = n != nullptr ? n->as_array() : nullptr;
  return a != nullptr && i < a->size() ? a->get(i) : nullptr;
}

// Paths, devices, tcp ports and udp destinations, each at most once in the
// daemon (a udp destination may repeat on one receiver).
class Claims {
public:
  Claims(TableReader& root, const Config& c) : root_(root) {
    if (c.status.port != 0 && !c.status.free_port) owner_["tcp " + std::to_string(c.status.port)] = {"the status page", ""};
  }

  // port of receiver (who: "vehicle 'x' receiver 'y'"), its table node at.
  void add(const OutputPortConfig& port, const std::string& who, const toml::node* at, std::string_view port_key) {
    const std::string owner = who + " output '" + port.name + "'";
    if (const std::string path = claimed_path(port.transport); !path.empty()) {
      claim("path " + path, owner, who, false, at, port.type() == PortType::kSerial ? "device" : "path",
            "'" + path + "'");
    }
    if (const auto* tcp = std::get_if<TcpPortConfig>(&port.transport); tcp != nullptr && tcp->port != 0) {
      claim("tcp " + std::to_string(tcp->port), owner, who, false, at, port_key,
            "tcp port " + std::to_string(tcp->port));
    }
    if (const auto* udp = std::get_if<UdpPortConfig>(&port.transport)) {
      const std::string dest = udp->address + " port " + std::to_string(udp->port);
      claim("udp " + dest, owner, who, true, at, port_key, "udp destination " + dest);
    }
  }

private:
  struct Owner {
    std::string text;
    std::string receiver;
  };

  void claim(const std::string& what, const std::string& owner, const std::string& receiver, bool same_receiver_ok,
             const toml::node* at, std::string_view key, const std::string& shown) {
    const auto [it, fresh] = owner_.try_emplace(what, Owner{owner, receiver});
    if (fresh || (same_receiver_ok && it->second.receiver == receiver)) return;
    const toml::node* n = child(at, key);
    throw Error(root_.file(), n != nullptr ? line_of(*n) : root_.line(),
                owner + ": " + std::string(key) + ": " + shown + " is already used by " + it->second.text);
  }

  TableReader& root_;
  std::map<std::string, Owner> owner_;
};

}  // namespace

void check_vehicles(TableReader& t, const Field<Config>&, Config& c) {
  if (c.vehicles.empty() && !c.fleet) return;
  if (!c.outputs.empty()) {
    const toml::node* out = item(t.find("output"), 0);
    throw Error(t.file(), out != nullptr ? line_of(*out) : t.line(),
                "output: a top-level [[output]] is the single-vehicle form; with [[vehicle]] or [fleet] give the "
                "ports in [[vehicle.receiver.output]] or [[fleet.output]]");
  }
  if (!c.truth.vehicle.empty()) {
    throw Error(t.file(), line_of(*child(t.find("truth"), "vehicle")),
                "truth.vehicle: picks the vehicle of the single-vehicle form; [[vehicle]] and [fleet] name their own");
  }
  Claims claims(t, c);
  const toml::node* vehicles = t.find("vehicle");
  for (std::size_t i = 0; i < c.vehicles.size(); ++i) {
    const VehicleConfig& v = c.vehicles[i];
    for (std::size_t j = 0; j < v.receivers.size(); ++j) {
      const VehicleReceiverConfig& r = v.receivers[j];
      const toml::node* outs = child(item(child(item(vehicles, i), "receiver"), j), "output");
      const std::string who = "vehicle '" + v.id + "' receiver '" + r.name + "'";
      for (std::size_t k = 0; k < r.outputs.size(); ++k) claims.add(r.outputs[k], who, item(outs, k), "port");
    }
  }
  if (!c.fleet) return;
  const toml::node* templates = child(t.find("fleet"), "output");
  const std::string receiver(kDefaultReceiverName);
  for (int i = 0; i < c.fleet->count; ++i) {
    const std::string id = fleet_vehicle_id(i);
    const std::string who = "vehicle '" + id + "' receiver '" + receiver + "'";
    for (std::size_t k = 0; k < c.fleet->outputs.size(); ++k) {
      claims.add(expand_port(c.fleet->outputs[k], id, receiver, i), who, item(templates, k), "port_base");
    }
  }
}

ReceiverSettings receiver_overrides(TableReader& r, const Config& top) { return read_overrides(r, top); }

}  // namespace detail

}  // namespace gnssemu::config

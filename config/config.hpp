// SPDX-License-Identifier: Apache-2.0
#pragma once
// Typed gnssemu configuration, loaded from TOML with validation. Every bad
// key, type or value is a gnssemu::Error naming "file:line: reason".
// Reference: docs/configuration.md.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "config/address_block.hpp"
#include "core/common/range.hpp"
#include "core/common/vec3.hpp"
#include "core/orbit/constellation.hpp"
#include "core/common/violation.hpp"
#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/protocol/ubx/config/ubx_generation.hpp"
#include "core/protocol/ubx/config/ubx_ports.hpp"
#include "config/base_config.hpp"
#include "core/pipeline/receiver_profile.hpp"
#include "core/receiver/receiver_config.hpp"
#include "core/scene/mesh.hpp"
#include "core/scene/propagator.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/world_config.hpp"
#include "config/control_config.hpp"
#include "config/status_config.hpp"

namespace gnssemu::config {

/// How epochs map to GPS time.
enum class TimeMode {
  kRealtime,  ///< epochs follow the wall clock (shifted into the nav file's span, see start)
  kLockstep,  ///< epochs follow simulation time carried by truth packets
};

struct TimeRanges {
  static constexpr Range output_delay_s{0.0, 0.5, "s"};
};

struct TimeConfig {
  TimeMode mode = TimeMode::kRealtime;
  /// GPS time of the first epoch; empty: today (use_wall_clock_date), or
  /// the nav data's first toe + 1 h.
  std::optional<time::GpsTime> start;
  /// true: GPS time = system clock, today's date (the nav data are moved to
  /// it unless they cover it, [nav] mode); the default without start.
  bool use_wall_clock_date = true;
  /// Measurement epoch to the first byte on the wire, s (TimeRanges); the
  /// daemon's realtime scheduler sends every port's epoch this much later.
  /// A u-blox M8 starts its output about 0.1 s after the epoch (docs/daemon.md).
  double output_delay_s = 0.1;
};

/// Where the satellites come from ([nav], docs/models.md §Orbits for any date).
struct NavConfig {
  std::vector<std::string> files;  ///< RINEX nav files besides Config::nav_file, absolute
  std::string folder;              ///< every RINEX nav file in this folder is read too, absolute; "" none
  std::string almanac_file;        ///< YUMA or SEM almanac for mode almanac, absolute; "" none
  orbit::NavMode mode = orbit::NavMode::kAuto;
};

/// Mode almanac and an almanac file go together.
std::optional<Violation> check_nav(const NavConfig& n);

/// A start time and the wall clock's date exclude each other.
std::optional<Violation> check_start(const TimeConfig& t);

struct TruthInputConfig {
  std::string bind_address = "127.0.0.1";
  uint16_t port = 5500;           ///< 0: pick a free port (logged)
  double timeout_s = 2.0;         ///< no truth for this long -> no fix
  double max_extrapolation_s = 0.5;
  /// Senders accepted (addresses or CIDR blocks); empty: any sender.
  std::vector<AddressBlock> allow;
  /// Vehicle id that drives the receiver; empty: the first vehicle heard.
  std::string vehicle;
};

/// Truth is extrapolated within its timeout: max_extrapolation_s <= timeout_s.
std::optional<Violation> check_extrapolation(const TruthInputConfig& t);

/// Built-in demo trajectory used while no simulator sends truth.
struct DemoConfig {
  bool enabled = true;
  double radius_m = 50.0;         ///< circle around the origin
  double speed_m_s = 5.0;
  double height_m = 0.0;          ///< above the origin
};

/// Port kinds (docs/ports.md), in the order of PortTransport's alternatives.
enum class PortType {
  kPty,     ///< pseudo-terminal with a stable symlink (gpsd, SITL)
  kFile,    ///< log of everything sent (truncated at start)
  kSerial,  ///< real UART through libserialport, 8N1
  kTcp,     ///< TCP server; every client gets the stream, input from all clients
  kUdp,     ///< datagrams to one destination, output only
};

/// What each port type needs besides the settings every port has. The
/// daemon checks each (daemon::validate_port) and sets it up (open_port).
struct PtyPortConfig {
  std::string path;  ///< stable symlink to the pty, absolute (key "path")
  bool operator==(const PtyPortConfig&) const = default;
};
struct FilePortConfig {
  std::string path;  ///< file written, absolute: resolved against the config file's folder (key "path")
  bool operator==(const FilePortConfig&) const = default;
};
struct SerialPortConfig {
  std::string device;  ///< e.g. /dev/ttyUSB0, absolute (key "device")
  bool operator==(const SerialPortConfig&) const = default;
};
struct TcpPortConfig {
  std::string bind = "127.0.0.1";  ///< listen address, IPv4 or IPv6 (key "bind")
  uint16_t port = 0;               ///< listen port; 0: any free one (printed)
  bool operator==(const TcpPortConfig&) const = default;
};
struct UdpPortConfig {
  std::string address;  ///< destination, IPv4 or IPv6 (key "address")
  uint16_t port = 0;    ///< destination port, 1..65535
  bool operator==(const UdpPortConfig&) const = default;
};
using PortTransport = std::variant<PtyPortConfig, FilePortConfig, SerialPortConfig, TcpPortConfig, UdpPortConfig>;

/// The TOML `type` value of a port type: "pty", "file", "serial", "tcp", "udp".
std::string_view port_type_name(PortType type) noexcept;
/// Port type of a TOML `type` value, or nullopt.
std::optional<PortType> port_type_from_name(std::string_view name) noexcept;

/// A periodic message and its rate (u-blox CFG-MSG): sent every `rate`
/// navigation epochs, 0 = off. Standard NMEA sentences are class 0xF0.
struct MessageRate {
  uint8_t msg_class = 0;
  uint8_t msg_id = 0;
  uint8_t rate = 1;
  bool operator==(const MessageRate&) const = default;
};

struct OutputPortConfig {
  std::string name;               ///< unique, for logs
  PortTransport transport;        ///< the port type and its own settings
  /// Line rate, bit/s (8N1: 10 bits per byte). Applied on a serial port,
  /// recorded on a pty; sets the per-epoch byte budget. 0: no line (no
  /// budget), allowed for file/tcp/udp only. Unset on a pty or serial
  /// port: the generation's UART1 factory rate (settled after [receiver]).
  uint32_t baud = 9600;
  bool baud_given = false;  ///< `baud` was in the file
  bool nmea_version_given = false;  ///< `nmea_version` was in the file (else the chip's factory version)
  /// What the port's input accepts and what it sends: u-blox CFG-PRT
  /// inProtoMask / outProtoMask bits (protocol::ubx::proto).
  uint16_t protocols_in = protocol::ubx::proto::kUbx | protocol::ubx::proto::kNmea;
  uint16_t protocols_out = protocol::ubx::proto::kUbx | protocol::ubx::proto::kNmea;
  /// Periodic UBX messages with their rates (u-blox factory default: none),
  /// in config/message_names.hpp order.
  std::vector<MessageRate> ubx_messages;
  protocol::nmea::NmeaConfig nmea;  ///< sentences: the NMEA set
  /// Rates other than 1 for sentences of the set (class 0xF0), in u-blox order.
  std::vector<MessageRate> nmea_rates;

  PortType type() const noexcept { return static_cast<PortType>(transport.index()); }
};

/// The port's full periodic-message table: every UBX message and every
/// NMEA sentence of the set, with its rate (CFG-MSG view).
std::vector<MessageRate> message_rates(const OutputPortConfig& port);

/// What [receiver] sets for one receiver (the keys of kReceiverKeys): the
/// top level's values, overridden by a [[vehicle.receiver]]'s own keys.
struct ReceiverSettings {
  double rate_hz = 1.0;               ///< epoch rate, 1..10 Hz
  world::WorldConfig world;           ///< seed, error processes, clock, systems (and the top level's atmosphere, signal)
  receiver::ReceiverConfig receiver;  ///< solver, filter, acquisition ...
  protocol::ubx::Generation generation = protocol::ubx::Generation::kM8;
  bool raw_data = false;              ///< raw-data firmware (RXM-RAWX, RXM-SFRBX)
  std::string state_file;             ///< absolute; "" none
  std::optional<pipeline::ReceiverProfile> profile;
};

/// One receiver (antenna) on a vehicle ([[vehicle.receiver]]).
struct VehicleReceiverConfig {
  std::string name;  ///< unique on its vehicle; letters, digits, '_', '-', '.'
  /// Antenna in the body frame (forward, right, down), m, each within
  /// ±kMaxLeverArmM; applied with the truth's attitude.
  Vec3 lever_arm_m;
  ReceiverSettings settings;              ///< merged: top level + its own keys
  std::vector<OutputPortConfig> outputs;  ///< its ports ([[vehicle.receiver.output]])
};

/// Largest lever arm component, m.
inline constexpr double kMaxLeverArmM = 100.0;

/// One simulated vehicle ([[vehicle]]); a truth packet's "vehicle" picks it.
struct VehicleConfig {
  std::string id;  ///< a packet's vehicle id (1..64 bytes of letters, digits, '_', '-', '.'); "" = any (single form)
  std::vector<VehicleReceiverConfig> receivers;
  /// Senders whose packets may drive this vehicle (beside [truth] allow); empty: any.
  std::vector<AddressBlock> allow;
};

/// [base]: a static reference receiver sending RTCM 3 (config/base_config.hpp).
struct BaseConfig {
  Lla position;                   ///< antenna reference point (lat/lon rad, ellipsoidal height m)
  int station_id = 0;             ///< RTCM DF003, 0..4095
  double antenna_height_m = 0.0;  ///< 1006 DF028, 0..6.5535 m (the ARP is the position above)
  /// true: the base sees none of [scene]'s buildings (an antenna on a mast
  /// or a surveyed open site); false: it stands in the world's scene at its
  /// position, as the rover does.
  bool open_sky = false;
  ReceiverSettings settings;      ///< merged: top level + [base]'s own receiver keys
  std::vector<BaseMessage> messages;      ///< in the order given
  NtripCasterConfig ntrip;        ///< [base.ntrip]
  /// [[base.output]]: ports carrying the base's RTCM stream as it is made
  /// (no input, protocols_in 0); their names and ports are unique among
  /// every [[output]].
  std::vector<OutputPortConfig> outputs;
  int line = 0;                   ///< line of [base] (for messages)
};

/// Most vehicles of a [fleet].
inline constexpr int kMaxFleetCount = 1000;

/// [fleet]: vehicles "v0" .. "v{count-1}", one receiver "gps1" each, with the
/// top level's receiver settings and ports made from templates.
struct FleetConfig {
  int count = 1;  ///< 1..kMaxFleetCount
  /// [[fleet.output]]: {vehicle}, {receiver} and {index} expand in name and
  /// path (device); a tcp/udp port holds port_base (port = port_base + index).
  std::vector<OutputPortConfig> outputs;
};

struct LogConfig {
  std::string level = "info";     ///< trace, debug, info, warn, error
};

/// Buildings around the origin (docs/scene.md): mesh, placement, search effort.
struct SceneConfig {
  std::string mesh_file;           ///< .obj/.ply/.toml, absolute (resolved against the config file's folder)
  scene::Placement placement;      ///< model -> local ENU of [origin]
  scene::SearchConfig search;      ///< rays, bounces, reuse, arrival mask, loss cap
  double reflection_loss_db = 3.0; ///< every material, dB per reflection
  struct MaterialLoss {
    std::string name;              ///< material name in the mesh (OBJ usemtl, footprint material)
    double loss_db = 3.0;          ///< dB per reflection
    int line = 0;                  ///< config line (for messages)
  };
  std::vector<MaterialLoss> material_loss_db;
};

struct Config {
  std::string source;             ///< file the config came from ("" if built in)
  Lla origin;                     ///< local frame origin (lat/lon rad, height m)
  std::string nav_file;           ///< absolute, or relative to the config file's folder (resolved)
  NavConfig nav;                  ///< more nav data and how to date them
  double rate_hz = 1.0;           ///< epoch rate, 1..10 Hz
  TimeConfig time;
  world::WorldConfig world;       ///< what happens to the signals ([receiver.errors], [receiver.clock], [atmosphere], [signal] ...)
  receiver::ReceiverConfig receiver;  ///< the receiver's own settings ([receiver], [receiver.solver], [receiver.corrections] ...)
  /// [receiver] generation: the u-blox chip the outputs present (MON-VER, CFG-VAL*, MON-RF)
  protocol::ubx::Generation generation = protocol::ubx::Generation::kM8;
  /// [receiver] raw_data: the chip's firmware sends RXM-RAWX and RXM-SFRBX
  /// (an M8T/M8P-class timing or high-precision firmware; docs/raw-output.md)
  bool raw_data = false;
  /// [receiver] state_file: the chip's saved configuration (BBR/flash) across
  /// restarts, absolute; "" none (every start factory-fresh)
  std::string state_file;
  /// [receiver] profile: the profile whose values world and receiver started from
  std::optional<pipeline::ReceiverProfile> profile;
  TruthInputConfig truth;
  DemoConfig demo;
  /// Top-level [[output]]: the single-vehicle form's ports (one vehicle,
  /// truth.vehicle or any, one receiver); empty with vehicles or fleet.
  std::vector<OutputPortConfig> outputs;
  std::vector<VehicleConfig> vehicles;  ///< [[vehicle]], as written (settings merged)
  std::optional<FleetConfig> fleet;     ///< [fleet], templates as written
  std::optional<BaseConfig> base;       ///< [base]: an RTCM reference station
  LogConfig log;
  std::optional<SceneConfig> scene;  ///< no [scene]: no scene stage
  StatusConfig status;            ///< the live status page
  ControlConfig control;          ///< the control socket
};

/// The receiver settings of c's top level ([receiver] and what it holds).
ReceiverSettings receiver_settings(const Config& c);
/// c with settings in place of its top level's receiver settings.
Config with_receiver_settings(Config c, const ReceiverSettings& settings);

/// Name of the one receiver of the single-vehicle form and of each fleet vehicle.
inline constexpr std::string_view kDefaultReceiverName = "gps1";

/// Every vehicle the daemon runs, each with its receivers, their merged
/// settings, lever arms and ports (templates expanded): [[vehicle]] in file
/// order, then the fleet's; else the single-vehicle form (one vehicle with
/// id truth.vehicle, "" = any, and one receiver "gps1" with the top-level
/// [[output]]s). Deterministic; load_config has checked it (unique ids,
/// names, paths and ports).
std::vector<VehicleConfig> resolve_vehicles(const Config& c);

/// Load and validate a TOML file. Relative paths inside are resolved against
/// the file's folder. Throws gnssemu::Error("file:line: reason").
Config load_config(const std::string& path);
/// Parse TOML text; name is used in messages, base_dir for relative paths.
Config parse_config(const std::string& toml_text, const std::string& name, const std::string& base_dir);

/// Text of config/default.toml, embedded at build time.
std::string_view default_config_text();
/// Folder the embedded default's relative paths resolve against (the
/// config/ folder of the source tree, fixed at build time).
std::string default_config_dir();
/// The embedded default parsed against base_dir (empty: default_config_dir()).
/// source is "" (built in). Throws gnssemu::Error if e.g. its nav file is missing.
Config default_config(const std::string& base_dir = {});

/// A loadable TOML text for c (every key written, comments name the units).
/// Paths under relative_to (a folder; empty: none) are written relative to it,
/// others absolute. parse_config(to_toml(c, d), name, d) reproduces a valid c
/// (angles to within 1e-15 rad). Throws gnssemu::Error if c holds a value TOML
/// cannot carry (seed > 2^63 - 1).
std::string to_toml(const Config& c, const std::string& relative_to = {});

}  // namespace gnssemu::config

#pragma once
// Typed gnssemu configuration, loaded from TOML with validation. Every bad
// key, type or value is a gnssemu::Error naming "file:line: reason".
// Reference: docs/configuration.md.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/vec3.hpp"
#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/receiver/receiver_config.hpp"
#include "core/scene/mesh.hpp"
#include "core/scene/propagator.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/world_config.hpp"

namespace gnssemu::config {

/// How epochs map to GPS time.
enum class TimeMode {
  kRealtime,  ///< epochs follow the wall clock (shifted into the nav file's span, see start)
  kLockstep,  ///< epochs follow simulation time carried by truth packets
};

struct TimeConfig {
  TimeMode mode = TimeMode::kRealtime;
  /// GPS time of the first epoch; empty: inside the nav file's coverage
  /// (first toe + 1 h), so shipped historic nav files work at any wall-clock date.
  std::optional<time::GpsTime> start;
  bool use_wall_clock_date = false;  ///< true: GPS time = system clock (needs a current nav file)
};

struct TruthInputConfig {
  std::string bind_address = "127.0.0.1";
  uint16_t port = 5500;           ///< 0: pick a free port (logged)
  double timeout_s = 2.0;         ///< no truth for this long -> no fix
  double max_extrapolation_s = 0.5;
};

/// Built-in demo trajectory used while no simulator sends truth.
struct DemoConfig {
  bool enabled = true;
  double radius_m = 50.0;         ///< circle around the origin
  double speed_m_s = 5.0;
  double height_m = 0.0;          ///< above the origin
};

/// Port kinds (docs/ports.md).
enum class PortType {
  kPty,     ///< pseudo-terminal with a stable symlink (gpsd, SITL)
  kFile,    ///< log of everything sent (truncated at start)
  kSerial,  ///< real UART through libserialport, 8N1
  kTcp,     ///< TCP server; every client gets the stream, input from all clients
  kUdp,     ///< datagrams to one destination, output only
};

/// Protocol bits as in u-blox CFG-PRT inProtoMask / outProtoMask.
inline constexpr uint16_t kProtoUbx = 0x0001;
inline constexpr uint16_t kProtoNmea = 0x0002;

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
  PortType type = PortType::kPty;
  /// pty: stable symlink to create; file: file to write; serial: device
  /// (key "device"); unused for tcp/udp.
  std::string path;
  /// tcp: listen address (key "bind"); udp: destination address (key "address").
  std::string address;
  uint16_t port = 0;              ///< tcp: listen port (0: any free, printed); udp: destination port
  /// Line rate, bit/s (8N1: 10 bits per byte). Applied on a serial port,
  /// recorded on a pty; sets the per-epoch byte budget. 0: no line (no
  /// budget), allowed for file/tcp/udp only.
  uint32_t baud = 9600;
  uint16_t protocols_in = kProtoUbx | kProtoNmea;   ///< what the port's input accepts
  uint16_t protocols_out = kProtoUbx | kProtoNmea;  ///< what the port sends
  /// Periodic UBX messages with their rates (u-blox factory default: none),
  /// in config/message_names.hpp order.
  std::vector<MessageRate> ubx_messages;
  protocol::nmea::NmeaConfig nmea;  ///< sentences: the NMEA set
  /// Rates other than 1 for sentences of the set (class 0xF0), in u-blox order.
  std::vector<MessageRate> nmea_rates;
};

/// The port's full periodic-message table: every UBX message and every
/// NMEA sentence of the set, with its rate (CFG-MSG view).
std::vector<MessageRate> message_rates(const OutputPortConfig& port);

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
  double rate_hz = 1.0;           ///< epoch rate, 1..10 Hz
  TimeConfig time;
  world::WorldConfig world;       ///< what happens to the signals ([receiver.errors], [receiver.clock], [atmosphere], [signal] ...)
  receiver::ReceiverConfig receiver;  ///< the receiver's own settings ([receiver], [receiver.solver], [receiver.corrections] ...)
  TruthInputConfig truth;
  DemoConfig demo;
  std::vector<OutputPortConfig> outputs;
  LogConfig log;
  std::optional<SceneConfig> scene;  ///< no [scene]: no scene stage
};

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

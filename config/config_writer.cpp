// Config -> TOML text that load_config reads back to the same Config.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "config/config.hpp"
#include "config/config_atmosphere.hpp"
#include "config/message_names.hpp"
#include "config/toml_reader.hpp"
#include "core/common/error.hpp"

namespace gnssemu::config {

namespace {

namespace fs = std::filesystem;

// TOML float text; always has a '.' or exponent so it reads back as a float.
std::string number(double v) {
  std::string s = detail::format_number(v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// Degrees text whose reading times kDegToRad gives back rad exactly when a
// nearby double allows it (deg -> rad is not exactly invertible).
std::string degrees(double rad) {
  const double deg = rad * kRadToDeg;
  double candidate = deg;
  for (int i = 0; i < 16; ++i) {
    const double up = std::nextafter(deg, deg + 1.0) - deg;  // one ulp
    for (const double d : {deg + i * up, deg - i * up}) {
      if (d * kDegToRad == rad) return number(d);
    }
  }
  return number(candidate);
}

// TOML basic string with escapes (TOML 1.0 section "String").
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (u < 0x20 || u == 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", u);
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

std::string path_text(const std::string& path, const std::string& relative_to) {
  if (relative_to.empty()) return path;
  const fs::path base = fs::absolute(relative_to).lexically_normal();
  const fs::path rel = fs::path(path).lexically_relative(base);
  if (rel.empty() || *rel.begin() == "..") return path;
  return rel.string();
}

std::string datetime(const time::GpsTime& t) {
  const time::CalendarTime c = t.to_calendar();
  char buf[40];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:", c.year, c.month, c.day, c.hour, c.minute);
  std::string s = buf;
  char sbuf[48];
  const auto res = std::to_chars(sbuf, sbuf + sizeof sbuf, c.second, std::chars_format::fixed);
  std::string sec(sbuf, res.ptr);
  if (c.second < 10.0) sec = "0" + sec;
  return s + sec;
}

std::string nmea_version(protocol::nmea::NmeaVersion v) {
  switch (v) {
    case protocol::nmea::NmeaVersion::k23: return "2.3";
    case protocol::nmea::NmeaVersion::k410: return "4.10";
    case protocol::nmea::NmeaVersion::k411: return "4.11";
  }
  return "4.11";
}

std::string sentences(const protocol::nmea::SentenceSet& s) {
  std::string out = "[";
  for (const protocol::nmea::SentenceInfo& info : protocol::nmea::kSentences) {
    if (!s.has(info.sentence)) continue;
    if (out.size() > 1) out += ", ";
    out += quoted(std::string(info.name));
  }
  return out + "]";
}

// The keys of a port's own type.
std::string transport_keys(const PortTransport& transport, const std::string& relative_to) {
  struct Keys {
    const std::string& relative_to;
    std::string operator()(const PtyPortConfig& pty) const { return "path = " + quoted(pty.path) + "\n"; }
    std::string operator()(const FilePortConfig& file) const {
      return "path = " + quoted(path_text(file.path, relative_to)) + "\n";
    }
    std::string operator()(const SerialPortConfig& serial) const { return "device = " + quoted(serial.device) + "\n"; }
    std::string operator()(const TcpPortConfig& tcp) const {
      return "bind = " + quoted(tcp.bind) + "\nport = " + std::to_string(tcp.port) + "\n";
    }
    std::string operator()(const UdpPortConfig& udp) const {
      return "address = " + quoted(udp.address) + "\nport = " + std::to_string(udp.port) + "\n";
    }
  };
  return std::visit(Keys{relative_to}, transport);
}

std::string protocols(uint16_t mask) {
  std::string out = "[";
  if ((mask & protocol::ubx::proto::kUbx) != 0) out += "\"ubx\"";
  if ((mask & protocol::ubx::proto::kNmea) != 0) out += std::string(out.size() > 1 ? ", " : "") + "\"nmea\"";
  return out + "]";
}

std::string ubx_messages(const std::vector<MessageRate>& list) {
  std::string out = "[";
  for (const MessageRate& m : list) {
    if (out.size() > 1) out += ", ";
    out += quoted(std::string(message_name(m.msg_class, m.msg_id)));
  }
  return out + "]";
}

// Inline table of the rates other than 1 ("" when there are none).
std::string rates(const OutputPortConfig& p) {
  std::string out;
  const auto add = [&out](const MessageRate& m) {
    if (m.rate == 1) return;
    out += out.empty() ? "{ " : ", ";
    out += std::string(message_name(m.msg_class, m.msg_id)) + " = " + std::to_string(m.rate);
  };
  for (const MessageRate& m : p.ubx_messages) add(m);
  for (const MessageRate& m : p.nmea_rates) add(m);
  return out.empty() ? out : out + " }";
}

}  // namespace

std::string to_toml(const Config& c, const std::string& relative_to) {
  const receiver::ReceiverConfig& r = c.receiver;
  const world::WorldConfig& w = c.world;
  if (w.seed > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) {
    throw Error("receiver.seed " + std::to_string(w.seed) + " does not fit a TOML integer (max 2^63 - 1)");
  }
  std::string o;
  o += "# gnssemu configuration. Keys, units and ranges: docs/configuration.md\n";
  o += "\n[origin]  # local frame origin, WGS-84\n";
  o += "lat_deg = " + degrees(c.origin.lat_rad) + "\n";
  o += "lon_deg = " + degrees(c.origin.lon_rad) + "\n";
  o += "height_m = " + number(c.origin.height_m) + "  # above the ellipsoid\n";

  o += "\n[nav]\n";
  o += "file = " + quoted(path_text(c.nav_file, relative_to)) + "\n";

  o += "\n[time]\n";
  o += "mode = " + quoted(c.time.mode == TimeMode::kLockstep ? "lockstep" : "realtime") + "\n";
  if (c.time.start) o += "start = " + quoted(datetime(*c.time.start)) + "  # GPS time scale\n";
  o += std::string("use_wall_clock_date = ") + (c.time.use_wall_clock_date ? "true" : "false") + "\n";

  o += "\n[receiver]\n";
  o += "rate_hz = " + number(c.rate_hz) + "\n";
  o += "elevation_mask_deg = " + degrees(r.elevation_mask_rad) + "\n";
  o += "seed = " + std::to_string(w.seed) + "\n";
  o += "nominal_cn0_dbhz = " + number(w.nominal_cn0_dbhz) + "\n";
  o += "max_pdop = " + number(r.max_pdop) + "\n";
  o += "max_channels = " + std::to_string(r.max_channels) + "\n";
  o += "\n[receiver.errors]\n";
  o += "thermal_model = \"" + detail::thermal_model_name(w.errors.thermal_model) + "\"\n";
  o += "thermal_sigma_m = " + number(w.errors.thermal_sigma_m) + "\n";
  o += "doppler_sigma_m_s = " + number(w.errors.doppler_sigma_m_s) + "\n";
  o += "\n[receiver.errors.orbit_clock]  # first-order Gauss-Markov\n";
  o += "sigma_m = " + number(w.errors.orbit_clock.sigma_m) + "\n";
  o += "tau_s = " + number(w.errors.orbit_clock.tau_s) + "\n";
  o += "\n[receiver.errors.multipath]  # unit Gauss-Markov x sigma_m / sin(el); sigma_m 0 = off\n";
  o += "sigma_m = " + number(w.errors.multipath.sigma_m) + "\n";
  o += "tau_s = " + number(w.errors.multipath.tau_s) + "\n";
  o += "\n[receiver.errors.gradient]  # delay += G_N cos(az) + G_E sin(az); G_N = north_m + "
       "north_diurnal_m cos(2 pi (LT - north_peak_h) / 24 h) + g_N (E alike); g: Gauss-Markov\n";
  o += "north_m = " + number(w.errors.gradient.north_m) + "\n";
  o += "east_m = " + number(w.errors.gradient.east_m) + "\n";
  o += "north_diurnal_m = " + number(w.errors.gradient.north_diurnal_m) + "\n";
  o += "north_peak_h = " + number(w.errors.gradient.north_peak_h) + "\n";
  o += "east_diurnal_m = " + number(w.errors.gradient.east_diurnal_m) + "\n";
  o += "east_peak_h = " + number(w.errors.gradient.east_peak_h) + "\n";
  o += "sigma_m = " + number(w.errors.gradient.process.sigma_m) + "\n";
  o += "tau_s = " + number(w.errors.gradient.process.tau_s) + "\n";
  o += "\n[receiver.clock]\n";
  o += "bias_s = " + number(w.clock.bias_s) + "\n";
  o += "drift_s_s = " + number(w.clock.drift_s_s) + "\n";
  o += "drift_noise_s_s_sqrt_s = " + number(w.clock.drift_noise_s_s_sqrt_s) + "\n";
  o += "jump_threshold_s = " + number(w.clock.jump_threshold_s) + "\n";
  o += "\n[receiver.solver]  # what the receiver's own solver assumes\n";
  o += "sigma_a_m = " + number(r.solver.sigma_a_m) + "\n";
  o += "sigma_b_m = " + number(r.solver.sigma_b_m) + "\n";
  o += "sigma_c_m_sqrt_hz = " + number(r.solver.sigma_c_m_sqrt_hz) + "\n";
  o += "iono_model_fraction = " + number(r.solver.iono_model_fraction) + "\n";
  o += "tropo_model_sigma_m = " + number(r.solver.tropo_model_sigma_m) + "\n";
  o += "sigma_range_rate_m_s = " + number(r.solver.sigma_range_rate_m_s) + "\n";
  o += "height_hold_sigma_m = " + number(r.solver.height_hold_sigma_m) + "\n";
  o += "residual_test_pfa = " + number(r.solver.residual_test_pfa) + "\n";
  o += "max_exclusions = " + std::to_string(r.solver.max_exclusions) + "\n";
  o += "max_iterations = " + std::to_string(r.solver.max_iterations) + "\n";
  o += detail::corrections_toml(r.solver, number);
  o += detail::atmosphere_toml(w, number);
  o += detail::signal_toml(w, r, number);

  o += "\n[truth]  # UDP truth input\n";
  o += "bind = " + quoted(c.truth.bind_address) + "\n";
  o += "port = " + std::to_string(c.truth.port) + "\n";
  o += "timeout_s = " + number(c.truth.timeout_s) + "\n";
  o += "max_extrapolation_s = " + number(c.truth.max_extrapolation_s) + "\n";

  o += "\n[demo]  # circle around the origin while no truth arrives\n";
  o += std::string("enabled = ") + (c.demo.enabled ? "true" : "false") + "\n";
  o += "radius_m = " + number(c.demo.radius_m) + "\n";
  o += "speed_m_s = " + number(c.demo.speed_m_s) + "\n";
  o += "height_m = " + number(c.demo.height_m) + "\n";

  for (const OutputPortConfig& p : c.outputs) {
    o += "\n[[output]]\n";
    o += "name = " + quoted(p.name) + "\n";
    o += "type = " + quoted(std::string(port_type_name(p.type()))) + "\n";
    o += transport_keys(p.transport, relative_to);
    o += "baud = " + std::to_string(p.baud) + "\n";
    o += "protocols_in = " + protocols(p.protocols_in) + "\n";
    o += "protocols_out = " + protocols(p.protocols_out) + "\n";
    o += "ubx_messages = " + ubx_messages(p.ubx_messages) + "\n";
    o += "nmea_version = " + quoted(nmea_version(p.nmea.version)) + "\n";
    o += "sentences = " + sentences(p.nmea.sentences) + "\n";
    o += "course_min_speed_m_s = " + number(p.nmea.course_min_speed_m_s) + "\n";
    if (const std::string rt = rates(p); !rt.empty()) o += "rates = " + rt + "  # epochs per message\n";
  }

  if (c.scene) {
    const SceneConfig& s = *c.scene;
    o += "\n[scene]  # buildings, docs/scene.md\n";
    o += "mesh = " + quoted(path_text(s.mesh_file, relative_to)) + "\n";
    o += "offset_m = [" + number(s.placement.offset_m.x) + ", " + number(s.placement.offset_m.y) + ", " +
         number(s.placement.offset_m.z) + "]  # model origin in local ENU\n";
    o += "yaw_deg = " + degrees(s.placement.yaw_rad) + "  # counter-clockwise from east\n";
    o += "scale = " + number(s.placement.scale) + "\n";
    o += "up_axis = " + quoted(s.placement.y_up ? "y" : "z") + "\n";
    o += "rays = " + std::to_string(s.search.rays) + "\n";
    o += "azimuth_rays = " + std::to_string(s.search.azimuth_rays) + "  # per blocked satellite, vertical/horizontal scenes\n";
    o += "max_bounces = " + std::to_string(s.search.max_bounces) + "\n";
    o += "match_factor = " + number(s.search.match_factor) + "\n";
    o += "reuse_distance_m = " + number(s.search.reuse_distance_m) + "\n";
    o += "reuse_angle_deg = " + degrees(s.search.reuse_angle_rad) + "\n";
    o += "min_arrival_elevation_deg = " + degrees(s.search.min_arrival_el_rad) + "\n";
    o += "max_loss_db = " + number(s.search.max_loss_db) + "\n";
    o += "reflection_loss_db = " + number(s.reflection_loss_db) + "\n";
    if (!s.material_loss_db.empty()) {
      o += "\n[scene.material_loss_db]\n";
      for (const SceneConfig::MaterialLoss& m : s.material_loss_db) o += quoted(m.name) + " = " + number(m.loss_db) + "\n";
    }
  }

  o += "\n[log]\n";
  o += "level = " + quoted(c.log.level) + "\n";
  return o;
}

}  // namespace gnssemu::config

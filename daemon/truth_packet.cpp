#include "daemon/truth_packet.hpp"

#include <array>
#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"

namespace gnssemu::daemon {
namespace {

using nlohmann::json;

constexpr std::array kReasonNames = {
    "too_large",          "malformed_json",     "not_an_object",   "missing_version",
    "unknown_version",    "missing_field",      "bad_type",        "non_finite",
    "missing_position",   "duplicate_position", "duplicate_velocity", "duplicate_key",      "latitude_range",
    "longitude_range",    "height_range",       "speed_range",     "bad_gps_time",
    "bad_vehicle_id",     "sim_time_backwards", "too_many_vehicles",
};
static_assert(kReasonNames.size() == kDropReasonCount, "one name per DropReason");

ParseResult drop(DropReason reason, std::string detail) {
  ParseResult r;
  r.ok = false;
  r.reason = reason;
  r.detail = std::move(detail);
  return r;
}

// Reads obj[key] as a finite number. Returns false and fills err on failure.
bool read_number(const json& obj, const char* key, const std::string& where, double& out,
                 ParseResult& err) {
  auto it = obj.find(key);
  if (it == obj.end()) {
    err = drop(DropReason::kMissingField, where + "." + key + " missing");
    return false;
  }
  if (!it->is_number()) {
    err = drop(DropReason::kBadType, where + "." + key + " is not a number");
    return false;
  }
  out = it->get<double>();
  if (!std::isfinite(out)) {
    err = drop(DropReason::kNonFinite, where + "." + key + " is not finite");
    return false;
  }
  return true;
}

bool read_vec3(const json& obj, const char* key, const std::array<const char*, 3>& names,
               Vec3& out, ParseResult& err) {
  const json& v = obj.at(key);
  if (!v.is_object()) {
    err = drop(DropReason::kBadType, std::string(key) + " is not an object");
    return false;
  }
  return read_number(v, names[0], key, out.x, err) && read_number(v, names[1], key, out.y, err) &&
         read_number(v, names[2], key, out.z, err);
}

bool printable_id(const std::string& s) {
  for (unsigned char c : s) {
    if (c < 0x20 || c == 0x7f) return false;
  }
  return true;
}

}  // namespace

const char* drop_reason_name(DropReason reason) noexcept {
  const auto i = static_cast<std::size_t>(reason);
  return i < kDropReasonCount ? kReasonNames[i] : "unknown";
}

ParseResult parse_truth_packet(std::string_view datagram, const geo::LocalFrame& frame) {
  if (datagram.size() > kMaxTruthDatagramBytes) {
    return drop(DropReason::kTooLarge, std::to_string(datagram.size()) + " bytes");
  }
  // JSON allows repeated keys and nlohmann keeps the last; a sender that
  // repeats one is confused, so the packet is dropped instead.
  std::vector<std::vector<std::string>> open_objects;
  std::string repeated;
  const json::parser_callback_t watch = [&](int, json::parse_event_t ev, json& parsed) {
    if (ev == json::parse_event_t::object_start) {
      open_objects.emplace_back();
    } else if (ev == json::parse_event_t::object_end) {
      if (!open_objects.empty()) open_objects.pop_back();
    } else if (ev == json::parse_event_t::key && !open_objects.empty() && repeated.empty()) {
      auto& keys = open_objects.back();
      const std::string& k = parsed.get_ref<const std::string&>();
      for (const auto& seen : keys) {
        if (seen == k) repeated = k;
      }
      keys.push_back(k);
    }
    return true;
  };
  json doc;
  try {
    doc = json::parse(datagram.begin(), datagram.end(), watch);
  } catch (const json::exception& e) {
    // Python's json.dumps writes NaN/Infinity literals, which are not JSON;
    // 1e999 overflows a double ("number overflow").
    const std::string what = e.what();
    const bool non_finite = datagram.find("NaN") != std::string_view::npos ||
                            datagram.find("Infinity") != std::string_view::npos ||
                            what.find("overflow") != std::string::npos;
    return drop(non_finite ? DropReason::kNonFinite : DropReason::kMalformedJson, what);
  }
  if (!repeated.empty()) {
    const bool pos = repeated == "lla" || repeated == "ecef" || repeated == "enu";
    return drop(pos ? DropReason::kDuplicatePosition : DropReason::kDuplicateKey, "key \"" + repeated + "\" repeated");
  }
  if (!doc.is_object()) return drop(DropReason::kNotObject, "top level is not an object");

  auto ver = doc.find("version");
  if (ver == doc.end()) return drop(DropReason::kMissingVersion, "no \"version\"");
  if (!ver->is_number() || ver->get<double>() != kTruthProtocolVersion) {
    return drop(DropReason::kUnknownVersion, "version " + ver->dump());
  }

  ParseResult err;
  ParseResult out;
  TruthSample& s = out.sample;

  auto veh = doc.find("vehicle");
  if (veh == doc.end()) return drop(DropReason::kMissingField, "vehicle missing");
  if (!veh->is_string()) return drop(DropReason::kBadType, "vehicle is not a string");
  s.vehicle = veh->get<std::string>();
  if (s.vehicle.empty() || s.vehicle.size() > kMaxVehicleIdChars || !printable_id(s.vehicle)) {
    return drop(DropReason::kBadVehicleId, "vehicle id must be 1..64 printable characters");
  }
  if (!read_number(doc, "sim_time_s", "packet", s.sim_time_s, err)) return err;

  const bool has_lla = doc.contains("lla");
  const bool has_ecef = doc.contains("ecef");
  const bool has_enu = doc.contains("enu");
  const int n_pos = int(has_lla) + int(has_ecef) + int(has_enu);
  if (n_pos == 0) return drop(DropReason::kMissingPosition, "need one of lla, ecef, enu");
  if (n_pos > 1) return drop(DropReason::kDuplicatePosition, "more than one of lla, ecef, enu");

  Vec3 p;
  if (has_lla) {
    if (!read_vec3(doc, "lla", {"lat_deg", "lon_deg", "height_m"}, p, err)) return err;
    if (std::abs(p.x) > 90.0) return drop(DropReason::kLatitudeRange, "|lat_deg| > 90");
    if (p.y < -180.0 || p.y > 360.0) return drop(DropReason::kLongitudeRange, "lon_deg outside -180..360");
    double lon_deg = p.y > 180.0 ? p.y - 360.0 : p.y;
    s.lla = Lla{p.x * kDegToRad, lon_deg * kDegToRad, p.z};
    s.pos_m = geo::ecef_from_lla(s.lla);
  } else if (has_ecef) {
    if (!read_vec3(doc, "ecef", {"x_m", "y_m", "z_m"}, p, err)) return err;
    s.pos_m = Ecef(p);
    s.lla = geo::lla_from_ecef(s.pos_m);
  } else {
    if (!read_vec3(doc, "enu", {"e_m", "n_m", "u_m"}, p, err)) return err;
    s.pos_m = frame.to_ecef(Enu(p));
    s.lla = geo::lla_from_ecef(s.pos_m);
  }
  if (!(s.lla.height_m >= kMinHeight_m && s.lla.height_m <= kMaxHeight_m)) {
    return drop(DropReason::kHeightRange, "height " + std::to_string(s.lla.height_m) + " m outside -1000..100000");
  }

  const bool has_venu = doc.contains("vel_enu");
  const bool has_vecef = doc.contains("vel_ecef");
  if (has_venu && has_vecef) return drop(DropReason::kDuplicateVelocity, "both vel_enu and vel_ecef");
  if (has_venu || has_vecef) {
    Vec3 v;
    if (has_venu) {
      if (!read_vec3(doc, "vel_enu", {"e_m_s", "n_m_s", "u_m_s"}, v, err)) return err;
      // ENU axes at the vehicle (docs/truth-protocol.md).
      v = geo::enu_to_ecef_vector(Enu(v), s.lla.lat_rad, s.lla.lon_rad);
    } else {
      if (!read_vec3(doc, "vel_ecef", {"x_m_s", "y_m_s", "z_m_s"}, v, err)) return err;
    }
    if (v.norm() > kMaxSpeed_m_s) return drop(DropReason::kSpeedRange, "speed > 1000 m/s");
    s.vel_m_s = Ecef(v);
  }

  const bool has_week = doc.contains("gps_week");
  const bool has_tow = doc.contains("gps_tow_s");
  if (has_week != has_tow) return drop(DropReason::kMissingField, "gps_week and gps_tow_s come together");
  if (has_week) {
    double week = 0.0;
    double tow = 0.0;
    if (!read_number(doc, "gps_week", "packet", week, err)) return err;
    if (!read_number(doc, "gps_tow_s", "packet", tow, err)) return err;
    if (week != std::floor(week) || week < 0.0 || week > 9999.0) {
      return drop(DropReason::kBadGpsTime, "gps_week must be an integer 0..9999");
    }
    if (tow < 0.0 || tow >= kSecondsPerWeek) return drop(DropReason::kBadGpsTime, "gps_tow_s outside [0, 604800)");
    s.gps_time = time::GpsTime(static_cast<int32_t>(week), tow);
  }
  out.ok = true;
  return out;
}

}  // namespace gnssemu::daemon

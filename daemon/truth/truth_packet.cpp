// SPDX-License-Identifier: Apache-2.0
#include "daemon/truth/truth_packet.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"

namespace gnssemu::daemon {
namespace {

using nlohmann::json;

constexpr std::array kReasonNames = {
    "too_large",          "malformed_json",     "not_an_object",      "bad_magic",
    "bad_size",           "missing_version",    "unknown_version",    "bad_flags",
    "missing_field",      "bad_type",           "non_finite",         "missing_position",
    "duplicate_position", "duplicate_velocity", "duplicate_key",      "latitude_range",
    "longitude_range",    "height_range",       "speed_range",        "attitude_range",
    "bad_gps_time",       "bad_vehicle_id",     "sim_time_backwards", "too_many_vehicles",
    "unknown_vehicle",    "not_allowed",
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


// How a packet gives its position and velocity; the same for both encodings.
enum class PosForm : uint8_t { kLla, kEcef, kEnu };
enum class VelForm : uint8_t { kNone, kEnu, kEcef };

struct FieldNames {
  const char* key;
  std::array<const char*, 3> names;
};
constexpr std::array<FieldNames, 3> kPosFields = {{{"lla", {"lat_deg", "lon_deg", "height_m"}},
                                                   {"ecef", {"x_m", "y_m", "z_m"}},
                                                   {"enu", {"e_m", "n_m", "u_m"}}}};
constexpr std::array<FieldNames, 2> kVelFields = {{{"vel_enu", {"e_m_s", "n_m_s", "u_m_s"}},
                                                   {"vel_ecef", {"x_m_s", "y_m_s", "z_m_s"}}}};

const FieldNames& pos_fields(PosForm form) { return kPosFields[static_cast<std::size_t>(form)]; }
const FieldNames& vel_fields(VelForm form) { return kVelFields[static_cast<std::size_t>(form) - 1]; }

bool set_vehicle(std::string id, TruthSample& s, ParseResult& err) {
  if (id.empty() || id.size() > kMaxVehicleIdChars || !printable_id(id)) {
    err = drop(DropReason::kBadVehicleId, "vehicle id must be 1..64 printable characters");
    return false;
  }
  s.vehicle = std::move(id);
  return true;
}

// p: finite; degrees and metres as the packet gave them.
bool set_position(PosForm form, const Vec3& p, const geo::LocalFrame& frame, TruthSample& s, ParseResult& err) {
  if (form == PosForm::kLla) {
    if (std::abs(p.x) > 90.0) {
      err = drop(DropReason::kLatitudeRange, "|lat_deg| > 90");
      return false;
    }
    if (p.y < -180.0 || p.y > 360.0) {
      err = drop(DropReason::kLongitudeRange, "lon_deg outside -180..360");
      return false;
    }
    double lon_deg = p.y > 180.0 ? p.y - 360.0 : p.y;
    s.lla = Lla{p.x * kDegToRad, lon_deg * kDegToRad, p.z};
    s.pos_m = geo::ecef_from_lla(s.lla);
  } else if (form == PosForm::kEcef) {
    s.pos_m = Ecef(p);
    s.lla = geo::lla_from_ecef(s.pos_m);
  } else {
    s.pos_m = frame.to_ecef(Enu(p));
    s.lla = geo::lla_from_ecef(s.pos_m);
  }
  if (!(s.lla.height_m >= kMinHeight_m && s.lla.height_m <= kMaxHeight_m)) {
    err = drop(DropReason::kHeightRange, "height " + std::to_string(s.lla.height_m) + " m outside -1000..100000");
    return false;
  }
  return true;
}

// v: finite, m/s; ENU axes at the vehicle (docs/truth-protocol.md). Needs s.lla.
bool set_velocity(VelForm form, Vec3 v, TruthSample& s, ParseResult& err) {
  if (form == VelForm::kEnu) v = geo::enu_to_ecef_vector(Enu(v), s.lla.lat_rad, s.lla.lon_rad);
  if (v.norm() > kMaxSpeed_m_s) {
    err = drop(DropReason::kSpeedRange, "speed > 1000 m/s");
    return false;
  }
  s.vel_m_s = Ecef(v);
  return true;
}

// week, tow_s: finite.
bool set_gps_time(double week, double tow, TruthSample& s, ParseResult& err) {
  if (week != std::floor(week) || week < 0.0 || week > 9999.0) {
    err = drop(DropReason::kBadGpsTime, "gps_week must be an integer 0..9999");
    return false;
  }
  if (tow < 0.0 || tow >= kSecondsPerWeek) {
    err = drop(DropReason::kBadGpsTime, "gps_tow_s outside [0, 604800)");
    return false;
  }
  s.gps_time = time::GpsTime(static_cast<int32_t>(week), tow);
  return true;
}

// a: finite, rad.
bool set_attitude(const Attitude& a, TruthSample& s, ParseResult& err) {
  if (std::abs(a.roll_rad) > kPi || std::abs(a.pitch_rad) > kPi / 2.0 || a.yaw_rad < -kPi ||
      a.yaw_rad > 2.0 * kPi) {
    err = drop(DropReason::kAttitudeRange, "attitude outside roll -pi..pi, pitch -pi/2..pi/2, yaw -pi..2pi rad");
    return false;
  }
  s.attitude = a;
  return true;
}

bool finite_or_drop(double value, const char* where, const char* name, ParseResult& err) {
  if (std::isfinite(value)) return true;
  err = drop(DropReason::kNonFinite, std::string(where) + "." + name + " is not finite");
  return false;
}

bool finite_or_drop(const Vec3& v, const FieldNames& f, ParseResult& err) {
  return finite_or_drop(v.x, f.key, f.names[0], err) && finite_or_drop(v.y, f.key, f.names[1], err) &&
         finite_or_drop(v.z, f.key, f.names[2], err);
}

// --- binary record (docs/truth-protocol.md §Binary record) -----------------

constexpr std::size_t kOffVersion = 4;
constexpr std::size_t kOffFlags = 5;
constexpr std::size_t kOffGpsWeek = 6;
constexpr std::size_t kOffVehicle = 8;
constexpr std::size_t kOffSimTime = 72;
constexpr std::size_t kOffGpsTow = 80;
constexpr std::size_t kOffPos = 88;
constexpr std::size_t kOffVel = 112;
constexpr std::size_t kOffAttitude = 136;
static_assert(kOffVehicle + kTruthRecordVehicleBytes == kOffSimTime);
static_assert(kOffAttitude + 3 * 8 == kTruthRecordBytes);

constexpr uint8_t kFlagPosMask = 0x03;
constexpr uint8_t kFlagVelShift = 2;
constexpr uint8_t kFlagVelMask = 0x0C;
constexpr uint8_t kFlagAttitude = 0x10;
constexpr uint8_t kFlagGpsTime = 0x20;
constexpr uint8_t kFlagReserved = 0xC0;

uint8_t u8_at(std::string_view d, std::size_t off) { return static_cast<uint8_t>(d[off]); }

uint16_t u16_at(std::string_view d, std::size_t off) {
  return static_cast<uint16_t>(u8_at(d, off) | (u8_at(d, off + 1) << 8));
}

// Little-endian IEEE 754 binary64, whatever the host's byte order.
double f64_at(std::string_view d, std::size_t off) {
  uint64_t bits = 0;
  for (std::size_t i = 0; i < 8; ++i) bits |= uint64_t{u8_at(d, off + i)} << (8 * i);
  return std::bit_cast<double>(bits);
}

Vec3 vec3_at(std::string_view d, std::size_t off) {
  return Vec3(f64_at(d, off), f64_at(d, off + 8), f64_at(d, off + 16));
}

ParseResult parse_binary(std::string_view d, const geo::LocalFrame& frame) {
  if (d.size() <= kOffVersion) {
    return drop(DropReason::kBadSize, std::to_string(d.size()) + " bytes: shorter than magic and version");
  }
  if (std::memcmp(d.data(), kTruthRecordMagic.data(), kTruthRecordMagic.size()) != 0) {
    return drop(DropReason::kBadMagic, "first byte 0xF7 but not the magic F7 47 54 52");
  }
  const uint8_t version = u8_at(d, kOffVersion);
  if (version != kTruthRecordVersion) {
    return drop(DropReason::kUnknownVersion, "binary record version " + std::to_string(version));
  }
  if (d.size() != kTruthRecordBytes) {
    return drop(DropReason::kBadSize, "binary record version 1 is " + std::to_string(kTruthRecordBytes) +
                                          " bytes, got " + std::to_string(d.size()));
  }
  const uint8_t flags = u8_at(d, kOffFlags);
  const uint8_t pos_code = flags & kFlagPosMask;
  const uint8_t vel_code = static_cast<uint8_t>((flags & kFlagVelMask) >> kFlagVelShift);
  if ((flags & kFlagReserved) != 0 || pos_code > 2 || vel_code > 2) {
    return drop(DropReason::kBadFlags, "flags " + std::to_string(flags) + ": reserved bits or frame code 3");
  }

  ParseResult err;
  ParseResult out;
  TruthSample& s = out.sample;

  const std::string_view id_field = d.substr(kOffVehicle, kTruthRecordVehicleBytes);
  const std::string_view id = id_field.substr(0, id_field.find('\0'));
  if (id_field.find_first_not_of('\0', id.size()) != std::string_view::npos) {
    return drop(DropReason::kBadVehicleId, "vehicle id field has bytes after its NUL padding");
  }
  if (!set_vehicle(std::string(id), s, err)) return err;

  s.sim_time_s = f64_at(d, kOffSimTime);
  if (!finite_or_drop(s.sim_time_s, "packet", "sim_time_s", err)) return err;

  const auto pos_form = static_cast<PosForm>(pos_code);
  const Vec3 p = vec3_at(d, kOffPos);
  if (!finite_or_drop(p, pos_fields(pos_form), err)) return err;
  if (!set_position(pos_form, p, frame, s, err)) return err;

  const auto vel_form = static_cast<VelForm>(vel_code);
  if (vel_form != VelForm::kNone) {
    const Vec3 v = vec3_at(d, kOffVel);
    if (!finite_or_drop(v, vel_fields(vel_form), err)) return err;
    if (!set_velocity(vel_form, v, s, err)) return err;
  }

  if ((flags & kFlagGpsTime) != 0) {
    const double tow = f64_at(d, kOffGpsTow);
    if (!finite_or_drop(tow, "packet", "gps_tow_s", err)) return err;
    if (!set_gps_time(u16_at(d, kOffGpsWeek), tow, s, err)) return err;
  }

  if ((flags & kFlagAttitude) != 0) {
    const Vec3 a = vec3_at(d, kOffAttitude);
    if (!finite_or_drop(a, FieldNames{"attitude", {"roll_rad", "pitch_rad", "yaw_rad"}}, err)) return err;
    if (!set_attitude(Attitude{a.x, a.y, a.z}, s, err)) return err;
  }
  out.ok = true;
  return out;
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
  if (!datagram.empty() && static_cast<uint8_t>(datagram[0]) == kTruthRecordMagic[0]) {
    return parse_binary(datagram, frame);
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
  if (!set_vehicle(veh->get<std::string>(), s, err)) return err;
  if (!read_number(doc, "sim_time_s", "packet", s.sim_time_s, err)) return err;

  const bool has_lla = doc.contains("lla");
  const bool has_ecef = doc.contains("ecef");
  const bool has_enu = doc.contains("enu");
  const int n_pos = int(has_lla) + int(has_ecef) + int(has_enu);
  if (n_pos == 0) return drop(DropReason::kMissingPosition, "need one of lla, ecef, enu");
  if (n_pos > 1) return drop(DropReason::kDuplicatePosition, "more than one of lla, ecef, enu");

  const PosForm pos_form = has_lla ? PosForm::kLla : has_ecef ? PosForm::kEcef : PosForm::kEnu;
  const FieldNames& pf = pos_fields(pos_form);
  Vec3 p;
  if (!read_vec3(doc, pf.key, pf.names, p, err)) return err;
  if (!set_position(pos_form, p, frame, s, err)) return err;

  const bool has_venu = doc.contains("vel_enu");
  const bool has_vecef = doc.contains("vel_ecef");
  if (has_venu && has_vecef) return drop(DropReason::kDuplicateVelocity, "both vel_enu and vel_ecef");
  if (has_venu || has_vecef) {
    const VelForm vel_form = has_venu ? VelForm::kEnu : VelForm::kEcef;
    const FieldNames& vf = vel_fields(vel_form);
    Vec3 v;
    if (!read_vec3(doc, vf.key, vf.names, v, err)) return err;
    if (!set_velocity(vel_form, v, s, err)) return err;
  }

  const bool has_week = doc.contains("gps_week");
  const bool has_tow = doc.contains("gps_tow_s");
  if (has_week != has_tow) return drop(DropReason::kMissingField, "gps_week and gps_tow_s come together");
  if (has_week) {
    double week = 0.0;
    double tow = 0.0;
    if (!read_number(doc, "gps_week", "packet", week, err)) return err;
    if (!read_number(doc, "gps_tow_s", "packet", tow, err)) return err;
    if (!set_gps_time(week, tow, s, err)) return err;
  }
  out.ok = true;
  return out;
}

}  // namespace gnssemu::daemon

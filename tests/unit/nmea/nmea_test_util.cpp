// SPDX-License-Identifier: Apache-2.0
#include "nmea_test_util.hpp"

#include <cmath>
#include <stdexcept>

#include "core/common/constants.hpp"

namespace gnssemu::protocol::nmea::test {

receiver::Fix fix_from_json(const nlohmann::json& j) {
  receiver::Fix f;
  f.t = time::GpsTime(j.at("week").get<int>(), j.at("tow_s").get<double>());
  f.leap_seconds = j.value("leap_seconds", 18);
  f.in_leap_second = j.value("in_leap_second", false);
  f.time_valid = j.value("time_valid", true);
  const std::string type = j.value("type", "3d");
  if (type == "none") {
    f.type = receiver::FixType::kNone;
  } else if (type == "2d") {
    f.type = receiver::FixType::k2D;
  } else if (type == "3d") {
    f.type = receiver::FixType::k3D;
  } else {
    throw std::runtime_error("bad fix type " + type);
  }
  f.lla.lat_rad = j.value("lat_deg", 0.0) * kDegToRad;
  f.lla.lon_rad = j.value("lon_deg", 0.0) * kDegToRad;
  f.lla.height_m = j.value("height_m", 0.0);
  f.geoid_sep_m = j.value("geoid_sep_m", 0.0);
  f.speed_m_s = j.value("speed_m_s", 0.0);
  f.course_rad = j.value("course_deg", 0.0) * kDegToRad;
  if (j.contains("dop")) {
    const auto& d = j.at("dop");
    f.dop.gdop = d.value("gdop", receiver::Dop::kNoDop);
    f.dop.pdop = d.value("pdop", receiver::Dop::kNoDop);
    f.dop.hdop = d.value("hdop", receiver::Dop::kNoDop);
    f.dop.vdop = d.value("vdop", receiver::Dop::kNoDop);
    f.dop.tdop = d.value("tdop", receiver::Dop::kNoDop);
  }
  f.range_rms_m = j.value("range_rms_m", 0.0);
  f.sigma_e_m = j.value("sigma_e_m", 0.0);
  f.sigma_n_m = j.value("sigma_n_m", 0.0);
  f.cov_en_m2 = j.value("cov_en_m2", 0.0);
  f.sigma_u_m = j.value("sigma_u_m", 0.0);
  f.h_acc_m = j.value("h_acc_m", std::hypot(f.sigma_e_m, f.sigma_n_m));
  f.v_acc_m = j.value("v_acc_m", f.sigma_u_m);
  int used = 0, tracked = 0, visible = 0;
  if (j.contains("sats")) {
    for (const auto& js : j.at("sats")) {
      if (f.num_sats >= static_cast<int>(f.sats.size())) throw std::runtime_error("too many sats");
      receiver::SatInfo& s = f.sats[static_cast<std::size_t>(f.num_sats++)];
      // "sat": "R05" (any system), or "prn": a GPS PRN.
      const auto id = js.contains("sat") ? parse_sat(js.at("sat").get<std::string>()) : SatId::gps(js.at("prn").get<int>());
      if (!id) throw std::runtime_error("bad sat");
      s.sat = *id;
      s.glonass_channel = js.value("glonass_channel", 0);
      s.el_rad = js.at("el_deg").get<double>() * kDegToRad;
      s.az_rad = js.at("az_deg").get<double>() * kDegToRad;
      s.cn0_dbhz = js.value("cn0_dbhz", 0.0);
      s.healthy = js.value("healthy", true);
      s.above_mask = js.value("above_mask", s.el_rad >= 5.0 * kDegToRad);
      s.tracked = js.value("tracked", s.cn0_dbhz > 0.0);
      s.used = js.value("used", false);
      s.excluded = js.value("excluded", false);
      used += s.used ? 1 : 0;
      tracked += s.tracked ? 1 : 0;
      visible += (s.healthy && s.above_mask) ? 1 : 0;
    }
  }
  f.num_used = j.value("num_used", used);
  f.num_tracked = j.value("num_tracked", tracked);
  f.num_visible = j.value("num_visible", visible);
  return f;
}

NmeaConfig config_from_json(const nlohmann::json& j) {
  NmeaConfig c;
  if (j.contains("device")) {
    const std::string d = j.at("device").get<std::string>();
    if (d != "m8" && d != "m9") throw std::runtime_error("bad device " + d);
    static_cast<NmeaSettings&>(c) = factory_settings(d == "m8" ? NmeaDevice::kM8 : NmeaDevice::kM9);
  }
  if (j.contains("version")) c.version = version_from_text(j.at("version").get<std::string>());
  if (j.contains("sv_numbering")) {
    const std::string n = j.at("sv_numbering").get<std::string>();
    c.sv_numbering = n == "extended" ? SvNumbering::kExtended : SvNumbering::kStrict;
  }
  c.max_svs = j.value("max_svs", c.max_svs);
  c.consider = j.value("consider", c.consider);
  if (j.contains("systems")) {
    const auto set = parse_systems(j.at("systems").get<std::string>());
    if (!set) throw std::runtime_error("bad systems");
    c.systems = *set;
  }
  SentenceSet& s = c.sentences;
  for (const SentenceInfo& info : kSentences) {
    std::string key(info.name);
    for (char& ch : key) ch = static_cast<char>(ch - 'A' + 'a');  // "GGA" -> "gga"
    s.set(info.sentence, j.value(key, s.has(info.sentence)));
  }
  c.course_min_speed_m_s = j.value("course_min_speed_m_s", c.course_min_speed_m_s);
  return c;
}

NmeaVersion version_from_text(const std::string& v) {
  if (v == "2.1") return NmeaVersion::k21;
  if (v == "2.3") return NmeaVersion::k23;
  if (v == "4.0") return NmeaVersion::k40;
  if (v == "4.10") return NmeaVersion::k410;
  if (v == "4.11") return NmeaVersion::k411;
  throw std::runtime_error("bad NMEA version " + v);
}

std::vector<std::string> split_lines(std::string_view stream) {
  std::vector<std::string> out;
  while (!stream.empty()) {
    std::size_t nl = stream.find('\n');
    std::string_view line = stream.substr(0, nl);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    out.emplace_back(line);
    if (nl == std::string_view::npos) break;
    stream.remove_prefix(nl + 1);
  }
  return out;
}

Sentence parse_sentence(std::string_view line) {
  Sentence s;
  if (line.empty() || line.front() != '$') return s;
  line.remove_prefix(1);
  const std::size_t star = line.rfind('*');
  if (star != std::string_view::npos) line = line.substr(0, star);
  std::size_t pos = 0;
  bool first = true;
  while (true) {
    const std::size_t comma = line.find(',', pos);
    const std::string_view f = line.substr(pos, comma == std::string_view::npos ? comma : comma - pos);
    if (first) {
      s.address = std::string(f);
      s.type = s.address.size() >= 3 ? s.address.substr(s.address.size() - 3) : s.address;
      first = false;
    } else {
      s.fields.emplace_back(f);
    }
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
  }
  return s;
}

receiver::Fix sample_fix_3d() {
  nlohmann::json j = {
      {"week", 2190}, {"tow_s", 561618.25}, {"type", "3d"}, {"lat_deg", 47.285233}, {"lon_deg", 8.565265},
      {"height_m", 547.6}, {"geoid_sep_m", 48.0}, {"speed_m_s", 13.4}, {"course_deg", 87.3},
      {"dop", {{"gdop", 2.1}, {"pdop", 1.94}, {"hdop", 1.18}, {"vdop", 1.54}, {"tdop", 0.9}}},
      {"range_rms_m", 1.8}, {"sigma_e_m", 1.3}, {"sigma_n_m", 1.7}, {"sigma_u_m", 2.2},
  };
  const double sats[][4] = {{3, 12.4, 44.0, 31.2},  {7, 29.0, 116.4, 41.0}, {8, 9.2, 81.0, 36.0},
                            {9, 55.5, 300.2, 45.0}, {16, 3.0, 200.0, 0.0},  {18, 42.0, 10.0, 43.6},
                            {23, 38.4, 230.0, 44.0}, {26, 20.0, 170.0, 38.0}, {28, 65.0, 99.6, 47.4},
                            {29, 71.0, 156.0, 47.0}};
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& s : sats) {
    const bool tracked = s[3] > 0.0;
    arr.push_back({{"prn", static_cast<int>(s[0])}, {"el_deg", s[1]}, {"az_deg", s[2]},
                   {"cn0_dbhz", s[3]}, {"tracked", tracked}, {"used", tracked && s[1] >= 5.0}});
  }
  j["sats"] = arr;
  return fix_from_json(j);
}

}  // namespace gnssemu::protocol::nmea::test

// SPDX-License-Identifier: Apache-2.0
#include "tools/senders/trajectory.hpp"

#include <cmath>
#include <fstream>
#include <optional>
#include <string_view>

#include "core/common/error.hpp"
#include "core/common/text_fields.hpp"

namespace gnssemu::senders {

namespace {

std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(text::trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

struct PositionColumns {
  PositionFrame frame;
  std::array<const char*, 3> names;
};
constexpr std::array<PositionColumns, 3> kPositionColumns = {{
    {PositionFrame::kLla, {"lat_deg", "lon_deg", "height_m"}},
    {PositionFrame::kEnu, {"e_m", "n_m", "u_m"}},
    {PositionFrame::kEcef, {"x_m", "y_m", "z_m"}},
}};

// Column indices of the header, by name.
class Header {
public:
  explicit Header(std::vector<std::string_view> names) : names_(std::move(names)) {}
  std::optional<std::size_t> find(std::string_view name) const {
    for (std::size_t i = 0; i < names_.size(); ++i) {
      if (names_[i] == name) return i;
    }
    return std::nullopt;
  }
  bool has_all(const std::array<const char*, 3>& names) const {
    return find(names[0]) && find(names[1]) && find(names[2]);
  }
  std::size_t size() const { return names_.size(); }

private:
  std::vector<std::string_view> names_;
};

}  // namespace

TruthRecord circle_at(const CircleParams& circle, double t_s) noexcept {
  const double a = circle.speed_m_s / circle.radius_m * t_s;
  TruthRecord r;
  r.sim_time_s = t_s;
  r.position_frame = PositionFrame::kEnu;
  r.position = {circle.radius_m * std::cos(a), circle.radius_m * std::sin(a), circle.up_m};
  r.velocity_frame = VelocityFrame::kEnu;
  r.vel_m_s = {-circle.speed_m_s * std::sin(a), circle.speed_m_s * std::cos(a), 0.0};
  r.has_attitude = true;
  r.attitude_rad = {0.0, 0.0, std::atan2(r.vel_m_s[0], r.vel_m_s[1])};
  return r;
}

std::vector<TruthRecord> read_trajectory_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path, 0, "cannot open");
  std::string header_line;
  int line_no = 0;
  while (std::getline(in, header_line)) {
    ++line_no;
    const std::string_view t = text::trim(header_line);
    if (!t.empty() && t.front() != '#') break;
  }
  const Header header(split_commas(header_line));
  if (!header.find("sim_time_s")) throw Error(path, line_no, "need a sim_time_s column");
  const PositionColumns* pos = nullptr;
  for (const PositionColumns& c : kPositionColumns) {
    if (header.has_all(c.names)) {
      pos = &c;
      break;
    }
  }
  if (pos == nullptr) {
    throw Error(path, line_no, "need columns lat_deg,lon_deg,height_m or e_m,n_m,u_m or x_m,y_m,z_m");
  }
  const std::array<const char*, 3> vel_names = {"ve_m_s", "vn_m_s", "vu_m_s"};
  const bool has_vel = header.has_all(vel_names);
  const bool has_gps = header.find("gps_week") && header.find("gps_tow_s");

  std::vector<TruthRecord> out;
  std::string line;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view t = text::trim(line);
    if (t.empty() || t.front() == '#') continue;
    const auto fields = split_commas(t);
    if (fields.size() != header.size()) {
      throw Error(path, line_no, std::to_string(fields.size()) + " fields, header has " + std::to_string(header.size()));
    }
    auto number = [&](const char* name) {
      const std::optional<double> v = text::parse_real(fields[*header.find(name)]);
      if (!v || !std::isfinite(*v)) throw Error(path, line_no, std::string("column '") + name + "': not a finite number");
      return *v;
    };
    TruthRecord r;
    r.sim_time_s = number("sim_time_s");
    if (!out.empty() && !(r.sim_time_s > out.back().sim_time_s)) {
      throw Error(path, line_no, "sim_time_s must increase");
    }
    r.position_frame = pos->frame;
    for (std::size_t i = 0; i < 3; ++i) r.position[i] = number(pos->names[i]);
    if (has_vel) {
      r.velocity_frame = VelocityFrame::kEnu;
      for (std::size_t i = 0; i < 3; ++i) r.vel_m_s[i] = number(vel_names[i]);
    }
    if (has_gps) {
      const double week = number("gps_week");
      if (week != std::floor(week) || week < 0.0 || week > 9999.0) {
        throw Error(path, line_no, "column 'gps_week': not an integer 0..9999");
      }
      r.has_gps_time = true;
      r.gps_week = static_cast<uint16_t>(week);
      r.gps_tow_s = number("gps_tow_s");
    }
    out.push_back(r);
  }
  if (out.empty()) throw Error(path, 0, "no rows");
  return out;
}

}  // namespace gnssemu::senders

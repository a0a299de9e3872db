// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/batch/truth_csv.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string_view>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"

namespace gnssemu::cli {

namespace {

// Plausible limits; outside them the row is a typo, not a vehicle.
constexpr double kMinHeight_m = -1.0e4;
constexpr double kMaxHeight_m = 1.0e6;
constexpr double kMinRadius_m = 6.0e6;
constexpr double kMaxRadius_m = 1.0e8;
constexpr double kMaxSpeed_m_s = 1.0e4;
constexpr int kMaxWeek = 9999;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

bool skip_line(std::string_view line) {
  const std::string_view t = trim(line);
  return t.empty() || t.front() == '#';
}

struct Columns {
  int week = -1, tow = -1;
  int lat = -1, lon = -1, height = -1;
  int x = -1, y = -1, z = -1;
  int ve = -1, vn = -1, vu = -1;
  int valid = -1;
  std::size_t count = 0;
  bool lla() const { return lat >= 0; }
  bool vel() const { return ve >= 0; }
};

Columns parse_header(std::string_view line, const std::string& name, int line_no) {
  Columns c;
  const auto fields = split(line);
  c.count = fields.size();
  struct Slot {
    std::string_view name;
    int* index;
  };
  const Slot slots[] = {{"gps_week", &c.week}, {"tow_s", &c.tow},   {"lat_deg", &c.lat},
                        {"lon_deg", &c.lon},   {"height_m", &c.height}, {"x_m", &c.x},
                        {"y_m", &c.y},         {"z_m", &c.z},       {"ve_m_s", &c.ve},
                        {"vn_m_s", &c.vn},     {"vu_m_s", &c.vu},   {"valid", &c.valid}};
  for (std::size_t i = 0; i < fields.size(); ++i) {
    for (const Slot& s : slots) {
      if (fields[i] != s.name) continue;
      if (*s.index >= 0) throw Error(name, line_no, "column '" + std::string(s.name) + "' appears twice");
      *s.index = static_cast<int>(i);
    }
  }
  auto need = [&](int idx, const char* col) {
    if (idx < 0) throw Error(name, line_no, std::string("missing column '") + col + "'");
  };
  need(c.week, "gps_week");
  need(c.tow, "tow_s");
  const bool any_lla = c.lat >= 0 || c.lon >= 0 || c.height >= 0;
  const bool any_xyz = c.x >= 0 || c.y >= 0 || c.z >= 0;
  if (any_lla && any_xyz) {
    throw Error(name, line_no, "both lat_deg/lon_deg/height_m and x_m/y_m/z_m columns; give one position form");
  }
  if (!any_lla && !any_xyz) {
    throw Error(name, line_no, "missing position columns: need lat_deg,lon_deg,height_m or x_m,y_m,z_m");
  }
  if (any_lla) {
    need(c.lat, "lat_deg");
    need(c.lon, "lon_deg");
    need(c.height, "height_m");
  } else {
    need(c.x, "x_m");
    need(c.y, "y_m");
    need(c.z, "z_m");
  }
  if (c.ve >= 0 || c.vn >= 0 || c.vu >= 0) {
    need(c.ve, "ve_m_s");
    need(c.vn, "vn_m_s");
    need(c.vu, "vu_m_s");
  }
  return c;
}

class RowParser {
public:
  RowParser(const std::vector<std::string_view>& fields, const std::vector<std::string>& header,
            const std::string& name, int line_no)
      : fields_(fields), header_(header), name_(name), line_no_(line_no) {}

  double number(int col) const {
    std::string_view f = fields_[col];
    if (f.size() > 1 && f.front() == '+') f.remove_prefix(1);  // from_chars rejects '+'
    double v = 0.0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty()) fail(col, "empty value");
    if (ec != std::errc() || end != f.data() + f.size()) fail(col, "'" + std::string(f) + "' is not a number");
    if (!std::isfinite(v)) fail(col, "'" + std::string(f) + "' is not finite");
    return v;
  }

  int integer(int col) const {
    const std::string_view f = fields_[col];
    int v = 0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty()) fail(col, "empty value");
    if (ec != std::errc() || end != f.data() + f.size()) fail_value(col, f, "is not an integer");
    return v;
  }

  double in_range(int col, double lo, double hi, bool hi_open = false) const {
    const double v = number(col);
    if (v < lo || v > hi || (hi_open && v == hi)) {
      fail(col, std::string(fields_[col]) + " outside [" + fmt_num(lo) + ", " + fmt_num(hi) + (hi_open ? ")" : "]"));
    }
    return v;
  }

  // Built with append: GCC 12 warns falsely (-Wrestrict) on "'" + std::string(...) once inlined.
  [[noreturn]] void fail_value(int col, std::string_view value, std::string_view what) const {
    std::string reason = "'";
    reason.append(value).append("' ").append(what);
    fail(col, reason);
  }

  [[noreturn]] void fail(int col, const std::string& reason) const {
    throw Error(name_, line_no_, "column '" + header_[col] + "': " + reason);
  }

private:
  static std::string fmt_num(double v) {
    std::string s = std::to_string(v);
    while (s.size() > 1 && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  }

  const std::vector<std::string_view>& fields_;
  const std::vector<std::string>& header_;
  const std::string& name_;
  int line_no_;
};

}  // namespace

std::vector<world::TruthSample> read_truth_csv(std::istream& in, const std::string& name) {
  std::vector<world::TruthSample> out;
  std::string line;
  int line_no = 0;
  std::optional<Columns> cols;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    ++line_no;
    if (skip_line(line)) continue;
    if (!cols) {
      std::string_view h = line;
      if (h.substr(0, 3) == "\xEF\xBB\xBF") h.remove_prefix(3);  // UTF-8 byte-order mark (spreadsheet exports)
      cols = parse_header(h, name, line_no);
      for (std::string_view f : split(h)) header.emplace_back(f);
      continue;
    }
    const auto fields = split(line);
    if (fields.size() != cols->count) {
      throw Error(name, line_no,
                  std::to_string(fields.size()) + " fields, header has " + std::to_string(cols->count));
    }
    const RowParser p(fields, header, name, line_no);
    const int week = p.integer(cols->week);
    if (week < 0 || week > kMaxWeek) p.fail(cols->week, std::to_string(week) + " outside [0, 9999]");
    const double tow_s = p.in_range(cols->tow, 0.0, kSecondsPerWeek, true);
    world::TruthSample s;
    s.t = time::GpsTime(week, tow_s);
    if (cols->valid >= 0) {
      const int v = p.integer(cols->valid);
      if (v != 0 && v != 1) p.fail(cols->valid, std::to_string(v) + " is not 0 (no truth) or 1");
      s.valid = v == 1;
    }
    if (!s.valid) {
      // No truth: the position and velocity cells are not read (may be empty).
      if (!out.empty() && !(s.t - out.back().t > 0.0)) p.fail(cols->tow, "time is not after the previous row's");
      out.push_back(s);
      continue;
    }
    Lla lla;
    if (cols->lla()) {
      lla.lat_rad = p.in_range(cols->lat, -90.0, 90.0) * kDegToRad;
      lla.lon_rad = p.in_range(cols->lon, -180.0, 180.0) * kDegToRad;
      lla.height_m = p.in_range(cols->height, kMinHeight_m, kMaxHeight_m);
      s.pos_m = geo::ecef_from_lla(lla);
    } else {
      s.pos_m = Ecef(p.number(cols->x), p.number(cols->y), p.number(cols->z));
      const double r = s.pos_m.norm();
      if (r < kMinRadius_m || r > kMaxRadius_m) {
        p.fail(cols->x, "|(x,y,z)| = " + std::to_string(r) + " m is not a position near the Earth");
      }
      lla = geo::lla_from_ecef(s.pos_m);
    }
    if (cols->vel()) {
      const Enu v(p.in_range(cols->ve, -kMaxSpeed_m_s, kMaxSpeed_m_s),
                  p.in_range(cols->vn, -kMaxSpeed_m_s, kMaxSpeed_m_s),
                  p.in_range(cols->vu, -kMaxSpeed_m_s, kMaxSpeed_m_s));
      s.vel_m_s = Ecef(geo::enu_to_ecef_vector(v, lla.lat_rad, lla.lon_rad));
      s.has_vel = true;
    }
    if (!out.empty() && !(s.t - out.back().t > 0.0)) {
      p.fail(cols->tow, "time is not after the previous row's");
    }
    out.push_back(s);
  }
  if (in.bad()) throw Error(name, line_no, "read error");
  if (!cols) throw Error(name, 0, "empty file: no header line");
  if (out.empty()) throw Error(name, line_no, "no data rows after the header");
  return out;
}

std::vector<world::TruthSample> read_truth_csv(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path, 0, "truth file not found (or not a regular file)");
  std::ifstream in(path);
  if (!in) throw Error(path, 0, "cannot open truth file");
  return read_truth_csv(in, path);
}

}  // namespace gnssemu::cli

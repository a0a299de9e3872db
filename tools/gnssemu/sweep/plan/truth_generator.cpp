// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/plan/truth_generator.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"

namespace gnssemu::cli::sweep {

namespace {

constexpr double kSecondsPerDay = 86400.0;
constexpr double kMaxDuration_s = 7.0 * kSecondsPerDay;

double number(const toml::table& t, std::string_view key, std::optional<double> def, double lo, double hi,
              const std::string& file, int line) {
  const toml::node* n = t.get(key);
  if (n == nullptr) {
    if (!def) throw Error(file, line, fmt::format("truth generator: '{}' is required", key));
    return *def;
  }
  const std::optional<double> v = n->value<double>();
  if (!v || !std::isfinite(*v) || *v < lo || *v > hi) {
    throw Error(file, line, fmt::format("truth generator: '{}' must be a number in [{}, {}]", key, lo, hi));
  }
  return *v;
}

}  // namespace

bool is_generator_text(std::string_view text) noexcept { return !text.empty() && text.front() == '{'; }

TruthGenerator parse_generator(std::string_view inline_toml, const std::string& file, int line) {
  toml::table doc;
  try {
    doc = toml::parse("g = " + std::string(inline_toml));
  } catch (const toml::parse_error& e) {
    throw Error(file, line, std::string("truth generator: ") + std::string(e.description()));
  }
  const toml::table* t = doc["g"].as_table();
  if (t == nullptr) throw Error(file, line, "truth generator: expected an inline table");
  static constexpr std::string_view kKeys[] = {"generator", "name",     "week",      "tow_s",     "duration_s", "step_s",
                                               "lat_deg",   "lon_deg",  "height_m",  "speed_m_s", "heading_deg"};
  for (const auto& [k, v] : *t) {
    bool known = false;
    for (std::string_view key : kKeys) known = known || k.str() == key;
    if (!known) {
      throw Error(file, line, fmt::format("truth generator: unknown key '{}' (generator, name, week, tow_s, duration_s, "
                                          "step_s, lat_deg, lon_deg, height_m, speed_m_s, heading_deg)",
                                          k.str()));
    }
  }
  if (t->get_as<std::string>("generator") == nullptr || **t->get_as<std::string>("generator") != "line") {
    throw Error(file, line, "truth generator: generator = \"line\" is required (the one generator)");
  }
  TruthGenerator g;
  if (const auto* n = t->get_as<std::string>("name"); n != nullptr && !n->get().empty()) {
    g.name = n->get();
  } else {
    throw Error(file, line, "truth generator: 'name' (a non-empty string) is required");
  }
  g.week = static_cast<int>(number(*t, "week", std::nullopt, 0, 9999, file, line));
  g.tow_s = number(*t, "tow_s", std::nullopt, 0.0, kSecondsPerWeek - 1e-9, file, line);
  g.duration_s = number(*t, "duration_s", std::nullopt, 1e-3, kMaxDuration_s, file, line);
  g.step_s = number(*t, "step_s", 1.0, 1e-3, 3600.0, file, line);
  g.lat_deg = number(*t, "lat_deg", std::nullopt, -90.0, 90.0, file, line);
  g.lon_deg = number(*t, "lon_deg", std::nullopt, -180.0, 180.0, file, line);
  g.height_m = number(*t, "height_m", 0.0, -1e4, 1e6, file, line);
  g.speed_m_s = number(*t, "speed_m_s", 0.0, 0.0, 1000.0, file, line);
  g.heading_deg = number(*t, "heading_deg", 0.0, 0.0, 360.0 - 1e-9, file, line);
  return g;
}

std::vector<world::TruthSample> generate_truth(const TruthGenerator& g) {
  const Lla start{g.lat_deg * kDegToRad, g.lon_deg * kDegToRad, g.height_m};
  const Ecef p0 = geo::ecef_from_lla(start);
  const Enu vel_enu(g.speed_m_s * std::sin(g.heading_deg * kDegToRad), g.speed_m_s * std::cos(g.heading_deg * kDegToRad),
                    0.0);
  const Ecef vel(geo::enu_to_ecef_vector(vel_enu, start.lat_rad, start.lon_rad));
  const time::GpsTime t0(g.week, g.tow_s);
  const auto n = static_cast<long>(std::floor(g.duration_s / g.step_s + 1e-9));
  std::vector<world::TruthSample> out;
  out.reserve(static_cast<std::size_t>(n) + 1);
  for (long k = 0; k <= n; ++k) {
    const double dt = static_cast<double>(k) * g.step_s;
    world::TruthSample s;
    s.t = t0 + dt;
    s.pos_m = Ecef(p0 + vel * dt);
    s.vel_m_s = vel;
    s.has_vel = true;
    out.push_back(s);
  }
  return out;
}

void shift_to_hour(std::vector<world::TruthSample>& samples, double start_h) {
  if (samples.empty()) return;
  const time::GpsTime first = samples.front().t;
  const double day_start_tow = std::floor(first.tow_s() / kSecondsPerDay) * kSecondsPerDay;
  const double dt = (time::GpsTime(first.week(), day_start_tow + start_h * 3600.0)) - first;
  for (world::TruthSample& s : samples) s.t = s.t + dt;
}

std::string truth_csv_text(const std::vector<world::TruthSample>& samples) {
  // Velocity columns only when every sample with truth has one (the reader
  // needs all three in every such row).
  bool vel = true;
  for (const world::TruthSample& s : samples) vel = vel && (!s.valid || s.has_vel);
  std::string out = vel ? "gps_week,tow_s,x_m,y_m,z_m,ve_m_s,vn_m_s,vu_m_s,valid\n" : "gps_week,tow_s,x_m,y_m,z_m,valid\n";
  for (const world::TruthSample& s : samples) {
    if (!s.valid) {
      out += fmt::format("{},{:.6f},,,,{}0\n", s.t.week(), s.t.tow_s(), vel ? ",,," : "");
      continue;
    }
    out += fmt::format("{},{:.6f},{:.4f},{:.4f},{:.4f},", s.t.week(), s.t.tow_s(), s.pos_m.x, s.pos_m.y, s.pos_m.z);
    if (vel) {
      const Lla lla = geo::lla_from_ecef(s.pos_m);
      const Enu v = geo::ecef_to_enu_vector(s.vel_m_s, lla.lat_rad, lla.lon_rad);
      out += fmt::format("{:.4f},{:.4f},{:.4f},", v.x, v.y, v.z);
    }
    out += "1\n";
  }
  return out;
}

}  // namespace gnssemu::cli::sweep

// SPDX-License-Identifier: Apache-2.0
#include "core/orbit/almanac.hpp"

#include <cctype>
#include <cmath>
#include <optional>
#include <sstream>
#include <string_view>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/common/line_source.hpp"
#include "core/common/text_fields.hpp"

namespace gnssemu::orbit {

namespace {

using text::trim;

bool starts_with_nocase(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(s[i])) != std::tolower(static_cast<unsigned char>(prefix[i]))) {
      return false;
    }
  }
  return true;
}

double parse_real(std::string_view tok, const std::string& path, int line, const std::string& what) {
  const std::optional<double> v = text::parse_real(tok);
  if (!v) throw Error(path, line, "unparsable number '" + std::string(trim(tok)) + "' for " + what);
  if (!std::isfinite(*v)) throw Error(path, line, "non-finite value for " + what);
  return *v;
}

int parse_int(std::string_view tok, const std::string& path, int line, const std::string& what) {
  const double v = parse_real(tok, path, line, what);
  if (v != std::floor(v) || std::fabs(v) > 1e9) throw Error(path, line, "expected an integer for " + what);
  return static_cast<int>(v);
}

/// The GPS satellite of an almanac PRN; throws out of range.
SatId gps_sat(int prn, const std::string& path, int line) {
  if (prn < 1 || prn > system_size(GnssSystem::kGps)) {
    throw Error(path, line, "PRN " + std::to_string(prn) + " out of range 1..32");
  }
  return SatId::gps(prn);
}

/// Field lines: prn, e, sqrt(A) (1-based).
void check_entry(const AlmanacEntry& a, const std::string& path, const int (&line)[3]) {
  if (a.e < 0.0 || a.e >= 1.0) throw Error(path, line[1], "eccentricity must be in [0, 1)");
  if (a.sqrt_a_sqrtm <= 0.0) throw Error(path, line[2], "sqrt(A) must be positive");
}

// An almanac is ~18 kB (YUMA, 32 satellites): anything far larger is not one.
constexpr text::LineLimits kAlmanacLimits{1024, 4u << 20};

}  // namespace

std::vector<AlmanacEntry> read_yuma(const std::string& path, int reference_week) {
  text::LineSource in(path, kAlmanacLimits);
  // Field labels in file order (reference gps-orbits.md §8), matched by prefix.
  static constexpr std::string_view kLabels[] = {
      "ID", "Health", "Eccentricity", "Time of Applicability", "Orbital Inclination", "Rate of Right Ascen",
      "SQRT(A)", "Right Ascen at", "Argument of Perigee", "Mean Anom", "Af0", "Af1", "week"};
  constexpr int kFields = 13;

  std::vector<AlmanacEntry> out;
  text::Line line;
  int n = 0;
  int block_line = 0;  // header line of the block being read, 0 = none
  double v[kFields] = {};
  bool seen[kFields] = {};
  int at[kFields] = {};

  auto finish = [&]() {
    for (int k = 0; k < kFields; ++k) {
      if (!seen[k]) throw Error(path, block_line, "almanac block lacks '" + std::string(kLabels[k]) + "'");
    }
    // Range checks before any conversion: a toa of 1e300 must not reach GpsTime.
    if (!(v[3] >= 0.0 && v[3] < kSecondsPerWeek)) throw Error(path, at[3], "toa outside the week");
    if (v[12] < 0.0) throw Error(path, at[12], "negative almanac week");
    AlmanacEntry a;
    a.sat = gps_sat(static_cast<int>(v[0]), path, at[0]);
    a.health = static_cast<int>(v[1]);
    a.e = v[2];
    const int week = time::resolve_week_nearest(static_cast<int32_t>(v[12]) % 1024, reference_week);
    a.toa = time::GpsTime(week, v[3]);
    a.i0_rad = v[4];
    a.omega_dot_rad_s = v[5];
    a.sqrt_a_sqrtm = v[6];
    a.omega0_rad = v[7];
    a.omega_rad = v[8];
    a.m0_rad = v[9];
    a.af0_s = v[10];
    a.af1_s_s = v[11];
    check_entry(a, path, {at[0], at[2], at[6]});
    out.push_back(a);
    block_line = 0;
    for (bool& b : seen) b = false;
  };

  while (in.next(line)) {
    n = line.number;
    const std::string_view t = trim(line.text);
    if (t.empty()) continue;
    if (t.front() == '*') {
      if (block_line != 0) finish();
      block_line = n;
      continue;
    }
    if (block_line == 0) throw Error(path, n, "data outside an almanac block (expected a '****' header line)");
    const auto colon = t.find(':');
    if (colon == std::string_view::npos) throw Error(path, n, "expected 'label: value'");
    const std::string_view label = trim(t.substr(0, colon));
    int k = 0;
    while (k < kFields && !starts_with_nocase(label, kLabels[k])) ++k;
    if (k == kFields) throw Error(path, n, "unknown almanac field '" + std::string(label) + "'");
    if (k == 0 || k == 1 || k == 12) {
      v[k] = parse_int(t.substr(colon + 1), path, n, std::string(kLabels[k]));
    } else {
      v[k] = parse_real(t.substr(colon + 1), path, n, std::string(kLabels[k]));
    }
    seen[k] = true;
    at[k] = n;
  }
  if (block_line != 0) finish();
  if (out.empty()) throw Error(path, n, "no almanac entries");
  return out;
}

std::vector<AlmanacEntry> read_sem(const std::string& path, int reference_week) {
  text::LineSource in(path, kAlmanacLimits);
  struct Token {
    std::string text;
    int line;
  };
  std::vector<Token> toks;
  text::Line line;
  int n = 0;
  int last_line = 0;
  while (in.next(line)) {
    n = line.number;
    std::istringstream ls(line.text);
    std::string w;
    if (n == 1) {  // "N  name": the name may contain anything
      if (ls >> w) toks.push_back({w, n});
      continue;
    }
    while (ls >> w) toks.push_back({w, n});
    last_line = n;
  }
  if (toks.size() < 3) throw Error(path, n, "SEM header must give the record count, week and toa");
  const int count = parse_int(toks[0].text, path, toks[0].line, "record count");
  const int week10 = parse_int(toks[1].text, path, toks[1].line, "week");
  const double toa = parse_real(toks[2].text, path, toks[2].line, "toa");
  if (count < 1 || count > 64) throw Error(path, toks[0].line, "record count out of range 1..64");
  if (!(toa >= 0.0 && toa < kSecondsPerWeek)) throw Error(path, toks[2].line, "toa outside the week");
  if (week10 < 0) throw Error(path, toks[1].line, "negative almanac week");
  const time::GpsTime t_toa(time::resolve_week_nearest(week10 % 1024, reference_week), toa);

  // Per record (ICD-GPS-870 Table 30-III): PRN, SVN, URA, e, di, OMEGADOT,
  // sqrtA, OMEGA0, omega, M0, af0, af1, health, config.
  constexpr std::size_t kPerRecord = 14;
  std::vector<AlmanacEntry> out;
  std::size_t i = 3;
  for (int r = 0; r < count; ++r) {
    if (i + kPerRecord > toks.size()) {
      throw Error(path, last_line, "truncated SEM file: " + std::to_string(r) + " of " + std::to_string(count) +
                                       " records");
    }
    auto real = [&](std::size_t k, const char* what) {
      return parse_real(toks[i + k].text, path, toks[i + k].line, what);
    };
    AlmanacEntry a;
    a.sat = gps_sat(parse_int(toks[i].text, path, toks[i].line, "PRN"), path, toks[i].line);
    a.toa = t_toa;
    a.e = real(3, "eccentricity");
    a.i0_rad = (0.30 + real(4, "inclination offset")) * kPiGps;
    a.omega_dot_rad_s = real(5, "rate of right ascension") * kPiGps;
    a.sqrt_a_sqrtm = real(6, "sqrt(A)");
    a.omega0_rad = real(7, "right ascension") * kPiGps;
    a.omega_rad = real(8, "argument of perigee") * kPiGps;
    a.m0_rad = real(9, "mean anomaly") * kPiGps;
    a.af0_s = real(10, "af0");
    a.af1_s_s = real(11, "af1");
    a.health = parse_int(toks[i + 12].text, path, toks[i + 12].line, "health");
    check_entry(a, path, {toks[i].line, toks[i + 3].line, toks[i + 6].line});
    out.push_back(a);
    i += kPerRecord;
  }
  return out;
}

std::vector<AlmanacEntry> read_almanac(const std::string& path, int reference_week) {
  text::LineSource in(path, kAlmanacLimits);
  text::Line line;
  while (in.next(line)) {
    const std::string_view t = trim(line.text);
    if (t.empty()) continue;
    return t.front() == '*' ? read_yuma(path, reference_week) : read_sem(path, reference_week);
  }
  throw Error(path, in.line_number(), "empty almanac file");
}

Ephemeris to_ephemeris(const AlmanacEntry& alm) noexcept {
  Ephemeris e;
  e.sat = alm.sat;
  e.toc = alm.toa;
  e.toe = alm.toa;
  e.af0_s = alm.af0_s;
  e.af1_s_s = alm.af1_s_s;
  e.e = alm.e;
  e.sqrt_a_sqrtm = alm.sqrt_a_sqrtm;
  e.omega0_rad = alm.omega0_rad;
  e.i0_rad = alm.i0_rad;
  e.omega_rad = alm.omega_rad;
  e.m0_rad = alm.m0_rad;
  e.omega_dot_rad_s = alm.omega_dot_rad_s;
  e.health = alm.health;
  return e;
}

SatState almanac_state(const AlmanacEntry& alm, const time::GpsTime& t) noexcept {
  SatState s = sat_state(to_ephemeris(alm), t);
  // IS-GPS-200 §20.3.3.5.2.3 / RTKLIB alm2pos: almanac clock is af0 + af1 tk only.
  const double tk = t - alm.toa;
  s.clk_bias_s = alm.af0_s + alm.af1_s_s * tk;
  s.clk_drift_s_s = alm.af1_s_s;
  s.relativity_s = 0.0;
  return s;
}

}  // namespace gnssemu::orbit

// SPDX-License-Identifier: Apache-2.0
#include "core/orbit/rinex_nav.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string_view>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/common/line_source.hpp"
#include "core/common/text_fields.hpp"

namespace gnssemu::orbit {

namespace {

// RINEX 2.11 §6.7 / 3.04 §8: transmission time 0.9999e9 = not known.
constexpr double kUnknownTransmitTime_s = 0.9999e9;
// Nav lines are 80 columns; a year of 2-hourly sets for 32 satellites is
// 140k ephemerides. Beyond these the file is not a nav file.
constexpr text::LineLimits kNavLimits{1024, 512u << 20};
constexpr std::size_t kMaxEphemerides = 500000;
constexpr std::size_t kMaxRecordLines = 8;

using text::columns;
using text::Line;
using text::trim;
using Parser = text::ColumnReader;
using Record = std::array<Line, kMaxRecordLines>;

bool blank(const std::string& s) { return trim(s).empty(); }

/// Largest magnitude of a two's complement field of `bits` bits scaled by
/// 2^scale_log2: the negative end, one LSB beyond the positive one.
constexpr double field_max(int bits, int scale_log2) {
  double v = 1.0;
  for (int k = 1; k < bits; ++k) v *= 2.0;  // 2^(bits-1)
  double s = 1.0;
  for (int k = 0; k < (scale_log2 < 0 ? -scale_log2 : scale_log2); ++k) s *= 2.0;
  return scale_log2 < 0 ? v / s : v * s;
}

/// A value the broadcast message cannot carry (IS-GPS-200 Table 20-III bit
/// widths and scale factors) is a corrupt record: far beyond them the orbit
/// and clock models give infinities.
void check_broadcast_range(const Parser& p, int line, double value, double max_abs, const char* field) {
  if (!(std::fabs(value) <= max_abs)) {
    char msg[160];
    std::snprintf(msg, sizeof msg, "%s %.6g outside what the broadcast message carries (|x| <= %.6g, IS-GPS-200 Table 20-III)",
                  field, value, max_abs);
    p.fail(line, msg);
  }
}

/// Lines per record for a RINEX 3 system letter, 0 = unknown. version_x100:
/// 300..305. RINEX 3.04 Tables A6-A19: G/E/C/J/I 8 lines, R/S 4; RINEX 3.05
/// Table A11 adds a 5th GLONASS line (status flags, L1/L2 delay, URAI, health).
int record_lines_v3(char sys, int version_x100) {
  switch (sys) {
    case 'G': case 'E': case 'C': case 'J': case 'I': return 8;
    case 'R': return version_x100 >= 305 ? 5 : 4;
    case 'S': return 4;
    default: return 0;
  }
}

struct Header {
  double version = 0.0;
  int version_x100 = 0;  // 305 for 3.05: exact comparisons on the version
  int major = 0;
};

/// The first line is checked before anything else is read.
Header parse_header(const Parser& p, text::LineSource& src, NavData& out) {
  Header h;
  Line first;
  if (!src.next(first)) p.fail(1, "empty file");
  const text::RinexVersionLine v = text::read_rinex_version_line(p, first);
  h.version = v.version;
  h.version_x100 = static_cast<int>(std::lround(h.version * 100.0));
  h.major = v.major;
  if (h.major == 2) {
    if (v.type != 'N') {
      p.fail(first.number, std::string("not a RINEX 2 GPS navigation file (type '") + v.type + "')");
    }
  } else {
    if (v.type != 'N') p.fail(first.number, std::string("not a navigation file (type '") + v.type + "')");
    if (v.system != 'G' && v.system != 'M') {
      p.fail(first.number, std::string("navigation file for system '") + v.system + "', need GPS (G) or mixed (M)");
    }
  }
  out.rinex_version = h.version;

  bool have_alpha = false, have_beta = false;
  Line l;
  while (src.next(l)) {
    const std::string label = text::rinex_label(l.text);
    if (label == "END OF HEADER") {
      out.klobuchar.valid = have_alpha && have_beta;
      return h;
    }
    if (h.major == 2 && (label == "ION ALPHA" || label == "ION BETA")) {
      auto& dst = label == "ION ALPHA" ? out.klobuchar.alpha : out.klobuchar.beta;
      for (std::size_t k = 0; k < 4; ++k) dst[k] = p.real(l, 2 + 12 * k, 12, label.c_str());
      (label == "ION ALPHA" ? have_alpha : have_beta) = true;
    } else if (h.major == 2 && label == "DELTA-UTC: A0,A1,T,W") {
      out.utc.a0_s = p.real(l, 3, 19, "A0");
      out.utc.a1_s_s = p.real(l, 22, 19, "A1");
      out.utc.tot_s = p.integer(l, 41, 9, "T");
      out.utc.wnt = p.integer(l, 50, 9, "W");
      out.utc.valid = true;
    } else if (h.major == 3 && label == "IONOSPHERIC CORR") {
      const std::string_view kind = trim(columns(l.text, 0, 4));
      if (kind == "GPSA" || kind == "GPSB") {
        auto& dst = kind == "GPSA" ? out.klobuchar.alpha : out.klobuchar.beta;
        for (std::size_t k = 0; k < 4; ++k) dst[k] = p.real(l, 5 + 12 * k, 12, "IONOSPHERIC CORR");
        (kind == "GPSA" ? have_alpha : have_beta) = true;
      }
    } else if (h.major == 3 && label == "TIME SYSTEM CORR") {
      if (trim(columns(l.text, 0, 4)) == "GPUT") {
        out.utc.a0_s = p.real(l, 5, 17, "A0");
        out.utc.a1_s_s = p.real(l, 22, 16, "A1");
        out.utc.tot_s = p.integer(l, 38, 7, "T");
        out.utc.wnt = p.integer(l, 45, 5, "W");
        out.utc.valid = true;
      }
    } else if (label == "LEAP SECONDS") {
      out.leap_seconds = p.integer(l, 0, 6, "leap seconds");
    }
  }
  p.fail(src.line_number(), "end of file before END OF HEADER");
}

/// Parse the 8 lines of a GPS record; `v3` selects the layout.
Ephemeris parse_gps_record(const Parser& p, const Record& lines, bool v3) {
  const Line& e = lines[0];
  Ephemeris eph;
  time::CalendarTime c;
  std::size_t vcol = 0;  // column of the first value on every line
  if (v3) {
    eph.prn = p.integer(e, 1, 2, "PRN");
    c.year = p.integer(e, 4, 4, "year");
    c.month = p.integer(e, 9, 2, "month");
    c.day = p.integer(e, 12, 2, "day");
    c.hour = p.integer(e, 15, 2, "hour");
    c.minute = p.integer(e, 18, 2, "minute");
    c.second = p.integer(e, 21, 2, "second");
    vcol = 4;
  } else {
    eph.prn = p.integer(e, 0, 2, "PRN");
    const int yy = p.integer(e, 3, 2, "year");
    if (yy < 0 || yy > 99) p.fail(e.number, "two-digit year out of range");
    c.year = time::year_from_two_digits(yy);
    c.month = p.integer(e, 6, 2, "month");
    c.day = p.integer(e, 9, 2, "day");
    c.hour = p.integer(e, 12, 2, "hour");
    c.minute = p.integer(e, 15, 2, "minute");
    c.second = p.real(e, 17, 5, "second");
    vcol = 3;
  }
  if (eph.prn < 1 || eph.prn > kMaxGpsPrn) p.fail(e.number, "GPS PRN " + std::to_string(eph.prn) + " out of range 1..32");
  if (c.month < 1 || c.month > 12 || c.day < 1 || c.day > 31 || c.hour < 0 || c.hour > 23 || c.minute < 0 ||
      c.minute > 59 || c.second < 0.0 || c.second >= 61.0) {
    p.fail(e.number, "invalid epoch (toc)");
  }
  eph.toc = time::GpsTime::from_calendar(c);
  const std::size_t clk_col = v3 ? 23 : 22;
  eph.af0_s = p.real(e, clk_col, 19, "af0");
  eph.af1_s_s = p.real(e, clk_col + 19, 19, "af1");
  eph.af2_s_s2 = p.real(e, clk_col + 38, 19, "af2");

  double o[7][4];
  for (std::size_t k = 0; k < 7; ++k) {
    const Line& l = lines[1 + k];
    for (std::size_t f = 0; f < 4; ++f) o[k][f] = p.real(l, vcol + 19 * f, 19, "orbit field");
  }
  auto line_no = [&](std::size_t bo) { return lines[bo].number; };

  eph.iode = static_cast<int>(std::lround(o[0][0]));
  eph.crs_m = o[0][1];
  eph.delta_n_rad_s = o[0][2];
  eph.m0_rad = o[0][3];
  eph.cuc_rad = o[1][0];
  eph.e = o[1][1];
  eph.cus_rad = o[1][2];
  eph.sqrt_a_sqrtm = o[1][3];
  const double toe_sow = o[2][0];
  eph.cic_rad = o[2][1];
  eph.omega0_rad = o[2][2];
  eph.cis_rad = o[2][3];
  eph.i0_rad = o[3][0];
  eph.crc_m = o[3][1];
  eph.omega_rad = o[3][2];
  eph.omega_dot_rad_s = o[3][3];
  eph.idot_rad_s = o[4][0];
  const double week = o[4][2];
  eph.sv_accuracy_m = o[5][0];
  eph.health = static_cast<int>(std::lround(o[5][1]));
  eph.tgd_s = o[5][2];
  eph.iodc = static_cast<int>(std::lround(o[5][3]));
  const double ttr = o[6][0];
  eph.fit_interval_h = o[6][1];

  // Semicircles as radians (kPiGps, IS-GPS-200 §20.3.3.4.3). Angles get a
  // whole turn of slack: a writer may not normalise them, and any finite angle
  // is harmless.
  constexpr double kSc = kPiGps;
  constexpr double kAngle_rad = 2.0 * kPi;
  check_broadcast_range(p, e.number, eph.af0_s, field_max(22, -31), "af0 (s)");
  check_broadcast_range(p, e.number, eph.af1_s_s, field_max(16, -43), "af1 (s/s)");
  check_broadcast_range(p, e.number, eph.af2_s_s2, field_max(8, -55), "af2 (s/s^2)");
  check_broadcast_range(p, line_no(1), eph.crs_m, field_max(16, -5), "Crs (m)");
  check_broadcast_range(p, line_no(1), eph.delta_n_rad_s, field_max(16, -43) * kSc, "Delta n (rad/s)");
  check_broadcast_range(p, line_no(1), eph.m0_rad, kAngle_rad, "M0 (rad)");
  check_broadcast_range(p, line_no(2), eph.cuc_rad, field_max(16, -29), "Cuc (rad)");
  check_broadcast_range(p, line_no(2), eph.cus_rad, field_max(16, -29), "Cus (rad)");
  check_broadcast_range(p, line_no(2), eph.sqrt_a_sqrtm, field_max(33, -19), "sqrt(A) (sqrt(m))");
  check_broadcast_range(p, line_no(3), eph.cic_rad, field_max(16, -29), "Cic (rad)");
  check_broadcast_range(p, line_no(3), eph.omega0_rad, kAngle_rad, "OMEGA0 (rad)");
  check_broadcast_range(p, line_no(3), eph.cis_rad, field_max(16, -29), "Cis (rad)");
  check_broadcast_range(p, line_no(4), eph.i0_rad, kAngle_rad, "i0 (rad)");
  check_broadcast_range(p, line_no(4), eph.crc_m, field_max(16, -5), "Crc (m)");
  check_broadcast_range(p, line_no(4), eph.omega_rad, kAngle_rad, "omega (rad)");
  check_broadcast_range(p, line_no(4), eph.omega_dot_rad_s, field_max(24, -43) * kSc, "OMEGA DOT (rad/s)");
  check_broadcast_range(p, line_no(5), eph.idot_rad_s, field_max(14, -43) * kSc, "IDOT (rad/s)");
  check_broadcast_range(p, line_no(6), eph.tgd_s, field_max(8, -31), "TGD (s)");
  if (eph.sqrt_a_sqrtm <= 0.0) p.fail(line_no(2), "sqrt(A) must be positive");
  if (eph.e < 0.0 || eph.e >= 1.0) p.fail(line_no(2), "eccentricity must be in [0, 1)");
  if (toe_sow < 0.0 || toe_sow >= kSecondsPerWeek) p.fail(line_no(3), "toe outside [0, 604800) s");
  if (week < 0.0 || week > 100000.0 || week != std::floor(week)) p.fail(line_no(5), "invalid GPS week");
  if (eph.iode < 0 || eph.iodc < 0) p.fail(line_no(1), "negative IODE/IODC");

  // toc (full calendar date) fixes toe's week: the one putting toe within
  // half a week of toc. The BO-5 week (RINEX 2.11 Table A4: continuous, goes
  // with toe) is only checked: writers may give it mod 1024 or as the week of
  // transmission (+-1), anything else is a corrupt record.
  int32_t toe_week = eph.toc.week();
  const double toe_minus_toc = time::GpsTime(toe_week, toe_sow) - eph.toc;
  if (toe_minus_toc > kHalfWeek_s) --toe_week;
  if (toe_minus_toc < -kHalfWeek_s) ++toe_week;
  eph.toe = time::GpsTime(toe_week, toe_sow);
  const int64_t week_diff = static_cast<int64_t>(week) - toe_week;
  const int64_t off = ((week_diff % 1024) + 1024 + 512) % 1024 - 512;  // in [-512, 512)
  if (off < -1 || off > 1) {
    p.fail(line_no(5), "GPS week " + std::to_string(static_cast<int64_t>(week)) + " does not match toc: toe is in week " +
                           std::to_string(toe_week) + " (mod 1024: " + std::to_string(toe_week % 1024) +
                           "), allowed are that week +-1, also mod 1024");
  }
  const double file_week = static_cast<double>(toe_week + off);  // BO-5 week with 1024 rollovers undone

  if (std::fabs(ttr - kUnknownTransmitTime_s) < 1.0) {
    eph.transmit_tow_s = 0.0;
    eph.transmit_known = false;
  } else {
    // Seconds relative to the start of the BO-5 week (negative = previous
    // week, RINEX 3.04 Table A6 note); re-referenced to toe's week.
    eph.transmit_tow_s = ttr + (file_week - eph.toe.week()) * kSecondsPerWeek;
    eph.transmit_known = true;
  }
  return eph;
}

}  // namespace

namespace {

NavData read_nav(text::LineSource& src) {
  const Parser p(src.name());
  NavData out;
  out.source = src.name();
  const Header h = parse_header(p, src, out);

  Record rec;
  while (src.next(rec[0])) {
    const Line& l = rec[0];
    if (blank(l.text)) continue;
    int n_lines = 8;
    bool gps = true;
    if (h.major == 3) {
      const char sys = l.text[0];
      n_lines = record_lines_v3(sys, h.version_x100);
      if (n_lines == 0) p.fail(l.number, std::string("unknown satellite system '") + sys + "' at record start");
      gps = sys == 'G';
    } else if (l.text[0] != ' ' && (l.text[0] < '0' || l.text[0] > '9')) {
      p.fail(l.number, "record does not start with a PRN");
    }
    // Continuation lines start with blanks (RINEX 2: 3X, RINEX 3: 4X).
    const std::size_t indent = h.major == 3 ? 4 : 3;
    for (int k = 1; k < n_lines; ++k) {
      Line& c = rec[static_cast<std::size_t>(k)];
      if (!src.next(c)) {
        p.fail(l.number, "truncated record: file ends after " + std::to_string(k) + " of " +
                             std::to_string(n_lines) + " lines");
      }
      if (!trim(columns(c.text, 0, indent)).empty()) {
        p.fail(c.number, "truncated record: expected continuation line " + std::to_string(k + 1) + " of " +
                             std::to_string(n_lines) + " for the record at line " + std::to_string(l.number));
      }
    }
    if (!gps) {
      ++out.skipped_records;
      continue;
    }
    if (out.ephemerides.size() >= kMaxEphemerides) {
      p.fail(l.number, "more than " + std::to_string(kMaxEphemerides) + " GPS ephemerides: not supported");
    }
    out.ephemerides.push_back(parse_gps_record(p, rec, h.major == 3));
  }
  return out;
}

}  // namespace

NavData read_rinex_nav(std::istream& in, const std::string& name) {
  text::LineSource src(in, name, kNavLimits);
  return read_nav(src);
}

NavData read_rinex_nav(const std::string& path) {
  text::LineSource src(path, kNavLimits);
  return read_nav(src);
}

NavData read_rinex_nav_files(const std::vector<std::string>& paths) {
  std::vector<NavData> files;
  files.reserve(paths.size());
  for (const std::string& p : paths) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) throw Error(p, 0, "nav file not found (or not a regular file)");
    files.push_back(read_rinex_nav(p));
    if (files.back().ephemerides.empty()) throw Error(p, 0, "no GPS ephemerides in the file");
  }
  return merge(files);
}

}  // namespace gnssemu::orbit

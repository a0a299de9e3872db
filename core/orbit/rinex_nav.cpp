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
#include "core/time/beidou_time.hpp"
#include "core/time/glonass_time.hpp"
#include "core/time/utc.hpp"

namespace gnssemu::orbit {

namespace {

// RINEX 2.11 §6.7 / 3.04 §8: transmission time 0.9999e9 = not known.
constexpr double kUnknownTransmitTime_s = 0.9999e9;
// Nav lines are 80 columns; a daily mixed IGS file holds ~25000 records,
// a year of 2-hourly GPS sets 140k. Beyond these the file is not a nav file.
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

/// A value the broadcast message cannot carry (the ICD's bit widths and
/// scale factors) is a corrupt record: far beyond them the orbit and clock
/// models give infinities.
void check_broadcast_range(const Parser& p, int line, double value, double max_abs, const char* field,
                           const char* icd = "IS-GPS-200 Table 20-III") {
  // The relative slack admits the extreme value printed with 12 decimals.
  if (!(std::fabs(value) <= max_abs * (1.0 + 1e-11))) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "%s %.6g outside what the broadcast message carries (|x| <= %.6g, %s)", field, value,
                  max_abs, icd);
    p.fail(line, msg);
  }
}

/// Fields whose width differs between the Keplerian systems' messages:
/// IS-GPS-200 Table 20-III (GPS, QZSS), Galileo OS SIS ICD Tables 57-60,
/// BDS-SIS-ICD-B1I 3.0 §5.2.4.
struct KeplerLimits {
  double af0_s, af1_s_s, af2_s_s2, crs_m, tgd_s;
  const char* icd;
};
KeplerLimits kepler_limits(GnssSystem sys) {
  switch (sys) {
    case GnssSystem::kGalileo:
      return {field_max(31, -34), field_max(21, -46), field_max(6, -59), field_max(16, -5), field_max(10, -32),
              "Galileo OS SIS ICD"};
    case GnssSystem::kBeiDou:
      return {field_max(24, -33), field_max(22, -50), field_max(11, -66), field_max(18, -6), 512 * 0.1e-9,
              "BDS-SIS-ICD-B1I"};
    default:
      return {field_max(22, -31), field_max(16, -43), field_max(8, -55), field_max(16, -5), field_max(8, -31),
              "IS-GPS-200 Table 20-III"};
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
  /// RINEX 2: the one system of the file (type N GPS, G GLONASS, H SBAS).
  GnssSystem v2_system = GnssSystem::kGps;
  /// RINEX 3: the file's system letter ('M' mixed).
  char v3_system = 'M';
};

void read_klobuchar_line(const Parser& p, const Line& l, std::size_t col, std::size_t width, const char* what,
                         std::array<double, 4>& dst) {
  for (std::size_t k = 0; k < 4; ++k) dst[k] = p.real(l, col + width * k, width, what);
}

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
    // RINEX 2.11 Table A3/A10/A16: N GPS, G GLONASS, H SBAS (GEO) navigation.
    switch (v.type) {
      case 'N': h.v2_system = GnssSystem::kGps; break;
      case 'G': h.v2_system = GnssSystem::kGlonass; break;
      case 'H': h.v2_system = GnssSystem::kSbas; break;
      default:
        p.fail(first.number, std::string("not a RINEX 2 GPS, GLONASS or SBAS navigation file (type '") + v.type + "')");
    }
  } else {
    if (v.type != 'N') p.fail(first.number, std::string("not a navigation file (type '") + v.type + "')");
    if (v.system != 'M' && !system_from_letter(v.system)) {
      p.fail(first.number, std::string("navigation file for system '") + v.system +
                               "', need G, R, E, C, J, S or mixed (M)");
    }
    h.v3_system = v.system;
  }
  out.rinex_version = h.version;

  bool have_alpha = false, have_beta = false, have_bds_alpha = false, have_bds_beta = false;
  Line l;
  while (src.next(l)) {
    const std::string label = text::rinex_label(l.text);
    if (label == "END OF HEADER") {
      out.klobuchar.valid = have_alpha && have_beta;
      out.beidou_klobuchar.valid = have_bds_alpha && have_bds_beta;
      return h;
    }
    if (h.major == 2 && (label == "ION ALPHA" || label == "ION BETA")) {
      auto& dst = label == "ION ALPHA" ? out.klobuchar.alpha : out.klobuchar.beta;
      read_klobuchar_line(p, l, 2, 12, label.c_str(), dst);
      (label == "ION ALPHA" ? have_alpha : have_beta) = true;
    } else if (h.major == 2 && label == "DELTA-UTC: A0,A1,T,W") {
      out.utc.a0_s = p.real(l, 3, 19, "A0");
      out.utc.a1_s_s = p.real(l, 22, 19, "A1");
      out.utc.tot_s = p.integer(l, 41, 9, "T");
      out.utc.wnt = p.integer(l, 50, 9, "W");
      out.utc.valid = true;
    } else if (h.major == 2 && label == "CORR TO SYSTEM TIME") {
      // RINEX 2.11 Table A10: year, month, day, -tau_c.
      out.glonass_utc.a0_s = -p.real(l, 21, 19, "-TAU C");
      out.glonass_utc.valid = true;
    } else if (h.major == 3 && label == "IONOSPHERIC CORR") {
      const std::string_view kind = trim(columns(l.text, 0, 4));
      if ((kind == "GPSA" && !have_alpha) || (kind == "GPSB" && !have_beta)) {
        read_klobuchar_line(p, l, 5, 12, "IONOSPHERIC CORR", kind == "GPSA" ? out.klobuchar.alpha : out.klobuchar.beta);
        (kind == "GPSA" ? have_alpha : have_beta) = true;
      } else if ((kind == "BDSA" && !have_bds_alpha) || (kind == "BDSB" && !have_bds_beta)) {
        read_klobuchar_line(p, l, 5, 12, "IONOSPHERIC CORR",
                            kind == "BDSA" ? out.beidou_klobuchar.alpha : out.beidou_klobuchar.beta);
        (kind == "BDSA" ? have_bds_alpha : have_bds_beta) = true;
      } else if (kind == "GAL" && !out.galileo_nequick.valid) {
        for (std::size_t k = 0; k < 3; ++k) out.galileo_nequick.ai[k] = p.real(l, 5 + 12 * k, 12, "IONOSPHERIC CORR");
        out.galileo_nequick.valid = true;
      }
    } else if (h.major == 3 && label == "TIME SYSTEM CORR") {
      const std::string_view kind = trim(columns(l.text, 0, 4));
      UtcParams* dst = kind == "GPUT" ? &out.utc : kind == "GLUT" ? &out.glonass_utc : nullptr;
      if (dst != nullptr) {
        dst->a0_s = p.real(l, 5, 17, "A0");
        dst->a1_s_s = p.real(l, 22, 16, "A1");
        dst->tot_s = p.integer(l, 38, 7, "T");
        dst->wnt = p.integer(l, 45, 5, "W");
        dst->valid = true;
      }
    } else if (label == "LEAP SECONDS") {
      out.leap_seconds = p.integer(l, 0, 6, "leap seconds");
    }
  }
  p.fail(src.line_number(), "end of file before END OF HEADER");
}

/// The satellite of a record's first line: RINEX 3 "G05"/"G 5", RINEX 2 an
/// I2 number (SBAS: PRN - 100) of the file's system.
SatId parse_sat_field(const Parser& p, const Line& e, bool v3, GnssSystem sys) {
  const int n = v3 ? p.integer(e, 1, 2, "satellite number") : p.integer(e, 0, 2, "satellite number");
  const SatId id(sys, n >= 0 && n <= 255 ? n : 0);
  if (n < 0 || n > 255 || !id.valid()) {
    const SatNumbering& r = numbering(sys);
    p.fail(e.number, std::string(system_name(sys)) + " satellite number " + std::to_string(n) + " out of range " +
                         std::to_string(r.first) + ".." + std::to_string(r.last));
  }
  return id;
}

/// The epoch of a record's first line as a calendar time in the system's
/// own scale (GPST, BDT, UTC for GLONASS).
time::CalendarTime parse_epoch(const Parser& p, const Line& e, bool v3) {
  time::CalendarTime c;
  if (v3) {
    c.year = p.integer(e, 4, 4, "year");
    c.month = p.integer(e, 9, 2, "month");
    c.day = p.integer(e, 12, 2, "day");
    c.hour = p.integer(e, 15, 2, "hour");
    c.minute = p.integer(e, 18, 2, "minute");
    c.second = p.integer(e, 21, 2, "second");
  } else {
    const int yy = p.integer(e, 3, 2, "year");
    if (yy < 0 || yy > 99) p.fail(e.number, "two-digit year out of range");
    c.year = time::year_from_two_digits(yy);
    c.month = p.integer(e, 6, 2, "month");
    c.day = p.integer(e, 9, 2, "day");
    c.hour = p.integer(e, 12, 2, "hour");
    c.minute = p.integer(e, 15, 2, "minute");
    c.second = p.real(e, 17, 5, "second");
  }
  if (c.month < 1 || c.month > 12 || c.day < 1 || c.day > 31 || c.hour < 0 || c.hour > 23 || c.minute < 0 ||
      c.minute > 59 || c.second < 0.0 || c.second >= 61.0) {
    p.fail(e.number, "invalid epoch (toc)");
  }
  return c;
}

/// The three values of a record's first line and the four of each further line.
struct Values {
  double clk[3];
  double o[7][4];
};
Values read_values(const Parser& p, const Record& lines, int n_lines, bool v3) {
  Values v{};
  const Line& e = lines[0];
  const std::size_t clk_col = v3 ? 23 : 22;
  const std::size_t vcol = v3 ? 4 : 3;  // column of the first value on every line
  for (std::size_t f = 0; f < 3; ++f) v.clk[f] = p.real(e, clk_col + 19 * f, 19, "clock field");
  for (std::size_t k = 0; k + 1 < static_cast<std::size_t>(n_lines) && k < 7; ++k) {
    for (std::size_t f = 0; f < 4; ++f) v.o[k][f] = p.real(lines[1 + k], vcol + 19 * f, 19, "orbit field");
  }
  return v;
}

/// Parse the 8 lines of a GPS, Galileo, BeiDou or QZSS record (RINEX 3.04
/// Tables A6, A8, A14, A12; RINEX 2.11 Table A4 for GPS); `v3` selects the
/// layout. Times go to GPST: BeiDou's BDT epoch and week + 14 s.
Ephemeris parse_kepler_record(const Parser& p, const Record& lines, bool v3, GnssSystem sys) {
  const Line& e = lines[0];
  Ephemeris eph;
  eph.sat = parse_sat_field(p, e, v3, sys);
  const bool bds = sys == GnssSystem::kBeiDou;
  // Week arithmetic runs on the system's own calendar grid (BDT week w is
  // GPS-grid week w + 1356), converted to GPST at the end.
  const time::GpsTime toc_sys = time::GpsTime::from_calendar(parse_epoch(p, e, v3));
  const Values v = read_values(p, lines, 8, v3);
  eph.af0_s = v.clk[0];
  eph.af1_s_s = v.clk[1];
  eph.af2_s_s2 = v.clk[2];
  const auto& o = v.o;
  auto line_no = [&](std::size_t bo) { return lines[bo].number; };

  eph.iode = static_cast<int>(std::lround(o[0][0]));  // IODE / IODnav / AODE
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
  const double ttr = o[6][0];
  switch (sys) {
    case GnssSystem::kGalileo:
      eph.gal_data_sources = static_cast<int>(std::lround(o[4][1]));
      eph.tgd2_s = o[5][2];  // BGD(E1,E5a)
      eph.tgd_s = o[5][3];   // BGD(E1,E5b): the I/NAV E1 user's
      break;
    case GnssSystem::kBeiDou:
      eph.tgd_s = o[5][2];   // TGD1 (B1I/B3I)
      eph.tgd2_s = o[5][3];  // TGD2 (B2I/B3I)
      eph.iodc = static_cast<int>(std::lround(o[6][1]));  // AODC
      break;
    default:
      eph.tgd_s = o[5][2];
      eph.iodc = static_cast<int>(std::lround(o[5][3]));
      if (sys == GnssSystem::kGps) eph.fit_interval_h = o[6][1];
      break;
  }

  // Semicircles as radians (kPiGps, IS-GPS-200 §20.3.3.4.3). Angles get a
  // whole turn of slack: a writer may not normalise them, and any finite angle
  // is harmless.
  constexpr double kSc = kPiGps;
  constexpr double kAngle_rad = 2.0 * kPi;
  const KeplerLimits lim = kepler_limits(sys);
  check_broadcast_range(p, e.number, eph.af0_s, lim.af0_s, "af0 (s)", lim.icd);
  check_broadcast_range(p, e.number, eph.af1_s_s, lim.af1_s_s, "af1 (s/s)", lim.icd);
  check_broadcast_range(p, e.number, eph.af2_s_s2, lim.af2_s_s2, "af2 (s/s^2)", lim.icd);
  check_broadcast_range(p, line_no(1), eph.crs_m, lim.crs_m, "Crs (m)", lim.icd);
  check_broadcast_range(p, line_no(1), eph.delta_n_rad_s, field_max(16, -43) * kSc, "Delta n (rad/s)", lim.icd);
  check_broadcast_range(p, line_no(1), eph.m0_rad, kAngle_rad, "M0 (rad)", lim.icd);
  // BeiDou's Cuc/Cus/Cic/Cis are 18-bit with 2^-31: the same span as GPS's 16-bit 2^-29.
  check_broadcast_range(p, line_no(2), eph.cuc_rad, field_max(16, -29), "Cuc (rad)", lim.icd);
  check_broadcast_range(p, line_no(2), eph.cus_rad, field_max(16, -29), "Cus (rad)", lim.icd);
  check_broadcast_range(p, line_no(2), eph.sqrt_a_sqrtm, field_max(33, -19), "sqrt(A) (sqrt(m))", lim.icd);
  check_broadcast_range(p, line_no(3), eph.cic_rad, field_max(16, -29), "Cic (rad)", lim.icd);
  check_broadcast_range(p, line_no(3), eph.omega0_rad, kAngle_rad, "OMEGA0 (rad)", lim.icd);
  check_broadcast_range(p, line_no(3), eph.cis_rad, field_max(16, -29), "Cis (rad)", lim.icd);
  check_broadcast_range(p, line_no(4), eph.i0_rad, kAngle_rad, "i0 (rad)", lim.icd);
  check_broadcast_range(p, line_no(4), eph.crc_m, lim.crs_m, "Crc (m)", lim.icd);
  check_broadcast_range(p, line_no(4), eph.omega_rad, kAngle_rad, "omega (rad)", lim.icd);
  check_broadcast_range(p, line_no(4), eph.omega_dot_rad_s, field_max(24, -43) * kSc, "OMEGA DOT (rad/s)", lim.icd);
  check_broadcast_range(p, line_no(5), eph.idot_rad_s, field_max(14, -43) * kSc, "IDOT (rad/s)", lim.icd);
  check_broadcast_range(p, line_no(6), eph.tgd_s, lim.tgd_s, "TGD (s)", lim.icd);
  check_broadcast_range(p, line_no(6), eph.tgd2_s, lim.tgd_s, "TGD2/BGD (s)", lim.icd);
  if (eph.sqrt_a_sqrtm <= 0.0) p.fail(line_no(2), "sqrt(A) must be positive");
  if (eph.e < 0.0 || eph.e >= 1.0) p.fail(line_no(2), "eccentricity must be in [0, 1)");
  if (toe_sow < 0.0 || toe_sow >= kSecondsPerWeek) p.fail(line_no(3), "toe outside [0, 604800) s");
  if (week < 0.0 || week > 100000.0 || week != std::floor(week)) {
    p.fail(line_no(5), "invalid " + std::string(system_name(sys)) + " week");
  }
  if (eph.iode < 0 || eph.iodc < 0) p.fail(line_no(1), "negative IODE/IODC");
  if (sys == GnssSystem::kGalileo) {
    // RINEX 3.04 Table A8: bits 8 and 9 say which pair the clock is for; never both.
    const int ds = eph.gal_data_sources;
    if (ds < 0 || ds > 0x3ff || ((ds & kGalClockE5a) != 0 && (ds & kGalClockE5b) != 0)) {
      p.fail(line_no(5), "Galileo data sources " + std::to_string(ds) +
                             ": bits 8 (E5a clock) and 9 (E5b clock) exclude each other (RINEX 3.04 Table A8)");
    }
  }

  // toc (full calendar date) fixes toe's week: the one putting toe within
  // half a week of toc. The file's week (GPS/Galileo: GPS week, RINEX 2.11
  // Table A4 continuous; BeiDou: BDT week) is only checked: writers may give
  // it mod 1024 or as the week of transmission (+-1), anything else is a
  // corrupt record.
  const int32_t grid_offset = bds ? time::kBdtWeekOrigin : 0;
  int32_t toe_week = toc_sys.week();
  const double toe_minus_toc = time::GpsTime(toe_week, toe_sow) - toc_sys;
  if (toe_minus_toc > kHalfWeek_s) --toe_week;
  if (toe_minus_toc < -kHalfWeek_s) ++toe_week;
  const time::GpsTime toe_sys(toe_week, toe_sow);
  const int32_t own_toe_week = toe_week - grid_offset;
  const int64_t week_diff = static_cast<int64_t>(week) - own_toe_week;
  const int64_t off = ((week_diff % 1024) + 1024 + 512) % 1024 - 512;  // in [-512, 512)
  if (off < -1 || off > 1) {
    p.fail(line_no(5), std::string(system_name(sys)) + " week " + std::to_string(static_cast<int64_t>(week)) +
                           " does not match toc: toe is in week " + std::to_string(own_toe_week) + " (mod 1024: " +
                           std::to_string(own_toe_week % 1024) + "), allowed are that week +-1, also mod 1024");
  }
  const double file_week = static_cast<double>(toe_week + off);  // week with 1024 rollovers undone, grid
  const double to_gpst_s = bds ? time::kGpsMinusBdt_s : 0.0;
  eph.toc = bds ? toc_sys + to_gpst_s : toc_sys;
  eph.toe = bds ? toe_sys + to_gpst_s : toe_sys;

  if (std::fabs(ttr - kUnknownTransmitTime_s) < 1.0) {
    eph.transmit_tow_s = 0.0;
    eph.transmit_known = false;
  } else {
    // Seconds relative to the start of the file's week (negative = previous
    // week, RINEX 3.04 Table A6 note); re-referenced to toe's GPS week.
    eph.transmit_tow_s = ttr + (file_week - toe_sys.week()) * kSecondsPerWeek;
    if (bds) eph.transmit_tow_s += to_gpst_s - (eph.toe.week() - toe_sys.week()) * kSecondsPerWeek;
    eph.transmit_known = true;
  }
  return eph;
}

void check_state_vector(const Parser& p, const Record& lines, const Ephemeris& eph, const char* icd) {
  // Orbits up to GEO (42000 km) with margin; speeds and accelerations of
  // such orbits with margin: beyond them a record is corrupt.
  const Ecef* v[3] = {&eph.pos_m, &eph.vel_m_s, &eph.acc_m_s2};
  const double lim[3] = {1.0e8, 1.0e4, 1.0e-2};
  const char* what[3] = {"position (m)", "velocity (m/s)", "acceleration (m/s^2)"};
  for (int k = 0; k < 3; ++k) {
    const double c[3] = {v[k]->x, v[k]->y, v[k]->z};
    for (int a = 0; a < 3; ++a) check_broadcast_range(p, lines[1 + a].number, c[a], lim[k], what[k], icd);
  }
}

/// GLONASS record (RINEX 3.04 Table A10 / 3.05 A11, RINEX 2.11 Table A11):
/// epoch tb in UTC, -tau_n, +gamma_n, frame time; X/Y/Z lines in km with
/// health Bn, frequency number k, age E.
Ephemeris parse_glonass_record(const Parser& p, const Record& lines, int n_lines, bool v3,
                               std::optional<int> leap_s) {
  const Line& e = lines[0];
  Ephemeris eph;
  eph.sat = parse_sat_field(p, e, v3, GnssSystem::kGlonass);
  time::CalendarTime c = parse_epoch(p, e, v3);
  const Values v = read_values(p, lines, n_lines, v3);
  // tb is a multiple of 15 min of the GLONASST day, so of UTC too: round
  // the epoch to it, as RTKLIB does (decode_geph).
  const time::GpsTime epoch_utc_grid = time::GpsTime::from_calendar(c);
  const time::GpsTime tb_utc_grid(epoch_utc_grid.week(), std::floor((epoch_utc_grid.tow_s() + 450.0) / 900.0) * 900.0);
  c = tb_utc_grid.to_calendar();
  eph.toe = time::utc_to_gps(c, leap_s);
  eph.toc = eph.toe;
  eph.iode = static_cast<int>(std::fmod(tb_utc_grid.tow_s() + time::kGlonasstMinusUtc_s, kSecondsPerDay) / 900.0 + 0.5);
  eph.tau_n_s = -v.clk[0];
  eph.gamma_n = v.clk[1];
  const double tk = v.clk[2];
  const auto& o = v.o;
  eph.pos_m = Ecef(o[0][0] * 1e3, o[1][0] * 1e3, o[2][0] * 1e3);
  eph.vel_m_s = Ecef(o[0][1] * 1e3, o[1][1] * 1e3, o[2][1] * 1e3);
  eph.acc_m_s2 = Ecef(o[0][2] * 1e3, o[1][2] * 1e3, o[2][2] * 1e3);
  eph.health = static_cast<int>(std::lround(o[0][3]));
  const double k = o[1][3];
  eph.glo_age_days = static_cast<int>(std::lround(o[2][3]));
  if (k != std::floor(k) || k < kGlonassMinChannel || k > kGlonassMaxChannel) {
    char msg[120];
    std::snprintf(msg, sizeof msg, "GLONASS frequency number %g out of range %d..%+d (ICD GLONASS Ed. 5.1)", k,
                  kGlonassMinChannel, kGlonassMaxChannel);
    p.fail(lines[2].number, msg);
  }
  eph.glo_channel = static_cast<int>(k);
  // ICD GLONASS Ed. 5.1 Table 4.5: tau_n 22 bits x 2^-30 s, gamma_n 11 bits x 2^-40.
  constexpr const char* kIcd = "ICD GLONASS Ed. 5.1 Table 4.5";
  check_broadcast_range(p, e.number, eph.tau_n_s, field_max(22, -30), "tau_n (s)", kIcd);
  check_broadcast_range(p, e.number, eph.gamma_n, field_max(11, -40), "gamma_n", kIcd);
  check_state_vector(p, lines, eph, kIcd);
  if (eph.health < 0 || eph.glo_age_days < 0 || eph.glo_age_days > 31) p.fail(lines[1].number, "invalid health or age");
  // Frame time: RINEX 2 seconds of the UTC day, RINEX 3 of the UTC week;
  // the one nearest tb. Outside its range it is taken as unknown.
  const double period = v3 ? kSecondsPerWeek : kSecondsPerDay;
  if (tk >= 0.0 && tk < period) {
    const double start = v3 ? 0.0 : std::floor(tb_utc_grid.tow_s() / kSecondsPerDay) * kSecondsPerDay;
    double dt = start + tk - tb_utc_grid.tow_s();
    dt -= std::round(dt / period) * period;
    const time::GpsTime tof = eph.toe + dt;
    eph.transmit_tow_s = tof - time::GpsTime(eph.toe.week(), 0.0);
    eph.transmit_known = true;
  }
  return eph;
}

/// SBAS record (RINEX 3.04 Table A16, RINEX 2.11 Table A16): epoch t0 in
/// GPST, aGf0, aGf1, transmission time; X/Y/Z lines in km with health, URA,
/// IODN.
Ephemeris parse_sbas_record(const Parser& p, const Record& lines, bool v3) {
  const Line& e = lines[0];
  Ephemeris eph;
  eph.sat = parse_sat_field(p, e, v3, GnssSystem::kSbas);
  eph.toe = time::GpsTime::from_calendar(parse_epoch(p, e, v3));
  eph.toc = eph.toe;
  const Values v = read_values(p, lines, 4, v3);
  eph.af0_s = v.clk[0];
  eph.af1_s_s = v.clk[1];
  const double ttr = v.clk[2];
  const auto& o = v.o;
  eph.pos_m = Ecef(o[0][0] * 1e3, o[1][0] * 1e3, o[2][0] * 1e3);
  eph.vel_m_s = Ecef(o[0][1] * 1e3, o[1][1] * 1e3, o[2][1] * 1e3);
  eph.acc_m_s2 = Ecef(o[0][2] * 1e3, o[1][2] * 1e3, o[2][2] * 1e3);
  eph.health = static_cast<int>(std::lround(o[0][3]));
  eph.sv_accuracy_m = o[1][3];
  eph.iode = static_cast<int>(std::lround(o[2][3]));
  // RTCA DO-229 Table A-18: aGf0 12 bits x 2^-31 s, aGf1 8 bits x 2^-40 s/s.
  constexpr const char* kIcd = "RTCA DO-229 Table A-18";
  check_broadcast_range(p, e.number, eph.af0_s, field_max(12, -31), "aGf0 (s)", kIcd);
  check_broadcast_range(p, e.number, eph.af1_s_s, field_max(8, -40), "aGf1 (s/s)", kIcd);
  check_state_vector(p, lines, eph, kIcd);
  if (std::fabs(ttr - kUnknownTransmitTime_s) >= 1.0 && ttr >= 0.0 && ttr < kSecondsPerWeek) {
    double dt = ttr - eph.toe.tow_s();
    dt -= std::round(dt / kSecondsPerWeek) * kSecondsPerWeek;
    eph.transmit_tow_s = (eph.toe + dt) - time::GpsTime(eph.toe.week(), 0.0);
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
  const bool v3 = h.major == 3;

  Record rec;
  while (src.next(rec[0])) {
    const Line& l = rec[0];
    if (blank(l.text)) continue;
    GnssSystem sys = h.v2_system;
    bool known = true;
    int n_lines = sys == GnssSystem::kGps ? 8 : 4;
    if (v3) {
      const char letter = l.text[0];
      n_lines = record_lines_v3(letter, h.version_x100);
      if (n_lines == 0) p.fail(l.number, std::string("unknown satellite system '") + letter + "' at record start");
      if (h.v3_system != 'M' && letter != h.v3_system) {
        p.fail(l.number, std::string("record of system '") + letter + "' in a navigation file for system '" +
                             h.v3_system + "' only");
      }
      const auto s = system_from_letter(letter);
      known = s.has_value();
      if (known) sys = *s;
    } else if (l.text[0] != ' ' && (l.text[0] < '0' || l.text[0] > '9')) {
      p.fail(l.number, "record does not start with a satellite number");
    }
    // Continuation lines start with blanks (RINEX 2: 3X, RINEX 3: 4X).
    const std::size_t indent = v3 ? 4 : 3;
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
    if (!known) {  // a system without a row in the system table (I/NavIC)
      ++out.skipped_records;
      continue;
    }
    if (out.ephemerides.size() >= kMaxEphemerides) {
      p.fail(l.number, "more than " + std::to_string(kMaxEphemerides) + " ephemerides: not supported");
    }
    switch (system_info(sys).orbit) {
      case OrbitKind::kKepler: out.ephemerides.push_back(parse_kepler_record(p, rec, v3, sys)); break;
      case OrbitKind::kStateVector:
        out.ephemerides.push_back(parse_glonass_record(p, rec, n_lines, v3, out.leap_seconds));
        break;
      case OrbitKind::kSbasPoly: out.ephemerides.push_back(parse_sbas_record(p, rec, v3)); break;
    }
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
    if (files.back().ephemerides.empty()) throw Error(p, 0, "no ephemerides in the file");
  }
  return merge(files);
}

}  // namespace gnssemu::orbit

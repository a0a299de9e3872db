// SPDX-License-Identifier: Apache-2.0
#include "core/rinex/rinex_nav_writer.hpp"

#include <cmath>

#include "core/common/constants.hpp"
#include "core/rinex/rinex_format.hpp"
#include "core/time/beidou_time.hpp"
#include "core/time/utc.hpp"

namespace gnssemu::rinex {

namespace {

// RINEX 3.04 §8: transmission time not known.
constexpr double kUnknownTransmitTime_s = 0.9999e9;

/// A D19.12 field (written with E, as RTKLIB and most writers do).
void real(LineBuf& l, double v) noexcept { l.add("%19.12E", std::isfinite(v) ? v + 0.0 : 0.0); }

/// A record's first line: satellite, epoch (calendar in the system's scale), three values.
void first_line(LineBuf& l, const SatId& sat, const time::CalendarTime& c, double a, double b, double d) noexcept {
  l.add("%c%02d %04d %02d %02d %02d %02d %02d", system_letter(sat.system), sat.number, c.year, c.month, c.day, c.hour,
        c.minute, static_cast<int>(std::lround(c.second)));
  real(l, a);
  real(l, b);
  real(l, d);
}

void orbit_line(std::ostream& out, LineBuf& l, double a, double b, double c, double d) noexcept {
  l.add("    ");
  real(l, a);
  real(l, b);
  real(l, c);
  real(l, d);
  l.flush(out);
}

/// Whole seconds of a calendar time rounded (a toc is on whole seconds).
time::CalendarTime rounded(const time::GpsTime& t) noexcept {
  return time::GpsTime(t.week(), std::round(t.tow_s())).to_calendar();
}

void write_kepler(std::ostream& out, LineBuf& l, const orbit::Ephemeris& e) {
  const bool bds = e.sat.system == GnssSystem::kBeiDou;
  const double to_sys_s = bds ? -time::kGpsMinusBdt_s : 0.0;
  const time::GpsTime toc_sys = e.toc + to_sys_s;
  const time::GpsTime toe_sys = e.toe + to_sys_s;
  const int32_t week = toe_sys.week() - (bds ? time::kBdtWeekOrigin : 0);
  first_line(l, e.sat, rounded(toc_sys), e.af0_s, e.af1_s_s, e.af2_s_s2);
  l.flush(out);
  orbit_line(out, l, e.iode, e.crs_m, e.delta_n_rad_s, e.m0_rad);
  orbit_line(out, l, e.cuc_rad, e.e, e.cus_rad, e.sqrt_a_sqrtm);
  orbit_line(out, l, toe_sys.tow_s(), e.cic_rad, e.omega0_rad, e.cis_rad);
  orbit_line(out, l, e.i0_rad, e.crc_m, e.omega_rad, e.omega_dot_rad_s);
  // Transmission time in seconds of the record's week (negative: the one before).
  double ttr = kUnknownTransmitTime_s;
  if (e.transmit_known) ttr = e.transmit_tow_s + (e.toe.week() - toe_sys.week()) * kSecondsPerWeek + to_sys_s;
  switch (e.sat.system) {
    case GnssSystem::kGalileo:
      orbit_line(out, l, e.idot_rad_s, e.gal_data_sources, week, 0.0);
      orbit_line(out, l, e.sv_accuracy_m, e.health, e.tgd2_s, e.tgd_s);
      orbit_line(out, l, ttr, 0.0, 0.0, 0.0);
      break;
    case GnssSystem::kBeiDou:
      orbit_line(out, l, e.idot_rad_s, 0.0, week, 0.0);
      orbit_line(out, l, e.sv_accuracy_m, e.health, e.tgd_s, e.tgd2_s);
      orbit_line(out, l, ttr, e.iodc, 0.0, 0.0);
      break;
    default:
      orbit_line(out, l, e.idot_rad_s, 0.0, week, 0.0);
      orbit_line(out, l, e.sv_accuracy_m, e.health, e.tgd_s, e.iodc);
      orbit_line(out, l, ttr, e.fit_interval_h, 0.0, 0.0);
      break;
  }
}

void write_glonass(std::ostream& out, LineBuf& l, const orbit::Ephemeris& e, std::optional<int> leap_s) {
  const time::CalendarTime tb_utc = time::gps_to_utc(e.toe, leap_s);
  // Frame time tk as seconds of the UTC week (RINEX 3.04 Table A10).
  const time::GpsTime tb_utc_grid = time::GpsTime::from_calendar(tb_utc);
  double tk = kUnknownTransmitTime_s;
  if (e.transmit_known) {
    const time::GpsTime tof = time::GpsTime(e.toe.week(), 0.0) + e.transmit_tow_s;
    tk = std::fmod(tb_utc_grid.tow_s() + (tof - e.toe) + kSecondsPerWeek, kSecondsPerWeek);
  }
  time::CalendarTime c = tb_utc;
  c.second = std::round(c.second);
  first_line(l, e.sat, c, -e.tau_n_s, e.gamma_n, tk);
  l.flush(out);
  orbit_line(out, l, e.pos_m.x * 1e-3, e.vel_m_s.x * 1e-3, e.acc_m_s2.x * 1e-3, e.health);
  orbit_line(out, l, e.pos_m.y * 1e-3, e.vel_m_s.y * 1e-3, e.acc_m_s2.y * 1e-3, e.glo_channel);
  orbit_line(out, l, e.pos_m.z * 1e-3, e.vel_m_s.z * 1e-3, e.acc_m_s2.z * 1e-3, e.glo_age_days);
}

void write_sbas(std::ostream& out, LineBuf& l, const orbit::Ephemeris& e) {
  const double ttr =
      e.transmit_known ? std::fmod((time::GpsTime(e.toe.week(), 0.0) + e.transmit_tow_s).tow_s(), kSecondsPerWeek)
                       : kUnknownTransmitTime_s;
  first_line(l, e.sat, rounded(e.toe), e.af0_s, e.af1_s_s, ttr);
  l.flush(out);
  orbit_line(out, l, e.pos_m.x * 1e-3, e.vel_m_s.x * 1e-3, e.acc_m_s2.x * 1e-3, e.health);
  orbit_line(out, l, e.pos_m.y * 1e-3, e.vel_m_s.y * 1e-3, e.acc_m_s2.y * 1e-3, e.sv_accuracy_m);
  orbit_line(out, l, e.pos_m.z * 1e-3, e.vel_m_s.z * 1e-3, e.acc_m_s2.z * 1e-3, e.iode);
}

void klobuchar_lines(std::ostream& out, LineBuf& l, const char* a, const char* b, const orbit::KlobucharParams& k) {
  if (!k.valid) return;
  for (int pass = 0; pass < 2; ++pass) {
    l.add("%-4s ", pass == 0 ? a : b);
    for (double v : pass == 0 ? k.alpha : k.beta) l.add("%12.4E", v);
    header_line(out, l, "IONOSPHERIC CORR");
  }
}

void time_corr_line(std::ostream& out, LineBuf& l, const char* kind, const orbit::UtcParams& u) {
  if (!u.valid) return;
  l.add("%-4s %17.10E%16.9E%7d%5d", kind, u.a0_s, u.a1_s_s, static_cast<int>(std::lround(u.tot_s)), u.wnt);
  header_line(out, l, "TIME SYSTEM CORR");
}

}  // namespace

void write_nav(std::ostream& out, const orbit::NavData& nav) {
  LineBuf l;
  version_line(out, "N: GNSS NAV DATA", "M: MIXED");
  program_line(out);
  klobuchar_lines(out, l, "GPSA", "GPSB", nav.klobuchar);
  if (nav.galileo_nequick.valid) {
    l.add("%-4s ", "GAL");
    for (double v : nav.galileo_nequick.ai) l.add("%12.4E", v);
    l.add("%12.4E", 0.0);
    header_line(out, l, "IONOSPHERIC CORR");
  }
  klobuchar_lines(out, l, "BDSA", "BDSB", nav.beidou_klobuchar);
  time_corr_line(out, l, "GPUT", nav.utc);
  time_corr_line(out, l, "GLUT", nav.glonass_utc);
  if (nav.leap_seconds) {
    l.add("%6d", *nav.leap_seconds);
    header_line(out, l, "LEAP SECONDS");
  }
  header_line(out, l, "END OF HEADER");
  for (const orbit::Ephemeris& e : nav.ephemerides) {
    switch (system_info(e.sat.system).orbit) {
      case OrbitKind::kKepler: write_kepler(out, l, e); break;
      case OrbitKind::kStateVector: write_glonass(out, l, e, nav.leap_seconds); break;
      case OrbitKind::kSbasPoly: write_sbas(out, l, e); break;
    }
  }
  out.flush();
}

}  // namespace gnssemu::rinex

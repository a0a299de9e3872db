// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/rtcm/rtcm_ephemeris.hpp"

#include <array>
#include <cmath>

#include "core/common/constants.hpp"
#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"
#include "core/time/beidou_time.hpp"
#include "core/time/galileo_time.hpp"
#include "core/time/glonass_time.hpp"

namespace gnssemu::protocol::rtcm {

namespace {

constexpr double kSecondsPerDay = 86400.0;

std::int64_t rnd(double v) noexcept { return static_cast<std::int64_t>(std::floor(v + 0.5)); }
/// v / 2^-n.
std::int64_t scaled(double v, int n) noexcept { return rnd(std::ldexp(v, n)); }
/// An angle in rad as semicircles / 2^-n.
std::int64_t semicircles(double rad, int n) noexcept { return scaled(rad / kPi, n); }

void finish(const Payload& buf, const BitWriter& w, std::string& out) {
  append_frame(std::span<const std::uint8_t>(buf.data(), w.bytes()), out);
}

/// 1019: GPS LNAV ephemeris, 488 bits.
void write_gps(const orbit::Ephemeris& e, std::string& out) {
  Payload buf;
  BitWriter w(buf);
  const double toc_s = e.toc - time::GpsTime(e.toe.week(), 0.0);
  w.u(12, 1019);
  w.u(6, static_cast<std::uint64_t>(e.sat.prn()));
  w.u(10, static_cast<std::uint64_t>(e.toe.week() % time::kGpsWeekModulus));
  w.u(4, static_cast<std::uint64_t>(gps_ura_index(e.sv_accuracy_m)));
  w.u(2, 1);  // L2 codes: P code (not in RINEX 3 nav as we keep it)
  w.s(14, semicircles(e.idot_rad_s, 43));
  w.u(8, static_cast<std::uint64_t>(e.iode & 0xFF));
  w.u(16, static_cast<std::uint64_t>(rnd(toc_s / 16.0)));
  w.s(8, scaled(e.af2_s_s2, 55));
  w.s(16, scaled(e.af1_s_s, 43));
  w.s(22, scaled(e.af0_s, 31));
  w.u(10, static_cast<std::uint64_t>(e.iodc & 0x3FF));
  w.s(16, scaled(e.crs_m, 5));
  w.s(16, semicircles(e.delta_n_rad_s, 43));
  w.s(32, semicircles(e.m0_rad, 31));
  w.s(16, scaled(e.cuc_rad, 29));
  w.u(32, static_cast<std::uint64_t>(scaled(e.e, 33)));
  w.s(16, scaled(e.cus_rad, 29));
  w.u(32, static_cast<std::uint64_t>(scaled(e.sqrt_a_sqrtm, 19)));
  w.u(16, static_cast<std::uint64_t>(rnd(e.toe.tow_s() / 16.0)));
  w.s(16, scaled(e.cic_rad, 29));
  w.s(32, semicircles(e.omega0_rad, 31));
  w.s(16, scaled(e.cis_rad, 29));
  w.s(32, semicircles(e.i0_rad, 31));
  w.s(16, scaled(e.crc_m, 5));
  w.s(32, semicircles(e.omega_rad, 31));
  w.s(24, semicircles(e.omega_dot_rad_s, 43));
  w.s(8, scaled(e.tgd_s, 31));
  w.u(6, static_cast<std::uint64_t>(e.health & 0x3F));
  w.u(1, 0);  // L2 P data flag
  w.u(1, e.fit_interval_h > 4.0 ? 1 : 0);
  finish(buf, w, out);
}

/// Seconds of the GLONASST day and the day count of a GPS instant.
struct GlonassDay {
  double tod_s;
  int nt;  ///< day within the four-year interval, 1..1461
};

GlonassDay glonass_day(const time::GpsTime& t, int leap_s) noexcept {
  const time::GpsTime g = t + (time::kGlonasstMinusUtc_s - leap_s);
  const double day_f = std::floor(g.tow_s() / kSecondsPerDay);
  const std::int64_t days = time::days_from_civil(1980, 1, 6) + static_cast<std::int64_t>(g.week()) * 7 +
                            static_cast<std::int64_t>(day_f);
  int y = 0, mo = 0, d = 0;
  time::civil_from_days(days, y, mo, d);
  const int first_year = y - ((y - time::kGlonassFirstCycleYear) % 4 + 4) % 4;
  const auto nt = static_cast<int>(days - time::days_from_civil(first_year, 1, 1) + 1);
  return {g.tow_s() - day_f * kSecondsPerDay, nt};
}

void write_glonass(const orbit::Ephemeris& e, int leap_s, std::string& out) {
  Payload buf;
  BitWriter w(buf);
  const time::GpsTime tof =
      e.transmit_known ? time::GpsTime(e.toe.week(), 0.0) + e.transmit_tow_s : e.toe - 900.0;
  const GlonassDay tk = glonass_day(tof, leap_s);
  const GlonassDay tb = glonass_day(e.toe, leap_s);
  const auto tk_h = static_cast<int>(tk.tod_s / 3600.0);
  const auto tk_m = static_cast<int>((tk.tod_s - tk_h * 3600.0) / 60.0);
  const auto tk_30 = static_cast<int>(rnd((tk.tod_s - tk_h * 3600.0 - tk_m * 60.0) / 30.0));
  w.u(12, 1020);
  w.u(6, static_cast<std::uint64_t>(e.sat.number));
  w.u(5, static_cast<std::uint64_t>(e.glo_channel + 7));
  w.u(1, 0);  // almanac health (Cn)
  w.u(1, 0);  // almanac health availability
  w.u(2, 0);  // P1
  w.u(5, static_cast<std::uint64_t>(tk_h));
  w.u(6, static_cast<std::uint64_t>(tk_m));
  w.u(1, static_cast<std::uint64_t>(tk_30 & 1));
  w.u(1, static_cast<std::uint64_t>(e.health & 1));  // Bn
  w.u(1, 0);                                         // P2
  w.u(7, static_cast<std::uint64_t>(rnd(tb.tod_s / 900.0)));
  const std::array<double, 3> p{e.pos_m.x, e.pos_m.y, e.pos_m.z};
  const std::array<double, 3> v{e.vel_m_s.x, e.vel_m_s.y, e.vel_m_s.z};
  const std::array<double, 3> a{e.acc_m_s2.x, e.acc_m_s2.y, e.acc_m_s2.z};
  for (std::size_t i = 0; i < 3; ++i) {
    w.sm(24, scaled(v[i] * 1e-3, 20));
    w.sm(27, scaled(p[i] * 1e-3, 11));
    w.sm(5, scaled(a[i] * 1e-3, 30));
  }
  w.u(1, 0);  // P3
  w.sm(11, scaled(e.gamma_n, 40));
  w.u(2, 0);  // P
  w.u(1, 0);  // ln (third string)
  w.sm(22, scaled(e.tau_n_s, 30));
  w.sm(5, 0);  // delta tau_n
  w.u(5, static_cast<std::uint64_t>(e.glo_age_days & 0x1F));
  w.u(1, 0);  // P4
  w.u(4, 0);  // FT accuracy index
  w.u(11, static_cast<std::uint64_t>(tk.nt));
  w.u(2, 1);  // M: GLONASS-M
  w.u(1, 0);  // no additional data (NA, tau_c, N4, tau_GPS, ln)
  w.u(11, 0);
  w.u(32, 0);
  w.u(5, 0);
  w.u(22, 0);
  w.u(1, 0);
  w.u(7, 0);  // reserved
  finish(buf, w, out);
}

void write_beidou(const orbit::Ephemeris& e, std::string& out) {
  Payload buf;
  BitWriter w(buf);
  const time::WeekTime toe = time::bdt_from_gps(e.toe);
  const time::WeekTime toc = time::bdt_from_gps(e.toc);
  w.u(12, 1042);
  w.u(6, static_cast<std::uint64_t>(e.sat.prn()));
  w.u(13, static_cast<std::uint64_t>(toe.week % time::kBeiDouWeekModulus));
  w.u(4, static_cast<std::uint64_t>(gps_ura_index(e.sv_accuracy_m)));
  w.s(14, semicircles(e.idot_rad_s, 43));
  w.u(5, static_cast<std::uint64_t>(e.iode & 0x1F));
  w.u(17, static_cast<std::uint64_t>(rnd(toc.tow_s / 8.0)));
  w.s(11, scaled(e.af2_s_s2, 66));
  w.s(22, scaled(e.af1_s_s, 50));
  w.s(24, scaled(e.af0_s, 33));
  w.u(5, static_cast<std::uint64_t>(e.iodc & 0x1F));
  w.s(18, scaled(e.crs_m, 6));
  w.s(16, semicircles(e.delta_n_rad_s, 43));
  w.s(32, semicircles(e.m0_rad, 31));
  w.s(18, scaled(e.cuc_rad, 31));
  w.u(32, static_cast<std::uint64_t>(scaled(e.e, 33)));
  w.s(18, scaled(e.cus_rad, 31));
  w.u(32, static_cast<std::uint64_t>(scaled(e.sqrt_a_sqrtm, 19)));
  w.u(17, static_cast<std::uint64_t>(rnd(toe.tow_s / 8.0)));
  w.s(18, scaled(e.cic_rad, 31));
  w.s(32, semicircles(e.omega0_rad, 31));
  w.s(18, scaled(e.cis_rad, 31));
  w.s(32, semicircles(e.i0_rad, 31));
  w.s(18, scaled(e.crc_m, 6));
  w.s(32, semicircles(e.omega_rad, 31));
  w.s(24, semicircles(e.omega_dot_rad_s, 43));
  w.s(10, rnd(e.tgd_s / 1e-10));
  w.s(10, rnd(e.tgd2_s / 1e-10));
  w.u(1, static_cast<std::uint64_t>(e.health & 1));
  finish(buf, w, out);
}

void write_galileo(const orbit::Ephemeris& e, std::string& out) {
  Payload buf;
  BitWriter w(buf);
  const time::WeekTime toe = time::gst_from_gps(e.toe);
  const time::WeekTime toc = time::gst_from_gps(e.toc);
  w.u(12, 1046);
  w.u(6, static_cast<std::uint64_t>(e.sat.prn()));
  w.u(12, static_cast<std::uint64_t>(toe.week % time::kGalileoWeekModulus));
  w.u(10, static_cast<std::uint64_t>(e.iode & 0x3FF));
  w.u(8, static_cast<std::uint64_t>(galileo_sisa_index(e.sv_accuracy_m)));
  w.s(14, semicircles(e.idot_rad_s, 43));
  w.u(14, static_cast<std::uint64_t>(rnd(toc.tow_s / 60.0)));
  w.s(6, scaled(e.af2_s_s2, 59));
  w.s(21, scaled(e.af1_s_s, 46));
  w.s(31, scaled(e.af0_s, 34));
  w.s(16, scaled(e.crs_m, 5));
  w.s(16, semicircles(e.delta_n_rad_s, 43));
  w.s(32, semicircles(e.m0_rad, 31));
  w.s(16, scaled(e.cuc_rad, 29));
  w.u(32, static_cast<std::uint64_t>(scaled(e.e, 33)));
  w.s(16, scaled(e.cus_rad, 29));
  w.u(32, static_cast<std::uint64_t>(scaled(e.sqrt_a_sqrtm, 19)));
  w.u(14, static_cast<std::uint64_t>(rnd(toe.tow_s / 60.0)));
  w.s(16, scaled(e.cic_rad, 29));
  w.s(32, semicircles(e.omega0_rad, 31));
  w.s(16, scaled(e.cis_rad, 29));
  w.s(32, semicircles(e.i0_rad, 31));
  w.s(16, scaled(e.crc_m, 5));
  w.s(32, semicircles(e.omega_rad, 31));
  w.s(24, semicircles(e.omega_dot_rad_s, 43));
  // BGD(E1,E5a) then BGD(E1,E5b); tgd_s holds E5b for I/NAV users.
  w.s(10, scaled(e.tgd2_s, 32));
  w.s(10, scaled(e.tgd_s, 32));
  // Health bits as RINEX stores them: E5b HS bits 7-8, DVS bit 6; E1-B HS bits 1-2, DVS bit 0.
  w.u(2, static_cast<std::uint64_t>((e.health >> 7) & 3));
  w.u(1, static_cast<std::uint64_t>((e.health >> 6) & 1));
  w.u(2, static_cast<std::uint64_t>((e.health >> 1) & 3));
  w.u(1, static_cast<std::uint64_t>(e.health & 1));
  finish(buf, w, out);
}

}  // namespace

int ephemeris_message_number(GnssSystem sys) noexcept {
  switch (sys) {
    case GnssSystem::kGps: return 1019;
    case GnssSystem::kGlonass: return 1020;
    case GnssSystem::kBeiDou: return 1042;
    case GnssSystem::kGalileo: return 1046;
    default: return 0;
  }
}

bool append_ephemeris(const orbit::Ephemeris& eph, int leap_s, std::string& out) {
  switch (eph.sat.system) {
    case GnssSystem::kGps: write_gps(eph, out); return true;
    case GnssSystem::kGlonass: write_glonass(eph, leap_s, out); return true;
    case GnssSystem::kBeiDou: write_beidou(eph, out); return true;
    case GnssSystem::kGalileo: write_galileo(eph, out); return true;
    default: return false;
  }
}

int gps_ura_index(double accuracy_m) noexcept {
  static constexpr std::array<double, 15> kUpper{2.4, 3.4, 4.85, 6.85, 9.65, 13.65, 24.0, 48.0,
                                                 96.0, 192.0, 384.0, 768.0, 1536.0, 3072.0, 6144.0};
  for (std::size_t i = 0; i < kUpper.size(); ++i)
    if (accuracy_m <= kUpper[i]) return static_cast<int>(i);
  return 15;
}

int galileo_sisa_index(double accuracy_m) noexcept {
  const double cm = accuracy_m * 100.0;
  if (!(cm >= 0.0)) return 255;
  if (cm < 50.0) return static_cast<int>(std::ceil(cm));
  if (cm < 100.0) return 50 + static_cast<int>(std::ceil((cm - 50.0) / 2.0));
  if (cm < 200.0) return 75 + static_cast<int>(std::ceil((cm - 100.0) / 4.0));
  if (cm <= 600.0) return 100 + static_cast<int>(std::ceil((cm - 200.0) / 16.0));
  return 255;
}

}  // namespace gnssemu::protocol::rtcm

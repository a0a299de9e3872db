// SPDX-License-Identifier: Apache-2.0
#include "core/orbit/ephemeris.hpp"

#include <cmath>

#include "core/common/constants.hpp"

namespace gnssemu::orbit {

SatState sat_state(const Ephemeris& eph, const time::GpsTime& t) noexcept {
  SatState s;
  const double a = eph.sqrt_a_sqrtm * eph.sqrt_a_sqrtm;
  const double n0 = std::sqrt(kMuGps_m3_s2 / (a * a * a));
  const double n = n0 + eph.delta_n_rad_s;
  // Continuous times make the ±302400 s crossover rule unnecessary.
  const double tk = t - eph.toe;
  const double mk = eph.m0_rad + n * tk;

  double ek = mk;
  for (int i = 0; i < 30; ++i) {  // Newton; e < 0.03 converges in a few steps
    const double d = (ek - eph.e * std::sin(ek) - mk) / (1.0 - eph.e * std::cos(ek));
    ek -= d;
    if (std::fabs(d) < 1e-14) break;
  }
  const double sin_e = std::sin(ek), cos_e = std::cos(ek);
  const double one_m_ecos = 1.0 - eph.e * cos_e;
  const double sq1me2 = std::sqrt(1.0 - eph.e * eph.e);
  const double nu = std::atan2(sq1me2 * sin_e, cos_e - eph.e);
  const double phi = nu + eph.omega_rad;
  const double s2 = std::sin(2.0 * phi), c2 = std::cos(2.0 * phi);
  const double du = eph.cus_rad * s2 + eph.cuc_rad * c2;
  const double dr = eph.crs_m * s2 + eph.crc_m * c2;
  const double di = eph.cis_rad * s2 + eph.cic_rad * c2;
  const double u = phi + du;
  const double r = a * one_m_ecos + dr;
  const double inc = eph.i0_rad + eph.idot_rad_s * tk + di;
  const double xp = r * std::cos(u), yp = r * std::sin(u);
  const double omega_k =
      eph.omega0_rad + (eph.omega_dot_rad_s - kOmegaEarth_rad_s) * tk - kOmegaEarth_rad_s * eph.toe.tow_s();
  const double so = std::sin(omega_k), co = std::cos(omega_k);
  const double si = std::sin(inc), ci = std::cos(inc);
  s.pos_m = Ecef(xp * co - yp * ci * so, xp * so + yp * ci * co, yp * si);

  // Velocity: analytic derivative (NGS bc_velo form).
  const double e_dot = n / one_m_ecos;
  const double phi_dot = sq1me2 * e_dot / one_m_ecos;
  const double u_dot = phi_dot * (1.0 + 2.0 * (eph.cus_rad * c2 - eph.cuc_rad * s2));
  const double r_dot = a * eph.e * sin_e * e_dot + 2.0 * phi_dot * (eph.crs_m * c2 - eph.crc_m * s2);
  const double i_dot = eph.idot_rad_s + 2.0 * phi_dot * (eph.cis_rad * c2 - eph.cic_rad * s2);
  const double xp_dot = r_dot * std::cos(u) - yp * u_dot;
  const double yp_dot = r_dot * std::sin(u) + xp * u_dot;
  const double omega_k_dot = eph.omega_dot_rad_s - kOmegaEarth_rad_s;
  const double q = yp_dot * ci - yp * si * i_dot;
  s.vel_m_s = Ecef(-omega_k_dot * s.pos_m.y + xp_dot * co - q * so,
                   omega_k_dot * s.pos_m.x + xp_dot * so + q * co,
                   yp * ci * i_dot + yp_dot * si);

  const double dtc = t - eph.toc;
  s.relativity_s = kRelativityF_s_sqrtm * eph.e * eph.sqrt_a_sqrtm * sin_e;
  const double rel_rate = kRelativityF_s_sqrtm * eph.e * eph.sqrt_a_sqrtm * cos_e * e_dot;
  s.clk_bias_s = eph.af0_s + eph.af1_s_s * dtc + eph.af2_s_s2 * dtc * dtc + s.relativity_s;
  s.clk_drift_s_s = eph.af1_s_s + 2.0 * eph.af2_s_s2 * dtc + rel_rate;
  return s;
}

double sat_clock_at_sv_time(const Ephemeris& eph, const time::GpsTime& t_sv) noexcept {
  double dt = 0.0;
  for (int i = 0; i < 3; ++i) dt = sat_state(eph, t_sv - dt).clk_bias_s;
  return dt;
}

double validity_half_window_s(const Ephemeris& eph) noexcept {
  if (eph.fit_interval_h > 4.0) return eph.fit_interval_h * 1800.0;
  return 7200.0;
}

}  // namespace gnssemu::orbit

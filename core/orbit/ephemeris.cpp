// SPDX-License-Identifier: Apache-2.0
#include "core/orbit/ephemeris.hpp"

#include <cmath>

#include "core/common/constants.hpp"
#include "core/time/beidou_time.hpp"

namespace gnssemu::orbit {

namespace {

// PZ-90.11 (ICD GLONASS Ed. 5.1 §3.1.3; multi-gnss.md §1.1): J2 and the
// equatorial radius of the GLONASS force model. mu and omega_e come from
// the system table. RTKLIB 2.4.3 uses mu = 3.9860044e14, J2 = 1.0826257e-3.
constexpr double kGlonassJ2 = 1.08262575e-3;
constexpr double kGlonassAe_m = 6378136.0;
// BeiDou GEO: the broadcast frame is tilted by -5 degrees about x (BDS-SIS-ICD-B1I 3.0).
constexpr double kSinMinus5 = -0.0871557427476582;
constexpr double kCosMinus5 = 0.9961946980917456;

/// Relativistic clock constant F = -2 sqrt(mu) / c^2 of a system: IS-GPS-200's
/// rounded value for GPS and QZSS, computed from mu for the others.
double relativity_f(GnssSystem sys, double mu) noexcept {
  if (sys == GnssSystem::kGps || sys == GnssSystem::kQzss) return kRelativityF_s_sqrtm;
  return -2.0 * std::sqrt(mu) / (kSpeedOfLight_m_s * kSpeedOfLight_m_s);
}

SatState kepler_state(const Ephemeris& eph, const time::GpsTime& t) noexcept {
  const SystemInfo& info = system_info(eph.sat.system);
  const double mu = info.mu_m3_s2;
  const double omega_e = info.omega_e_rad_s;
  SatState s;
  const double a = eph.sqrt_a_sqrtm * eph.sqrt_a_sqrtm;
  const double n0 = std::sqrt(mu / (a * a * a));
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
  // BeiDou GEO: the node in the inertial-like GK frame, no -omega_e tk term;
  // Earth rotation enters through the final R_z(omega_e tk).
  const bool geo = is_beidou_geo(eph.sat);
  const double omega_k_dot = geo ? eph.omega_dot_rad_s : eph.omega_dot_rad_s - omega_e;
  const double omega_k = eph.omega0_rad + omega_k_dot * tk - omega_e * toe_of_week_s(eph);
  const double so = std::sin(omega_k), co = std::cos(omega_k);
  const double si = std::sin(inc), ci = std::cos(inc);
  Ecef pos(xp * co - yp * ci * so, xp * so + yp * ci * co, yp * si);

  // Velocity: analytic derivative (NGS bc_velo form).
  const double e_dot = n / one_m_ecos;
  const double phi_dot = sq1me2 * e_dot / one_m_ecos;
  const double u_dot = phi_dot * (1.0 + 2.0 * (eph.cus_rad * c2 - eph.cuc_rad * s2));
  const double r_dot = a * eph.e * sin_e * e_dot + 2.0 * phi_dot * (eph.crs_m * c2 - eph.crc_m * s2);
  const double i_dot = eph.idot_rad_s + 2.0 * phi_dot * (eph.cis_rad * c2 - eph.cic_rad * s2);
  const double xp_dot = r_dot * std::cos(u) - yp * u_dot;
  const double yp_dot = r_dot * std::sin(u) + xp * u_dot;
  const double q = yp_dot * ci - yp * si * i_dot;
  Ecef vel(-omega_k_dot * pos.y + xp_dot * co - q * so, omega_k_dot * pos.x + xp_dot * so + q * co,
           yp * ci * i_dot + yp_dot * si);
  if (geo) {
    // r = R_z(omega_e tk) R_x(-5 deg) r_GK (multi-gnss.md §4); dR_z/dt adds omega_e (Y, -X, 0).
    const double f = omega_e * tk;
    const double sf = std::sin(f), cf = std::cos(f);
    auto rotate = [&](const Ecef& g) {
      const double y1 = g.y * kCosMinus5 + g.z * kSinMinus5;
      const double z1 = -g.y * kSinMinus5 + g.z * kCosMinus5;
      return Ecef(g.x * cf + y1 * sf, -g.x * sf + y1 * cf, z1);
    };
    pos = rotate(pos);
    const Ecef v = rotate(vel);
    vel = Ecef(v.x + omega_e * pos.y, v.y - omega_e * pos.x, v.z);
  }
  s.pos_m = pos;
  s.vel_m_s = vel;

  const double f_rel = relativity_f(eph.sat.system, mu);
  const double dtc = t - eph.toc;
  s.relativity_s = f_rel * eph.e * eph.sqrt_a_sqrtm * sin_e;
  const double rel_rate = f_rel * eph.e * eph.sqrt_a_sqrtm * cos_e * e_dot;
  s.clk_bias_s = eph.af0_s + eph.af1_s_s * dtc + eph.af2_s_s2 * dtc * dtc + s.relativity_s;
  s.clk_drift_s_s = eph.af1_s_s + 2.0 * eph.af2_s_s2 * dtc + rel_rate;
  return s;
}

struct GloState {
  double x[6];  // position m, velocity m/s
};

/// ICD GLONASS Ed. 5.1 App. A.3.1.2 in the rotating PZ-90 frame (central
/// term, J2, centrifugal and Coriolis terms; luni-solar acceleration held
/// constant), as multi-gnss.md §3 writes it; mu and omega_e from info (the
/// Keplerian systems' accelerations use their own with the same J2 term).
GloState glonass_derivative(const GloState& s, const Ecef& acc, const SystemInfo& info) noexcept {
  const double mu = info.mu_m3_s2, w = info.omega_e_rad_s;
  const double r2 = s.x[0] * s.x[0] + s.x[1] * s.x[1] + s.x[2] * s.x[2];
  GloState d{};
  if (!(r2 > 0.0)) return d;
  const double r = std::sqrt(r2), r3 = r2 * r;
  const double a = 1.5 * kGlonassJ2 * mu * kGlonassAe_m * kGlonassAe_m / (r3 * r2);
  const double b = 5.0 * s.x[2] * s.x[2] / r2;
  const double c = -mu / r3 - a * (1.0 - b);
  d.x[0] = s.x[3];
  d.x[1] = s.x[4];
  d.x[2] = s.x[5];
  d.x[3] = (c + w * w) * s.x[0] + 2.0 * w * s.x[4] + acc.x;
  d.x[4] = (c + w * w) * s.x[1] - 2.0 * w * s.x[3] + acc.y;
  d.x[5] = (c - 2.0 * a) * s.x[2] + acc.z;
  return d;
}

void rk4_step(GloState& s, const Ecef& acc, double h) noexcept {
  auto add = [](const GloState& a, const GloState& k, double f) {
    GloState o;
    for (int i = 0; i < 6; ++i) o.x[i] = a.x[i] + k.x[i] * f;
    return o;
  };
  const SystemInfo& info = system_info(GnssSystem::kGlonass);
  const GloState k1 = glonass_derivative(s, acc, info);
  const GloState k2 = glonass_derivative(add(s, k1, h / 2.0), acc, info);
  const GloState k3 = glonass_derivative(add(s, k2, h / 2.0), acc, info);
  const GloState k4 = glonass_derivative(add(s, k3, h), acc, info);
  for (int i = 0; i < 6; ++i) s.x[i] += (k1.x[i] + 2.0 * k2.x[i] + 2.0 * k3.x[i] + k4.x[i]) * h / 6.0;
}

/// Clock without relativity: GLONASS -tau_n + gamma_n (t - tb); SBAS
/// aGf0 + aGf1 (t - t0) (multi-gnss.md §2).
void state_vector_clock(const Ephemeris& eph, const time::GpsTime& t, SatState& s) noexcept {
  const double dt = t - eph.toc;
  if (eph.sat.system == GnssSystem::kGlonass) {
    s.clk_bias_s = -eph.tau_n_s + eph.gamma_n * dt;
    s.clk_drift_s_s = eph.gamma_n;
  } else {
    s.clk_bias_s = eph.af0_s + eph.af1_s_s * dt;
    s.clk_drift_s_s = eph.af1_s_s;
  }
}

SatState sbas_state(const Ephemeris& eph, const time::GpsTime& t) noexcept {
  SatState s;
  const double dt = t - eph.toe;
  s.pos_m = Ecef(eph.pos_m + eph.vel_m_s * dt + eph.acc_m_s2 * (0.5 * dt * dt));
  s.vel_m_s = Ecef(eph.vel_m_s + eph.acc_m_s2 * dt);
  state_vector_clock(eph, t, s);
  return s;
}

/// The RK4 integration from tb to t with steps of h; node (if any) holds
/// the state after whole steps: resumed when it lies on the way, and left at
/// the last whole step. The same arithmetic either way: whole steps of
/// exactly h from tb (left - h is exact), then one shortened step.
SatState glonass_integrate(const Ephemeris& eph, const time::GpsTime& t, double h, GlonassNode* node) noexcept {
  SatState out;
  GloState s{{eph.pos_m.x, eph.pos_m.y, eph.pos_m.z, eph.vel_m_s.x, eph.vel_m_s.y, eph.vel_m_s.z}};
  double left = t - eph.toe;
  // A set is used within 30 min of tb, a continued one for days; beyond
  // kGlonassMaxSpan_s the state is held, so no call runs unbounded.
  if (std::isfinite(left)) {
    left = std::fmax(-kGlonassMaxSpan_s, std::fmin(kGlonassMaxSpan_s, left));
    const double sign = left < 0.0 ? -1.0 : 1.0;
    int steps = 0;
    if (node != nullptr && node->eph == &eph && node->toe == eph.toe && node->steps > 0 && node->sign == sign &&
        node->steps * h <= std::fabs(left)) {
      for (int i = 0; i < node->steps; ++i) left -= std::copysign(h, left);
      // Whole steps from tb are taken while |left| >= h: resume only if the
      // node's last one was due for this t as well.
      for (int i = 0; i < 6; ++i) s.x[i] = node->x[i];
      steps = node->steps;
    }
    while (std::fabs(left) >= h) {
      const double step = std::copysign(h, left);
      rk4_step(s, eph.acc_m_s2, step);
      left -= step;
      ++steps;
    }
    if (node != nullptr) {
      node->eph = &eph;
      node->toe = eph.toe;
      node->steps = steps;
      node->sign = sign;
      for (int i = 0; i < 6; ++i) node->x[i] = s.x[i];
    }
    if (std::fabs(left) > 1e-9) rk4_step(s, eph.acc_m_s2, left);
  }
  out.pos_m = Ecef(s.x[0], s.x[1], s.x[2]);
  out.vel_m_s = Ecef(s.x[3], s.x[4], s.x[5]);
  state_vector_clock(eph, t, out);
  return out;
}

double glonass_step_or_default(double step_s) noexcept {
  return std::fabs(step_s) > 0.0 && std::isfinite(step_s) ? std::fabs(step_s) : kGlonassStep_s;
}
}  // namespace

double toe_of_week_s(const Ephemeris& eph) noexcept {
  if (eph.sat.system == GnssSystem::kBeiDou) return (eph.toe - time::kGpsMinusBdt_s).tow_s();
  return eph.toe.tow_s();
}


SatState glonass_state(const Ephemeris& eph, const time::GpsTime& t, double step_s) noexcept {
  return glonass_integrate(eph, t, glonass_step_or_default(step_s), nullptr);
}

SatState sat_state(const Ephemeris& eph, const time::GpsTime& t, GlonassNode& node) noexcept {
  if (system_info(eph.sat.system).orbit == OrbitKind::kStateVector) return glonass_integrate(eph, t, kGlonassStep_s, &node);
  return sat_state(eph, t);
}

Ecef ecef_acceleration_m_s2(const Ephemeris& eph, const Ecef& pos_m, const Ecef& vel_m_s) noexcept {
  const OrbitKind kind = system_info(eph.sat.system).orbit;
  if (kind == OrbitKind::kSbasPoly) return eph.acc_m_s2;
  const GloState st{{pos_m.x, pos_m.y, pos_m.z, vel_m_s.x, vel_m_s.y, vel_m_s.z}};
  const GloState d = kind == OrbitKind::kStateVector ? glonass_derivative(st, eph.acc_m_s2, system_info(GnssSystem::kGlonass))
                                                     : glonass_derivative(st, Ecef(), system_info(eph.sat.system));
  return Ecef(d.x[3], d.x[4], d.x[5]);
}

SatState sat_state(const Ephemeris& eph, const time::GpsTime& t) noexcept {
  switch (system_info(eph.sat.system).orbit) {
    case OrbitKind::kStateVector: return glonass_state(eph, t, kGlonassStep_s);
    case OrbitKind::kSbasPoly: return sbas_state(eph, t);
    case OrbitKind::kKepler: break;
  }
  return kepler_state(eph, t);
}

double sat_clock_at_sv_time(const Ephemeris& eph, const time::GpsTime& t_sv) noexcept {
  double dt = 0.0;
  if (system_info(eph.sat.system).orbit != OrbitKind::kKepler) {
    SatState s;
    for (int i = 0; i < 3; ++i) state_vector_clock(eph, t_sv - dt, s), dt = s.clk_bias_s;
    return dt;
  }
  for (int i = 0; i < 3; ++i) dt = kepler_state(eph, t_sv - dt).clk_bias_s;
  return dt;
}

double validity_half_window_s(const Ephemeris& eph) noexcept {
  if (eph.sat.system != GnssSystem::kGps) return system_info(eph.sat.system).max_ephemeris_age_s;
  if (eph.fit_interval_h > 4.0) return eph.fit_interval_h * 1800.0;
  return 7200.0;
}

}  // namespace gnssemu::orbit

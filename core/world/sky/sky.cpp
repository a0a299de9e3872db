// SPDX-License-Identifier: Apache-2.0
#include "core/world/sky/sky.hpp"

#include <cmath>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"

namespace gnssemu::world {

namespace {

// Horizon pre-test before the light-time iteration, as in SharedSky (light
// time moves a satellite by < 0.01° as seen from the ground).
constexpr double kCullSinEl = -0.02;

/// Light-time iteration with state_at(t) the satellite's state at GPS time t:
/// fills t_tx, pos, vel, clock, range and range rate of out.
template <class StateAt>
void light_time(StateAt&& state_at, const time::GpsTime& t_rx, const Ecef& rx_pos_m, const Ecef& rx_vel_m_s,
                SkySat& s, double tau_guess_s = 0.075) noexcept {
  double tau_s = tau_guess_s;
  orbit::SatState st;
  Ecef pos;
  double range_m = 0.0;
  double tau_eval_s = tau_s;
  for (int pass = 0; pass < 5; ++pass) {
    tau_eval_s = tau_s;
    st = state_at(t_rx - tau_s);
    pos = rotate_earth(st.pos_m, kOmegaEarth_rad_s * tau_s);
    range_m = (pos - rx_pos_m).norm();
    const double tau_new = range_m / kSpeedOfLight_m_s;
    const bool done = std::fabs(tau_new - tau_s) < 1e-9;
    if (done) break;
    tau_s = tau_new;
  }
  // pos/range belong to tau_eval_s; the light-time equation holds to 1e-9 s
  // (< 5 um of satellite motion) after convergence.
  tau_s = tau_eval_s;
  s.t_tx = t_rx - tau_s;
  s.pos_m = pos;
  s.vel_m_s = rotate_earth(st.vel_m_s, kOmegaEarth_rad_s * tau_s);
  s.clk_bias_s = st.clk_bias_s;
  s.clk_drift_s_s = st.clk_drift_s_s;
  s.range_m = range_m;
  const Vec3 los = (pos - rx_pos_m) / (range_m > 0.0 ? range_m : 1.0);
  s.range_rate_m_s = los.dot(s.vel_m_s - rx_vel_m_s);
}

}  // namespace

SkySat sky_sat(const orbit::Ephemeris& eph, const time::GpsTime& t_rx, const Ecef& rx_pos_m,
               const Lla& rx_lla, const Ecef& rx_vel_m_s) noexcept {
  SkySat s;
  light_time([&eph](const time::GpsTime& t) { return orbit::sat_state(eph, t); }, t_rx, rx_pos_m, rx_vel_m_s, s);
  const geo::LookAngles la = geo::look_angles(rx_pos_m, rx_lla, s.pos_m);
  s.az_rad = la.az_rad;
  s.el_rad = la.el_rad;
  return s;
}

RxPlace RxPlace::of(const Ecef& pos_m, const Lla& lla) noexcept {
  RxPlace p;
  p.pos_m = pos_m;
  p.sin_lat = std::sin(lla.lat_rad);
  p.cos_lat = std::cos(lla.lat_rad);
  p.sin_lon = std::sin(lla.lon_rad);
  p.cos_lon = std::cos(lla.lon_rad);
  return p;
}

double light_time_guess(const SkySat& prev, const time::GpsTime& t_rx) noexcept {
  constexpr double kDefault_s = 0.075;
  if (!(prev.range_m > 0.0)) return kDefault_s;
  const double tau_prev_s = prev.range_m / kSpeedOfLight_m_s;
  const double dt_s = t_rx - (prev.t_tx + tau_prev_s);
  if (!(dt_s > 0.0 && dt_s <= 2.0)) return kDefault_s;
  const double tau_s = tau_prev_s + prev.range_rate_m_s * dt_s / kSpeedOfLight_m_s;
  return tau_s > 0.0 && tau_s < 0.2 ? tau_s : kDefault_s;
}

bool sky_sat(const SharedSky& sky, const orbit::Ephemeris& eph, const time::GpsTime& t_rx, const RxPlace& rx,
             const Ecef& rx_vel_m_s, SkySat& s, double tau_guess_s) noexcept {
  const SkyState& ss = sky.state(eph.sat);
  if (ss.eph == &eph) {
    // A satellite the sky culled has an older evaluation of this set (from
    // the last couple of minutes): good enough to stay culled here.
    const Vec3 d = (ss.current ? ss.pos_m : taylor_state(ss, t_rx - ss.t).pos_m) - rx.pos_m;
    const double up = rx.up(d);
    if (up < 0.0 && up * up > kCullSinEl * kCullSinEl * d.dot(d)) return false;
  }
  light_time([&sky, &eph](const time::GpsTime& t) { return sky.state_at(eph, t); }, t_rx, rx.pos_m, rx_vel_m_s, s,
             tau_guess_s);
  // geo::look_angles with the axes computed once (the same arithmetic).
  const Vec3 d = s.pos_m - rx.pos_m;
  const double e = -rx.sin_lon * d.x + rx.cos_lon * d.y;
  const double n = -rx.sin_lat * rx.cos_lon * d.x - rx.sin_lat * rx.sin_lon * d.y + rx.cos_lat * d.z;
  const double u = rx.up(d);
  if (!(u > 0.0) || !(d.norm() > 0.0)) return false;
  s.el_rad = std::atan2(u, std::hypot(e, n));
  double az = std::atan2(e, n);
  if (az < 0.0) az += 2.0 * kPi;
  if (az >= 2.0 * kPi) az -= 2.0 * kPi;
  s.az_rad = az;
  return true;
}

}  // namespace gnssemu::world

// SPDX-License-Identifier: Apache-2.0
#include "core/world/sky.hpp"

#include <cmath>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"

namespace gnssemu::world {

SkySat sky_sat(const orbit::Ephemeris& eph, const time::GpsTime& t_rx, const Ecef& rx_pos_m,
               const Lla& rx_lla, const Ecef& rx_vel_m_s) noexcept {
  SkySat s;
  double tau_s = 0.075;
  orbit::SatState st;
  Ecef pos;
  double range_m = 0.0;
  double tau_eval_s = tau_s;
  for (int pass = 0; pass < 5; ++pass) {
    tau_eval_s = tau_s;
    st = orbit::sat_state(eph, t_rx - tau_s);
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
  const geo::LookAngles la = geo::look_angles(rx_pos_m, rx_lla, pos);
  s.az_rad = la.az_rad;
  s.el_rad = la.el_rad;
  return s;
}

}  // namespace gnssemu::world

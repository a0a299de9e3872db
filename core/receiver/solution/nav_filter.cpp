// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/solution/nav_filter.hpp"

#include <cmath>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"

namespace gnssemu::receiver {

void validate(const NavFilterConfig& c) {
  using R = NavFilterRanges;
  check_ranges("navigation filter config",
               {{c.smoothing_window_s, R::smoothing_window_s, "smoothing_window_s"},
                {c.static_hold_speed_m_s, R::static_hold_speed_m_s, "static_hold_speed_m_s"},
                {c.static_hold_max_dist_m, R::static_hold_max_dist_m, "static_hold_max_dist_m"},
                {c.position_noise_m2_s, R::position_noise_m2_s, "position_noise_m2_s"},
                {c.coast_limit_s, R::coast_limit_s, "coast_limit_s"},
                {c.clock_h0_s, R::clock_h0_s, "clock_h0_s"},
                {c.clock_h_minus2_per_s, R::clock_h_minus2_per_s, "clock_h_minus2_per_s"},
                {c.innovation_gate_sigma, R::innovation_gate_sigma, "innovation_gate_sigma"},
                {c.reinit_margin_m, R::reinit_margin_m, "reinit_margin_m"}});
}

double clock_phase_psd_m2_s(double h0_s) noexcept { return kSpeedOfLight_m_s * kSpeedOfLight_m_s * h0_s / 2.0; }

double clock_freq_psd_m2_s3(double h_minus2_per_s) noexcept {
  return kSpeedOfLight_m_s * kSpeedOfLight_m_s * 2.0 * kPi * kPi * h_minus2_per_s;
}

void NavFilter::init(const Ecef& pos_m, const Ecef& vel_m_s, double clock_m, double drift_m_s, double pos_var_m2,
                     double vel_var_m2_s2, double clock_var_m2, double drift_var_m2_s2) noexcept {
  x_ = {pos_m.x, pos_m.y, pos_m.z, vel_m_s.x, vel_m_s.y, vel_m_s.z, clock_m, drift_m_s};
  p_ = {};
  for (int i = 0; i < 3; ++i) {
    p_[i][i] = pos_var_m2;
    p_[i + 3][i + 3] = vel_var_m2_s2;
  }
  p_[6][6] = clock_var_m2;
  p_[7][7] = drift_var_m2_s2;
  initialised_ = true;
}

void NavFilter::predict(double dt_s, double q_h, double q_v, double q_pos, double sf, double sg,
                        bool zero_velocity) noexcept {
  if (!(dt_s > 0.0)) return;
  const double dt = dt_s;
  // x <- F x with F = [I dt I; 0 I] for position/velocity and [1 dt; 0 1] for the clock.
  for (int i = 0; i < 3; ++i) x_[i] += dt * x_[i + 3];
  x_[6] += dt * x_[7];
  // P <- F P F': rows then columns (pairs (i, i+3) and (6, 7)).
  const auto couple = [&](int a, int b) {
    for (int k = 0; k < kNavStates; ++k) p_[a][k] += dt * p_[b][k];
    for (int k = 0; k < kNavStates; ++k) p_[k][a] += dt * p_[k][b];
  };
  for (int i = 0; i < 3; ++i) couple(i, i + 3);
  couple(6, 7);
  // Motion noise: q along local east, north (q_h) and up (q_v), in ECEF.
  const Lla lla = geo::lla_from_ecef(pos_m());
  const geo::EnuAxes ax = geo::enu_axes(lla.lat_rad, lla.lon_rad);
  const double a[3][3] = {{ax.e.x, ax.e.y, ax.e.z}, {ax.n.x, ax.n.y, ax.n.z}, {ax.u.x, ax.u.y, ax.u.z}};
  const double q[3] = {q_h, q_h, q_v};
  const double t3 = dt * dt * dt / 3.0, t2 = dt * dt / 2.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double qa = 0.0;  // (A' diag(q) A)_ij
      for (int k = 0; k < 3; ++k) qa += a[k][i] * q[k] * a[k][j];
      p_[i][j] += qa * t3;
      p_[i][j + 3] += qa * t2;
      p_[i + 3][j] += qa * t2;
      p_[i + 3][j + 3] += qa * dt;
    }
  }
  for (int i = 0; i < 3; ++i) p_[i][i] += q_pos * dt;
  p_[6][6] += sf * dt + sg * t3;
  p_[6][7] += sg * t2;
  p_[7][6] += sg * t2;
  p_[7][7] += sg * dt;
  if (zero_velocity) hold_velocity(1e-6);
}

void NavFilter::hold_velocity(double var_m2_s2) noexcept {
  for (int i = 3; i < 6; ++i) {
    x_[i] = 0.0;
    for (int k = 0; k < kNavStates; ++k) p_[i][k] = p_[k][i] = 0.0;
    p_[i][i] = var_m2_s2;
  }
}

bool NavFilter::update(const NavVector& h, double innovation, double r, double gate_sigma) noexcept {
  NavVector ph{};  // P h'
  for (int i = 0; i < kNavStates; ++i)
    for (int k = 0; k < kNavStates; ++k) ph[i] += p_[i][k] * h[k];
  double s = r;
  for (int i = 0; i < kNavStates; ++i) s += h[i] * ph[i];
  if (!(s > 0.0) || !std::isfinite(innovation) || !(std::fabs(innovation) <= gate_sigma * std::sqrt(s))) return false;
  // K = P h' / s; P -= K (P h')' on the upper triangle, mirrored: P stays
  // exactly symmetric, with one division instead of one per element.
  const double inv_s = 1.0 / s;
  for (int i = 0; i < kNavStates; ++i) {
    const double k_i = ph[i] * inv_s;
    x_[i] += k_i * innovation;
    for (int k = i; k < kNavStates; ++k) p_[i][k] -= k_i * ph[k];
    for (int k = i + 1; k < kNavStates; ++k) p_[k][i] = p_[i][k];
  }
  return true;
}

double NavFilter::variance_of(const NavVector& h) const noexcept {
  double s = 0.0;
  for (int i = 0; i < kNavStates; ++i)
    for (int k = 0; k < kNavStates; ++k) s += h[i] * p_[i][k] * h[k];
  return s;
}

void NavFilter::widen_position(double var_m2) noexcept {
  for (int i = 0; i < 3; ++i) p_[i][i] += var_m2;
  p_[6][6] += var_m2;
}

void NavFilter::shift_clock(double offset_m, double var_m2) noexcept {
  x_[6] += offset_m;
  p_[6][6] += var_m2;
}

}  // namespace gnssemu::receiver

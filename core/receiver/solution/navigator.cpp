// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/solution/navigator.hpp"

#include <algorithm>
#include <cmath>

#include "core/geo/geodesy.hpp"
#include "core/receiver/solution/enu_rotation.hpp"
#include "core/receiver/solution/small_matrix.hpp"

namespace gnssemu::receiver {

namespace {

// A common pseudorange innovation beyond this is a receiver clock step
// (whole milliseconds, 300 km each), not a position error, m.
constexpr double kClockStepGate_m = 1000.0;
// Static hold ends above this multiple of its threshold (hysteresis against
// a speed estimate hovering at the threshold).
constexpr double kStaticHoldExit = 1.5;
constexpr double kPivotTol = 1e-10;

using Mat3 = std::array<std::array<double, 3>, 3>;

/// Covariance of the three ECEF states from index k of p, in local ENU: R P R'.
Mat3 enu_block(const NavMatrix& p, int k, const Lla& lla) noexcept {
  const geo::EnuAxes a = geo::enu_axes(lla.lat_rad, lla.lon_rad);
  const Mat3 r{{{a.e.x, a.e.y, a.e.z}, {a.n.x, a.n.y, a.n.z}, {a.u.x, a.u.y, a.u.z}}};
  Mat3 rp{}, out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int m = 0; m < 3; ++m) rp[i][j] += r[i][m] * p[k + m][k + j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int m = 0; m < 3; ++m) out[i][j] += rp[i][m] * r[j][m];
  return out;
}

}  // namespace

Navigator::Navigator(const NavFilterConfig& cfg, const SolverConfig& solver) noexcept
    : cfg_(cfg), rate_sigma_m_s_(solver.sigma_range_rate_m_s), height_sigma_m_(solver.height_hold_sigma_m) {}

void Navigator::set_static_hold(double speed_m_s, double max_dist_m) noexcept {
  cfg_.static_hold_speed_m_s = speed_m_s;
  cfg_.static_hold_max_dist_m = max_dist_m;
  if (!(speed_m_s > 0.0)) holding_ = false;
}

void Navigator::reset() noexcept {
  kf_.reset();
  last_type_ = FixType::kNone;
  coast_s_ = 0.0;
  coasting_ = false;
  have_height_ = false;
  holding_ = false;
}

void Navigator::fill_state(FixType type, SolverOutput& out) noexcept {
  out.type = type;
  out.pos_m = kf_.pos_m();
  out.lla = geo::lla_from_ecef(out.pos_m);
  out.clock_m = kf_.clock_m();
  out.drift_m_s = kf_.drift_m_s();
  out.vel_m_s = kf_.vel_m_s();
  out.vel_enu_m_s = geo::ecef_to_enu_vector(out.vel_m_s, out.lla.lat_rad, out.lla.lon_rad);
  const NavMatrix& p = kf_.covariance();
  const auto pp = enu_block(p, 0, out.lla);
  const auto pv = enu_block(p, 3, out.lla);
  out.cov_pos = {};
  out.cov_vel = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      out.cov_pos[i][j] = pp[i][j];
      out.cov_vel[i][j] = pv[i][j];
    }
  out.cov_pos[3][3] = p[6][6];
  out.cov_vel[3][3] = p[7][7];
}

void Navigator::start_from(const SolverOutput& snapshot, SolverOutput& out) noexcept {
  const auto& q = snapshot.cov_pos;
  const auto& qv = snapshot.cov_vel;
  const DynamicModelParams& dm = dynamic_model_params(cfg_.dynamic_model);
  kf_.init(snapshot.pos_m, dm.zero_velocity ? Ecef{} : snapshot.vel_m_s, snapshot.clock_m, snapshot.drift_m_s,
           std::max((q[0][0] + q[1][1] + q[2][2]) / 3.0, 1e-4), std::max((qv[0][0] + qv[1][1] + qv[2][2]) / 3.0, 1e-6),
           std::max(q[3][3], 1e-4), std::max(qv[3][3], 1e-6));
  if (dm.zero_velocity) kf_.hold_velocity(1e-6);
  ++restarts_;
  updates_ = 0;
  out = snapshot;
  last_type_ = snapshot.type;
  last_dop_ = snapshot.dop;
  coast_s_ = 0.0;
  coasting_ = false;
  have_height_ = snapshot.type == FixType::k3D;
  held_height_m_ = snapshot.lla.height_m;
  for (int i = 0; i < 3; ++i) floor_var_[i] = kf_var_at_update_[i] = q[i][i];
  floor_var_[3] = kf_var_at_update_[3] = q[3][3];
  holding_ = false;
  apply_static_hold(out);
}

void Navigator::apply_static_hold(SolverOutput& out) noexcept {
  const DynamicModelParams& dm = dynamic_model_params(cfg_.dynamic_model);
  if (dm.zero_velocity) {
    out.vel_m_s = Ecef{};
    out.vel_enu_m_s = Enu{};
  }
  const double thr = cfg_.static_hold_speed_m_s;
  if (!(thr > 0.0) || out.type == FixType::kNone) {
    holding_ = false;
    return;
  }
  const double speed = out.vel_m_s.norm();
  if (holding_) {
    const bool moved = cfg_.static_hold_max_dist_m > 0.0 && (out.pos_m - hold_pos_m_).norm() > cfg_.static_hold_max_dist_m;
    if (speed > kStaticHoldExit * thr || moved) holding_ = false;
  } else if (speed < thr) {
    holding_ = true;
    hold_pos_m_ = out.pos_m;
    hold_lla_ = out.lla;
  }
  if (!holding_) return;
  out.pos_m = hold_pos_m_;
  out.lla = hold_lla_;
  out.vel_m_s = Ecef{};
  out.vel_enu_m_s = Enu{};
}

void Navigator::step(double dt_s, const SolverInput& in, const SolverOutput& snapshot, Solver& solver,
                     SolverOutput& out) noexcept {
  out = SolverOutput{};
  coasting_ = false;
  const bool snap_ok = snapshot.type != FixType::kNone;
  if (!kf_.initialised()) {
    if (snapshot.type == FixType::k3D) start_from(snapshot, out);
    return;
  }
  const DynamicModelParams& dm = dynamic_model_params(cfg_.dynamic_model);
  kf_.predict(dt_s, dm.accel_psd_h_m2_s3, dm.accel_psd_v_m2_s3, dm.zero_velocity ? 0.0 : cfg_.position_noise_m2_s,
              clock_phase_psd_m2_s(cfg_.clock_h0_s),
              clock_freq_psd_m2_s3(cfg_.clock_h_minus2_per_s), dm.zero_velocity);
  coast_s_ += std::max(dt_s, 0.0);

  // The snapshot far outside the prediction: the filter no longer describes
  // the antenna (moved, or it went wrong); start again from the snapshot.
  const NavMatrix& p = kf_.covariance();
  if (snapshot.type == FixType::k3D) {
    const double var = p[0][0] + p[1][1] + p[2][2] + snapshot.cov_pos[0][0] + snapshot.cov_pos[1][1] + snapshot.cov_pos[2][2];
    if ((snapshot.pos_m - kf_.pos_m()).norm() > 5.0 * std::sqrt(var) + cfg_.reinit_margin_m) {
      start_from(snapshot, out);
      return;
    }
  }

  const int n = solver.measurement_model(in, kf_.pos_m(), kf_.clock_m(), rows_);
  // A millisecond step of the receiver clock moves every pseudorange alike.
  if (n > 0) {
    std::array<double, kMaxSatsInView> r{};
    for (int i = 0; i < n; ++i) r[i] = rows_[i].range_resid_m;
    std::nth_element(r.begin(), r.begin() + n / 2, r.begin() + n);
    const double median = r[n / 2];
    if (std::fabs(median) > kClockStepGate_m) {
      kf_.shift_clock(median, 100.0);
      for (int i = 0; i < n; ++i) rows_[i].range_resid_m -= median;
    }
  }

  // Most pseudoranges far outside the prediction: the prediction is what is
  // wrong (the antenna moved unlike the model), not the satellites. Start
  // over from the snapshot when there is one; else widen the prediction.
  if (n > 0) {
    int outside = 0, considered = 0;
    double worst2 = 0.0;
    const double g2 = cfg_.innovation_gate_sigma * cfg_.innovation_gate_sigma;
    for (int i = 0; i < n; ++i) {
      if (snap_ok && snapshot.excluded[i]) continue;
      const MeasurementRow& m = rows_[i];
      const double s = m.sigma2_m2 + kf_.variance_of({-m.los.x, -m.los.y, -m.los.z, 0.0, 0.0, 0.0, 1.0, 0.0});
      const double v2 = m.range_resid_m * m.range_resid_m;
      ++considered;
      if (v2 > g2 * s) {
        ++outside;
        worst2 = std::max(worst2, v2);
      }
    }
    if (outside >= 2 && 2 * outside >= considered) {
      if (snapshot.type == FixType::k3D) {
        start_from(snapshot, out);
        return;
      }
      kf_.widen_position(worst2);
    }
  }

  // Sequential updates; innovations at the prediction minus what the earlier
  // updates of this epoch already moved.
  const NavVector x0{kf_.pos_m().x, kf_.pos_m().y, kf_.pos_m().z, 0.0, 0.0, 0.0, kf_.clock_m(), 0.0};
  const auto moved = [&](const NavVector& h) {
    const Ecef pos = kf_.pos_m();
    return h[0] * (pos.x - x0[0]) + h[1] * (pos.y - x0[1]) + h[2] * (pos.z - x0[2]) + h[6] * (kf_.clock_m() - x0[6]);
  };
  const double gate = cfg_.innovation_gate_sigma;
  int used = 0;
  double sum_s2 = 0.0;
  for (int i = 0; i < n; ++i) {
    out.excluded[i] = snap_ok && snapshot.excluded[i];
    if (out.excluded[i]) continue;
    const MeasurementRow& m = rows_[i];
    const NavVector h{-m.los.x, -m.los.y, -m.los.z, 0.0, 0.0, 0.0, 1.0, 0.0};
    if (kf_.update(h, m.range_resid_m - moved(h), m.sigma2_m2, gate)) {
      ++used;
      sum_s2 += m.sigma2_m2;
    } else {
      out.excluded[i] = true;
    }
  }
  const double r_rate = rate_sigma_m_s_ * rate_sigma_m_s_;
  for (int i = 0; i < n; ++i) {
    if (out.excluded[i]) continue;
    const MeasurementRow& m = rows_[i];
    const NavVector h{0.0, 0.0, 0.0, -m.los.x, -m.los.y, -m.los.z, 0.0, 1.0};
    const Ecef v = kf_.vel_m_s();
    kf_.update(h, m.rate_obs_m_s - (-m.los.dot(v) + kf_.drift_m_s()), r_rate, gate);
  }
  FixType type = FixType::kNone;
  if (used >= 4) {
    type = FixType::k3D;
  } else if (used == 3 && dm.allows_2d && have_height_) {
    const Lla lla = geo::lla_from_ecef(kf_.pos_m());
    const Vec3 up = geo::up_unit_ecef(lla);
    kf_.update({up.x, up.y, up.z, 0.0, 0.0, 0.0, 0.0, 0.0}, held_height_m_ - lla.height_m,
               height_sigma_m_ * height_sigma_m_, 1e9);
    type = FixType::k2D;
  }

  if (type == FixType::kNone) {
    // Coasting on the prediction, then no fix.
    if (coast_s_ > cfg_.coast_limit_s || last_type_ == FixType::kNone) {
      reset();
      return;
    }
    coasting_ = true;
    fill_state(FixType::kDeadReckoning, out);
    for (int i = 0; i < 4; ++i) {
      const double grown = std::max(out.cov_pos[i][i] - kf_var_at_update_[i], 0.0);
      out.cov_pos[i][i] = std::max(floor_var_[i], kf_var_at_update_[i]) + grown;
    }
    out.dop = last_dop_;
    out.num_used = 0;
    apply_static_hold(out);
    return;
  }

  ++updates_;
  coast_s_ = 0.0;
  last_type_ = type;
  fill_state(type, out);
  // Post-fit residuals; the used geometry for DOP and the reported accuracy.
  Mat4 nu{}, nw{};
  double sum_post2 = 0.0;
  const EnuRotation to_enu(out.lla.lat_rad, out.lla.lon_rad);
  for (int i = 0; i < n; ++i) {
    if (out.excluded[i]) continue;
    const MeasurementRow& m = rows_[i];
    const NavVector h{-m.los.x, -m.los.y, -m.los.z, 0.0, 0.0, 0.0, 1.0, 0.0};
    out.residual_m[i] = m.range_resid_m - moved(h);
    sum_post2 += out.residual_m[i] * out.residual_m[i];
    const Enu e = to_enu(m.los);
    const Vec4 g{-e.x, -e.y, -e.z, 1.0};
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        nu[a][b] += g[a] * g[b];
        nw[a][b] += g[a] * g[b] / m.sigma2_m2;
      }
  }
  if (type == FixType::k2D) {
    for (int k = 0; k < 4; ++k) nu[2][k] = nu[k][2] = nw[2][k] = nw[k][2] = 0.0;
    nu[2][2] = 1.0;
    nw[2][2] = 1.0 / (height_sigma_m_ * height_sigma_m_);
  }
  Mat4 qu, qw;
  if (spd_inverse4(nu, qu, kPivotTol) && spd_inverse4(nw, qw, kPivotTol)) {
    const double hdop = std::sqrt(qu[0][0] + qu[1][1]);
    out.dop.hdop = hdop;
    out.dop.tdop = std::sqrt(qu[3][3]);
    if (type == FixType::k3D) {
      out.dop.vdop = std::sqrt(qu[2][2]);
      out.dop.pdop = std::sqrt(qu[0][0] + qu[1][1] + qu[2][2]);
      out.dop.gdop = std::sqrt(qu[0][0] + qu[1][1] + qu[2][2] + qu[3][3]);
    }
    for (int i = 0; i < 4; ++i) floor_var_[i] = qw[i][i];
  }
  for (int i = 0; i < 4; ++i) {
    kf_var_at_update_[i] = out.cov_pos[i][i];
    out.cov_pos[i][i] = std::max(out.cov_pos[i][i], floor_var_[i]);
  }
  last_dop_ = out.dop;
  out.num_used = used;
  out.num_excluded = 0;
  for (int i = 0; i < n; ++i) out.num_excluded += out.excluded[i] ? 1 : 0;
  out.range_rms_m = std::sqrt(sum_post2 / used);
  out.sigma_uere_m = std::sqrt(sum_s2 / used);
  out.dof = used - 4;
  if (type == FixType::k3D) {
    have_height_ = true;
    held_height_m_ = out.lla.height_m;
  }
  apply_static_hold(out);
}

}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/solution/solver.hpp"

#include <algorithm>
#include <cmath>

#include "core/atmosphere/receiver_corrections.hpp"
#include "core/geo/geodesy.hpp"
#include "core/world/sky/sky.hpp"
#include "core/receiver/solution/enu_rotation.hpp"
#include "core/receiver/solution/small_matrix.hpp"
#include "core/receiver/solution/transmit_state.hpp"
#include "core/receiver/solution/weight_model.hpp"

namespace gnssemu::receiver {

namespace {

constexpr double kConvergence_m = 1e-4;     // Gauss–Newton step norm (pos + clock), m
// Plausible receiver heights; a converged solution outside is a false root.
constexpr double kMinHeight_m = -2000.0;
constexpr double kMaxHeight_m = 1.0e5;
// Below this radius (m) elevations are meaningless (cold start from the
// Earth's centre): unit elevation factor is used for the weights.
constexpr double kSurfaceRadius_m = 6.0e6;
constexpr double kMaxLightTime_s = 0.2;
constexpr double kPivotTol = 1e-10;         // relative Cholesky pivot tolerance
// Corrections are recomputed only once the estimate has moved this far (m),
// as receivers evaluate them at the prior position: a 5 m height change
// alters the 5-degree tropo correction by < 1.5 cm, and holding them keeps
// Gauss–Newton convergent where the Klobuchar pierce point is discontinuous
// in longitude (the poles).
constexpr double kCorrectionRefresh_m = 5.0;

double upper_normal_quantile(double p) noexcept {
  // Solve 0.5 erfc(z / sqrt 2) = p by bisection; p in (0, 0.5).
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (0.5 * std::erfc(mid / std::sqrt(2.0)) > p) lo = mid; else hi = mid;
  }
  return 0.5 * (lo + hi);
}

void accumulate(Mat4& n, Vec4& g, const Vec4& h, double w, double y) noexcept {
  for (int i = 0; i < 4; ++i) {
    g[i] += w * h[i] * y;
    for (int k = 0; k < 4; ++k) n[i][k] += w * h[i] * h[k];
  }
}

// The same over the leading ns states.
void accumulate(MatN& n, VecN& g, const VecN& h, double w, double y, int ns) noexcept {
  for (int i = 0; i < ns; ++i) {
    g[i] += w * h[i] * y;
    for (int k = 0; k < ns; ++k) n[i][k] += w * h[i] * h[k];
  }
}

// A pseudorange's design row (design_row(hx, hy, hz, col)) into the normal
// matrix (and g += w h y with g non-null): only its non-zero entries, each
// product formed as the dense loop forms it, so the sums are the same bits.
void accumulate_range(MatN& n, VecN* g, double hx, double hy, double hz, int col, double w, double y) noexcept {
  const double h[3] = {hx, hy, hz};
  const auto c = static_cast<std::size_t>(col);
  for (std::size_t i = 0; i < 3; ++i) {
    const double wh = w * h[i];
    if (g) (*g)[i] += wh * y;
    for (std::size_t k = 0; k < 3; ++k) n[i][k] += wh * h[k];
    n[i][3] += wh;
    if (col > 3) n[i][c] += wh;
  }
  for (std::size_t r = 3;; r = c) {
    if (g) (*g)[r] += w * y;
    for (std::size_t k = 0; k < 3; ++k) n[r][k] += w * h[k];
    n[r][3] += w;
    if (col > 3) n[r][c] += w;
    if (r == c || col <= 3) break;
  }
}

bool finite4(const Mat4& m) noexcept {
  for (const auto& r : m)
    for (double v : r)
      if (!std::isfinite(v)) return false;
  return true;
}

bool finite(const MatN& m, int ns) noexcept {
  for (int i = 0; i < ns; ++i)
    for (int k = 0; k < ns; ++k)
      if (!std::isfinite(m[i][k])) return false;
  return true;
}

// Design row of a pseudorange: -line of sight, 1 for the first system's
// clock, 1 for the satellite's inter-system bias (col > 3).
VecN design_row(double x, double y, double z, int col) noexcept {
  VecN h{};
  h[0] = x;
  h[1] = y;
  h[2] = z;
  h[3] = 1.0;
  if (col > 3) h[static_cast<std::size_t>(col)] = 1.0;
  return h;
}

}  // namespace

Solver::Solver(const SolverConfig& cfg, double max_pdop) noexcept
    : cfg_(cfg),
      max_pdop_(max_pdop),
      z_pfa_(cfg.residual_test_pfa > 0.0 && cfg.residual_test_pfa < 0.5
                 ? upper_normal_quantile(cfg.residual_test_pfa)
                 : 0.0) {
  for (int i = 0; i < kMaxSatsInView; ++i) orig_[static_cast<std::size_t>(i)] = i;
}

double Solver::chi2_threshold(int dof) const noexcept {
  // Wilson & Hilferty (1931) cube-root normal approximation of the quantile.
  const double k = static_cast<double>(std::max(dof, 1));
  const double h = 2.0 / (9.0 * k);
  const double c = 1.0 - h + z_pfa_ * std::sqrt(h);
  return k * c * c * c;
}

void Solver::update_corrections(const SolverInput& in, const Ecef& pos, const Lla& lla) noexcept {
  const bool iono = cfg_.iono != atmosphere::IonoCorrection::kNone;
  const bool tropo = cfg_.tropo != atmosphere::TropoCorrection::kNone;
  if (!iono && !tropo) return;
  if (corr_valid_ && (pos - corr_pos_).norm() < kCorrectionRefresh_m) return;
  corr_valid_ = true;
  corr_pos_ = pos;
  // Within solve() the corrections at its first position are kept per
  // measurement: the exclusion re-solves start from the same prior.
  const bool same_pos = corr_cache_valid_ && pos.x == corr_cache_pos_.x && pos.y == corr_cache_pos_.y &&
                        pos.z == corr_cache_pos_.z;
  const bool cache = in_solve_ && (same_pos || !corr_cache_valid_);
  if (cache && !corr_cache_valid_) {
    corr_cache_valid_ = true;
    corr_cache_pos_ = pos;
    corr_cached_.fill(false);
  }
  const double tow_s = in.t_rx_local.tow_s();
  const Vec3 up = geo::up_unit_ecef(lla);
  const Vec3 east{-std::sin(lla.lon_rad), std::cos(lla.lon_rad), 0.0};
  const Vec3 north = up.cross(east);
  const atmosphere::ReceiverTropo tropo_at(lla.lat_rad, lla.height_m, in.doy, cfg_.tropo);
  for (int i = 0; i < n_; ++i) {
    Sat& s = sats_[i];
    const std::size_t o = static_cast<std::size_t>(orig_[static_cast<std::size_t>(i)]);
    if (cache && corr_cached_[o]) {
      s.corr_m = corr_cache_m_[o];
      s.model_var_m2 = corr_cache_var_m2_[o];
      continue;
    }
    const Vec3 d = world::rotate_earth(s.pos_m, kOmegaEarth_rad_s * s.since_tx_s) - pos;
    const double e = d.dot(east), n = d.dot(north), u = d.dot(up);
    const double el = std::atan2(u, std::hypot(e, n));
    double az = std::atan2(e, n);
    if (az < 0.0) az += 2.0 * kPi;
    const Measurement& m = in.meas[i];
    const double i_m =
        m.iono_given ? m.iono_m
        : iono       ? atmosphere::receiver_iono_delay_m(klobuchar_, lla.lat_rad, lla.lon_rad, az, el, tow_s, m.wavelength_m)
                     : 0.0;
    s.corr_m = i_m;
    if (tropo) s.corr_m += tropo_at.delay_m(el);
    s.model_var_m2 = correction_variance_m2(cfg_, m.iono_given ? 0.0 : i_m, std::sin(el));
    if (cache) {
      corr_cached_[o] = true;
      corr_cache_m_[o] = s.corr_m;
      corr_cache_var_m2_[o] = s.model_var_m2;
    }
  }
}

void Solver::linearise(const SolverInput& in, const Ecef& pos, double clock_m, const Lla* lla) noexcept {
  const Vec3 up = lla ? geo::up_unit_ecef(*lla) : Vec3{};
  if (lla) {
    update_corrections(in, pos, *lla);
  } else if (corr_valid_) {
    corr_valid_ = false;
    for (int i = 0; i < n_; ++i) sats_[i].corr_m = sats_[i].model_var_m2 = 0.0;
  }
  for (int i = 0; i < n_; ++i) {
    Sat& s = sats_[i];
    // Flight time from the receiver's clock estimate; exact at convergence.
    const double rx_clock = rx_clock_m(s, clock_m);
    const double tau_s = std::clamp(s.since_tx_s - rx_clock / kSpeedOfLight_m_s, 0.0, kMaxLightTime_s);
    const double angle = kOmegaEarth_rad_s * tau_s;
    const Ecef p = world::rotate_earth(s.pos_m, angle);
    s.vel_rx_frame_m_s = world::rotate_earth(s.vel_m_s, angle);
    const Vec3 d = p - pos;
    const double rho = d.norm();
    s.los = rho > 0.0 ? d / rho : Vec3{0.0, 0.0, 1.0};
    s.resid_m = in.meas[i].pseudorange_m - (rho + rx_clock - s.clk_m + s.corr_m);
    const double sin_el = lla ? s.los.dot(up) : 1.0;
    s.sigma2 = elevation_variance_m2(cfg_, sin_el) * s.efact2 + s.sat_var_m2 + s.model_var_m2;
    s.weight = 1.0 / s.sigma2;
  }
}

bool Solver::iterate(const SolverInput& in, Ecef& pos, double& clock_m, bool two_d) noexcept {
  const double wh = 1.0 / (cfg_.height_hold_sigma_m * cfg_.height_hold_sigma_m);
  for (int it = 0; it < cfg_.max_iterations; ++it) {
    Lla lla;
    const bool near_surface = pos.norm() > kSurfaceRadius_m;
    if (near_surface) lla = geo::lla_from_ecef(pos);
    linearise(in, pos, clock_m, near_surface ? &lla : nullptr);
    const int ns = num_states_;
    MatN n{};
    VecN g{};
    for (int i = 0; i < n_; ++i) {
      const Sat& s = sats_[i];
      accumulate_range(n, &g, -s.los.x, -s.los.y, -s.los.z, s.col, s.weight, s.resid_m);
    }
    if (two_d) {
      if (!near_surface) return false;
      const Vec3 up = geo::up_unit_ecef(lla);
      accumulate(n, g, VecN{up.x, up.y, up.z}, wh, in.held_height_m - lla.height_m, ns);
    }
    MatN inv;
    if (!spd_inverse(n, inv, ns, kPivotTol)) return false;
    const VecN dx = mul(inv, g, ns);
    pos += Vec3{dx[0], dx[1], dx[2]};
    clock_m += dx[3];
    double step2 = 0.0;
    for (int k = 0; k < ns; ++k) step2 += dx[k] * dx[k];
    for (int k = 4; k < ns; ++k) bias_m_[static_cast<std::size_t>(k - 4)] += dx[k];
    if (!pos.finite() || !std::isfinite(clock_m) || !std::isfinite(step2)) return false;
    const double step = std::sqrt(step2);
    if (step < kConvergence_m) return true;
  }
  return false;
}

bool Solver::finish(const SolverInput& in, const Ecef& pos, double clock_m, bool two_d,
                    SolverOutput& out) noexcept {
  const Lla lla = geo::lla_from_ecef(pos);
  if (!(lla.height_m > kMinHeight_m && lla.height_m < kMaxHeight_m)) return false;
  linearise(in, pos, clock_m, &lla);

  const double wh = 1.0 / (cfg_.height_hold_sigma_m * cfg_.height_hold_sigma_m);
  const double wv = 1.0 / (cfg_.sigma_range_rate_m_s * cfg_.sigma_range_rate_m_s);
  const int ns = num_states_;
  MatN nu{}, nw{};
  Mat4 nv{};
  VecN unused{};
  Vec4 gv{};
  double chi2 = 0.0, sum_v2 = 0.0, sum_s2 = 0.0;
  const EnuRotation to_enu(lla.lat_rad, lla.lon_rad);
  for (int i = 0; i < n_; ++i) {
    const Sat& s = sats_[i];
    const Enu e = to_enu(s.los);
    const Vec4 h{-e.x, -e.y, -e.z, 1.0};
    accumulate_range(nu, nullptr, -e.x, -e.y, -e.z, s.col, 1.0, 0.0);
    accumulate_range(nw, nullptr, -e.x, -e.y, -e.z, s.col, s.weight, 0.0);
    // Measured range rate minus the satellite part: -e.v_rx + c * drift.
    const double rr = -in.meas[i].wavelength_m * in.meas[i].doppler_hz;
    accumulate(nv, gv, h, wv, rr - s.los.dot(s.vel_rx_frame_m_s) + s.drift_m_s);
    chi2 += s.weight * s.resid_m * s.resid_m;
    sum_v2 += s.resid_m * s.resid_m;
    sum_s2 += s.sigma2;
    out.residual_m[i] = s.resid_m;
  }
  if (two_d) {
    // DOP is satellite geometry only: with 3 satellites the 4x4 is singular,
    // so take E, N, clock with the height known exactly (U row/column out).
    for (int k = 0; k < ns; ++k) nu[2][k] = nu[k][2] = 0.0;
    nu[2][2] = 1.0;
    const Vec4 h{0.0, 0.0, 1.0, 0.0};
    accumulate(nw, unused, VecN{0.0, 0.0, 1.0}, wh, 0.0, ns);
    accumulate(nv, gv, h, wv, 0.0);  // vertical velocity held at zero
    const double dh = in.held_height_m - lla.height_m;
    chi2 += wh * dh * dh;
  }
  // DOP and accuracy: the position and first-clock block of the inverse
  // with every clock state (the biases marginalised).
  MatN qu, qw;
  Mat4 qv;
  if (!spd_inverse(nu, qu, ns, kPivotTol) || !spd_inverse(nw, qw, ns, kPivotTol) ||
      !spd_inverse4(nv, qv, kPivotTol) || !finite(qu, ns) || !finite(qw, ns) || !finite4(qv))
    return false;

  // 2D: the max_pdop gate applies to the height-constrained position DOP (= HDOP).
  const double hdop = std::sqrt(qu[0][0] + qu[1][1]);
  const double pdop = two_d ? hdop : std::sqrt(qu[0][0] + qu[1][1] + qu[2][2]);
  if (!(pdop <= max_pdop_)) return false;
  out.dof = n_ + (two_d ? 1 : 0) - ns;
  out.chi2 = chi2;  // residual test: solve()

  out.dop.hdop = hdop;
  out.dop.tdop = std::sqrt(qu[3][3]);
  if (two_d) {
    // Undefined from 3 satellites: reported as unavailable (u-blox 99.99).
    out.dop.vdop = out.dop.pdop = out.dop.gdop = Dop::kNoDop;
  } else {
    out.dop.vdop = std::sqrt(qu[2][2]);
    out.dop.pdop = pdop;
    out.dop.gdop = std::sqrt(qu[0][0] + qu[1][1] + qu[2][2] + qu[3][3]);
  }

  const Vec4 xv = mul4(qv, gv);
  out.vel_enu_m_s = Enu(xv[0], xv[1], xv[2]);
  out.vel_m_s = Ecef(geo::enu_to_ecef_vector(out.vel_enu_m_s, lla.lat_rad, lla.lon_rad));
  out.drift_m_s = xv[3];
  if (!out.vel_m_s.finite() || !std::isfinite(out.drift_m_s)) return false;

  out.type = two_d ? FixType::k2D : FixType::k3D;
  out.pos_m = pos;
  out.lla = lla;
  out.clock_m = clock_m;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) out.cov_pos[i][k] = qw[i][k];
  q_ = qw;
  out.isb_m.fill(0.0);
  out.clock_systems = SystemSet();
  for (int c = 3; c < ns; ++c) {
    const GnssSystem sys = col_system_[static_cast<std::size_t>(c - 3)];
    out.clock_systems = out.clock_systems.with(sys);
    if (c > 3) out.isb_m[static_cast<std::size_t>(sys)] = bias_m_[static_cast<std::size_t>(c - 4)];
  }
  for (int k = 0; k < kNumSystems; ++k) {
    const GnssSystem sys = static_cast<GnssSystem>(k);
    out.isb_m[static_cast<std::size_t>(k)] = out.isb_m[static_cast<std::size_t>(clock_group(sys))];
  }
  solved_isb_m_ = out.isb_m;
  out.cov_vel = qv;
  out.num_used = n_;
  out.range_rms_m = std::sqrt(sum_v2 / n_);
  out.sigma_uere_m = std::sqrt(sum_s2 / n_);
  return true;
}

void Solver::solve(const SolverInput& in, SolverOutput& out) noexcept {
  in_solve_ = true;
  corr_cache_valid_ = false;
  solve_epoch(in, out);
  in_solve_ = false;
  subset_prepared_ = false;
  for (int i = 0; i < kMaxSatsInView; ++i) orig_[static_cast<std::size_t>(i)] = i;  // measurement_model: identity
}

void Solver::solve_epoch(const SolverInput& in, SolverOutput& out) noexcept {
  // idx[j]: index in `in` of measurement j of the set being solved.
  std::array<int, kMaxSatsInView>& idx = orig_;
  for (int i = 0; i < kMaxSatsInView; ++i) idx[i] = i;
  subset_prepared_ = false;
  const SolverInput* cur = &in;
  Outcome o = solve_all(*cur, out);
  // Every measurement of in, prepared: measurement_model reuses them.
  solved_ = {&in, in.t_rx_local, n_};
  std::copy(sats_.begin(), sats_.begin() + n_, solved_sats_.begin());
  solved_corr_valid_ = corr_valid_;
  solved_corr_pos_ = corr_pos_;
  int exclusions = 0;
  while (o == Outcome::kResidualTestFailed && n_ - 1 >= num_states_ + 1 &&
         exclusions++ < cfg_.max_exclusions) {
    const int worst = worst_residual(out);
    if (cur != &subset_) {
      subset_ = in;
      subset_.num_meas = n_;
      cur = &subset_;
    }
    for (int j = worst; j + 1 < subset_.num_meas; ++j) {
      subset_.meas[j] = subset_.meas[j + 1];
      idx[j] = idx[j + 1];
    }
    --subset_.num_meas;
    subset_prepared_ = true;
    o = solve_all(subset_, out);
  }
  if (o != Outcome::kFix) {
    out = SolverOutput{};
    return;
  }
  if (cur == &in) return;
  // Back to the indices of `in`; the excluded ones are flagged.
  const int n_in = std::clamp(in.num_meas, 0, kMaxSatsInView);
  std::array<double, kMaxSatsInView> r{};
  out.excluded.fill(false);
  for (int i = 0; i < n_in; ++i) out.excluded[i] = true;
  for (int j = 0; j < subset_.num_meas; ++j) {
    r[idx[j]] = out.residual_m[j];
    out.excluded[idx[j]] = false;
  }
  out.residual_m = r;
  out.num_excluded = n_in - subset_.num_meas;
}

int Solver::worst_residual(const SolverOutput& out) const noexcept {
  // Normalised (studentised) residual: v_i / sqrt(sigma_i^2 - h_i' Q h_i),
  // Q the weighted covariance of the solution (ENU + clock).
  int worst = 0;
  double worst_w = -1.0;
  const EnuRotation to_enu(out.lla.lat_rad, out.lla.lon_rad);
  for (int i = 0; i < n_; ++i) {
    const Sat& s = sats_[i];
    const Enu e = to_enu(s.los);
    const VecN h = design_row(-e.x, -e.y, -e.z, s.col);
    const VecN qh = mul(q_, h, num_states_);
    double hqh = 0.0;
    for (int k = 0; k < num_states_; ++k) hqh += h[k] * qh[k];
    const double var = std::max(s.sigma2 - hqh, 1e-6 * s.sigma2);
    const double w = out.residual_m[i] * out.residual_m[i] / var;
    if (w > worst_w) {
      worst_w = w;
      worst = i;
    }
  }
  return worst;
}

bool Solver::prepare(const SolverInput& in) noexcept {
  n_ = std::clamp(in.num_meas, 0, kMaxSatsInView);
  corr_valid_ = false;
  for (int i = 0; i < n_; ++i) {
    const Measurement& m = in.meas[i];
    Sat& s = sats_[i];
    if (subset_prepared_) {
      // A measurement of the whole set, prepared there from the same inputs.
      s = solved_sats_[static_cast<std::size_t>(orig_[static_cast<std::size_t>(i)])];
      s.corr_m = 0.0;
      s.model_var_m2 = 0.0;
      continue;
    }
    if (m.eph == nullptr || !std::isfinite(m.pseudorange_m) || !std::isfinite(m.doppler_hz) ||
        !(m.wavelength_m > 0.0) || !std::isfinite(m.wavelength_m)) {
      n_ = 0;  // malformed input: no fix rather than a guess
      return false;
    }
    const TransmitState tx = transmit_state(in.sky, *m.eph, in.t_rx_local, m.pseudorange_m);
    const time::GpsTime& t_tx = tx.t_tx;
    const orbit::SatState& st = tx.state;
    s.pos_m = st.pos_m;
    s.vel_m_s = st.vel_m_s;
    s.clk_m = kSpeedOfLight_m_s * (st.clk_bias_s - m.eph->tgd_s);
    s.drift_m_s = kSpeedOfLight_m_s * st.clk_drift_s_s;
    s.since_tx_s = in.t_rx_local - t_tx;
    s.corr_m = 0.0;
    s.model_var_m2 = 0.0;
    s.system = m.eph->sat.system;
    const double f = cfg_.system_sigma_factor[static_cast<std::size_t>(s.system)];
    s.efact2 = f * f;
    s.sat_var_m2 = satellite_variance_m2(cfg_, m.cn0_dbhz, m.eph->sv_accuracy_m, s.system) +
                   (m.correction_var_m2 > 0.0 ? m.correction_var_m2 : 0.0);
  }
  assign_clock_states();
  return true;
}

GnssSystem Solver::clock_group(GnssSystem sys) const noexcept {
  if (sys == GnssSystem::kSbas || (sys == GnssSystem::kQzss && !cfg_.qzss_own_clock)) return GnssSystem::kGps;
  return sys;
}

void Solver::assign_clock_states() noexcept {
  SystemSet present;
  for (int i = 0; i < n_; ++i) present = present.with(clock_group(sats_[i].system));
  std::array<int, kNumSystems> col{};
  num_states_ = 3;
  for (int k = 0; k < kNumSystems; ++k) {
    const GnssSystem sys = static_cast<GnssSystem>(k);
    if (!present.has(sys)) continue;
    col[static_cast<std::size_t>(k)] = num_states_;
    col_system_[static_cast<std::size_t>(num_states_ - 3)] = sys;
    ++num_states_;
  }
  for (int i = 0; i < n_; ++i) sats_[i].col = col[static_cast<std::size_t>(clock_group(sats_[i].system))];
}

int Solver::measurement_model(const SolverInput& in, const Ecef& pos_m, double clock_m,
                              std::array<MeasurementRow, kMaxSatsInView>& rows) noexcept {
  if (solved_.in == &in && solved_.t_rx_local == in.t_rx_local && solved_.n == in.num_meas) {
    // The epoch solve() just prepared: same satellites, same corrections.
    n_ = solved_.n;
    std::copy(solved_sats_.begin(), solved_sats_.begin() + n_, sats_.begin());
    corr_valid_ = solved_corr_valid_;
    corr_pos_ = solved_corr_pos_;
  } else if (!prepare(in)) {
    return 0;
  }
  assign_clock_states();
  for (int c = 4; c < num_states_; ++c) {
    bias_m_[static_cast<std::size_t>(c - 4)] =
        solved_isb_m_[static_cast<std::size_t>(col_system_[static_cast<std::size_t>(c - 3)])];
  }
  if (!(pos_m.norm() > kSurfaceRadius_m)) return 0;
  const Lla lla = geo::lla_from_ecef(pos_m);
  linearise(in, pos_m, clock_m, &lla);
  for (int i = 0; i < n_; ++i) {
    const Sat& s = sats_[i];
    MeasurementRow& r = rows[i];
    r.los = s.los;
    r.range_resid_m = s.resid_m;
    r.sigma2_m2 = s.sigma2;
    r.rate_obs_m_s = -in.meas[i].wavelength_m * in.meas[i].doppler_hz - s.los.dot(s.vel_rx_frame_m_s) + s.drift_m_s;
  }
  return n_;
}

Solver::Outcome Solver::solve_all(const SolverInput& in, SolverOutput& out) noexcept {
  out = SolverOutput{};
  prepare(in);
  // One measurement per state at least; one fewer with the height held.
  if (n_ < 3 || n_ < num_states_ - 1) return Outcome::kNoFix;
  const bool two_d = n_ == num_states_ - 1;
  bias_m_.fill(0.0);
  if (two_d && !in.have_held_height) return Outcome::kNoFix;

  Ecef pos;
  double clock_m = 0.0;
  if (two_d) {
    pos = in.held_pos_m;
    clock_m = in.have_prior ? in.prior_clock_m : 0.0;
  } else if (in.have_prior) {
    pos = in.prior_pos_m;
    clock_m = in.prior_clock_m;
  }
  bool ok = iterate(in, pos, clock_m, two_d);
  if (!ok && !two_d && in.have_prior) {  // warm start diverged: cold start
    pos = Ecef{};
    clock_m = 0.0;
    bias_m_.fill(0.0);
    ok = iterate(in, pos, clock_m, two_d);
  }
  if (!ok || !finish(in, pos, clock_m, two_d, out)) {
    out = SolverOutput{};
    return Outcome::kNoFix;
  }
  if (out.dof >= 1 && z_pfa_ > 0.0 && out.chi2 > chi2_threshold(out.dof)) return Outcome::kResidualTestFailed;
  return Outcome::kFix;
}

}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/rtk/rtk_engine.hpp"

#include <algorithm>
#include <cmath>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/receiver/solution/transmit_state.hpp"
#include "core/world/sky/sky.hpp"

// update(), flush() and carry_code_block() are most of the filter's cost:
// also built for AVX2, picked at load time where the CPU has it. No FMA: the same products and
// sums in the same order, so the same results on every x86-64. GCC only:
// clang wants the attribute on a member's first declaration (the header),
// and its builds here are the fuzz targets, which do not need the speed.
#if defined(__x86_64__) && defined(__GLIBC__) && defined(__has_attribute) && !defined(__clang__)
#if __has_attribute(target_clones)
#define GNSSEMU_RTK_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#endif
#endif
#ifndef GNSSEMU_RTK_AVX2_CLONE
#define GNSSEMU_RTK_AVX2_CLONE
#endif

namespace gnssemu::receiver::rtk {
namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;

constexpr double kInitPosVar_m2 = 100.0;      // a standalone fix: metres
constexpr double kInitAmbVar_m2 = 900.0;      // RTKLIB's 30 m initial ambiguity sigma
constexpr double kClockVar_m2 = 1.0e4;        // the clock difference, white per epoch
constexpr double kMaxGap_s = 5.0;             // longer without an update: the filter starts over
constexpr double kMaxJump_m = 50.0;           // standalone fix this far from the filter: start over
constexpr double kCodeGate2 = 25.0;           // 5 sigma innovation gates
constexpr double kPhaseGate2 = 25.0;
constexpr double kMaxCodeInnovation_m = 30.0;
constexpr int kMinPhaseSats = 5;              // 4 double differences
constexpr int kMinCodeSats = 4;
// A held rover epoch and a base epoch are the same measurement epoch: both
// receivers measure on whole GPS milliseconds of one grid (at most 10 Hz here).
constexpr double kEpochMatch_s = 0.025;
// Validation of a held fix: carrier residuals against their sigma.
constexpr double kMaxNormResidual = 5.0;
constexpr double kMaxChi2PerDof = 4.0;

struct Range {
  double range_m = 0.0;
  Vec3 e;  // unit line of sight, receiver -> satellite
};

// Geometric range with the Earth's rotation during the signal's flight (from
// the geometry, not the pseudorange, so the receiver clock does not enter).
Range geometric_range(const Ecef& sat_m, const Ecef& rx_m) noexcept {
  Vec3 d = sat_m - rx_m;
  double r = d.norm();
  for (int i = 0; i < 2; ++i) {
    d = world::rotate_earth(sat_m, kOmegaEarth_rad_s * r / kSpeedOfLight_m_s) - rx_m;
    r = d.norm();
  }
  return {r, d / r};
}

double wavelength_of(const RawMeasurement& m) noexcept {
  return kSpeedOfLight_m_s / signal_carrier_hz(m.signal, m.glonass_channel);
}

int key_of(const RawMeasurement& m) noexcept { return m.sat.index() * kNumBands + signal_info(m.signal).band; }

double inv_sin_el(double el_rad) noexcept { return 1.0 / std::max(std::sin(el_rad), 0.1); }

Mat3 to_enu(const Mat3& c, const Lla& at) noexcept {
  const geo::EnuAxes ax = geo::enu_axes(at.lat_rad, at.lon_rad);
  const Vec3 r[3] = {ax.e, ax.n, ax.u};
  Mat3 out{};
  for (int a = 0; a < 3; ++a) {
    Vec3 ca{};
    ca.x = c[0][0] * r[a].x + c[0][1] * r[a].y + c[0][2] * r[a].z;
    ca.y = c[1][0] * r[a].x + c[1][1] * r[a].y + c[1][2] * r[a].z;
    ca.z = c[2][0] * r[a].x + c[2][1] * r[a].y + c[2][2] * r[a].z;
    for (int b = 0; b < 3; ++b) out[b][a] = r[b].dot(ca);
  }
  return out;
}

// 3x3 symmetric inverse by cofactors; false when singular.
bool inverse3(const Mat3& a, Mat3& inv) noexcept {
  const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
  if (!(std::fabs(det) > 1e-30) || !std::isfinite(det)) return false;
  inv[0][0] = c00 / det;
  inv[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det;
  inv[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det;
  inv[1][0] = c01 / det;
  inv[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
  inv[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det;
  inv[2][0] = c02 / det;
  inv[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det;
  inv[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det;
  return true;
}

}  // namespace

void RtkEngine::reset() noexcept {
  init_ = false;
  fixed_ = false;
  n_slots_ = 0;
  slot_of_.fill(-1);
  slot_map_ready_ = true;
  last_ar_s_ = -1.0e300;
}

void RtkEngine::reset_filter(const Ecef& pos_m) noexcept {
  reset();
  init_ = true;
  init_arp_ = false;
  for (auto& row : p_) row.fill(0.0);
  x_.fill(0.0);
  x_[0] = pos_m.x;
  x_[1] = pos_m.y;
  x_[2] = pos_m.z;
  for (int i = 0; i < 3; ++i) p_[i][i] = kInitPosVar_m2;
}

void RtkEngine::clear_link_fields(Fix& fix) const noexcept {
  fix.diff_soln = false;
  fix.sbas_soln = false;
  fix.carr_soln = CarrierSolution::kNone;
  fix.corr_age_s = -1.0;
  fix.ref_station_id = -1;
  fix.rel_pos = RelativePosition{};
}

void RtkEngine::zero_cross(int i) noexcept {
  flush();
  const int n = n_states();
  for (int j = 0; j < n; ++j) p_[i][j] = p_[j][i] = 0.0;
}

void RtkEngine::reset_ambiguity(int s, double value_cyc, double var_cyc2) noexcept {
  const int i = kAmbState0 + s;
  zero_cross(i);
  x_[i] = value_cyc;
  p_[i][i] = var_cyc2;
  Slot& sl = slots_[static_cast<std::size_t>(s)];
  ++sl.arc;
  sl.held = false;
}

int RtkEngine::slot_for(int key, GnssSystem sys, int band, double wavelength_m) noexcept {
  const int s = slot_of_[static_cast<std::size_t>(key)];
  if (s >= 0) return s;
  if (n_slots_ >= kMaxSlots) return -1;
  flush();  // before the state grows: the pending terms span the old states
  const int ns = n_slots_++;
  Slot& sl = slots_[static_cast<std::size_t>(ns)];
  const std::uint32_t arc = sl.arc;
  sl = Slot{};
  sl.arc = arc + 1;
  sl.key = key;
  sl.system = sys;
  sl.band = band;
  sl.wavelength_m = wavelength_m;
  slot_of_[static_cast<std::size_t>(key)] = static_cast<std::int8_t>(ns);
  zero_cross(kAmbState0 + ns);
  x_[static_cast<std::size_t>(kAmbState0 + ns)] = 0.0;
  p_[static_cast<std::size_t>(kAmbState0 + ns)][static_cast<std::size_t>(kAmbState0 + ns)] = 0.0;
  return ns;
}

// Move the last slot into s: the state vector stays dense.
void RtkEngine::free_slot(int s) noexcept {
  flush();
  const int last = n_slots_ - 1;
  slot_of_[static_cast<std::size_t>(slots_[static_cast<std::size_t>(s)].key)] = -1;
  if (s != last) {
    // Lower triangle (i < j): P(i,k) = P(j,k) for k < j.
    const int i = kAmbState0 + s, j = kAmbState0 + last;
    for (int k = 0; k < i; ++k) p_[i][k] = p_[j][k];
    for (int k = i + 1; k < j; ++k) p_[k][i] = p_[j][k];
    p_[i][i] = p_[j][j];
    x_[i] = x_[j];
    slots_[static_cast<std::size_t>(s)] = slots_[static_cast<std::size_t>(last)];
    slot_of_[static_cast<std::size_t>(slots_[static_cast<std::size_t>(s)].key)] = static_cast<std::int8_t>(s);
  }
  --n_slots_;
}

GNSSEMU_RTK_AVX2_CLONE bool RtkEngine::update(const int* idx, const double* h, int nh, double v, double r,
                                              double gate2, int n_active) noexcept {
  // P h from p_'s lower triangle, less the pending terms' share:
  // (p_ - sum_c ph_c ph_c' inv_c) h. A whole-state update computes it in
  // its pending slot.
  const bool block = n_active > 0;
  if (block) flush();
  const int n = block ? n_active : n_states();
  double* ph = block ? ph_.data() : pend_ph_[static_cast<std::size_t>(n_pend_)].data();
  // Row i of P h: h_k P(idx_k, i) summed in k order. The block alone: from
  // pv(). The whole state: the position-and-clock columns from cols_
  // (contiguous), an ambiguity's along its row, then down its column.
  if (block || n <= kAmbState0) {
    for (int i = 0; i < n; ++i) {
      double acc = 0.0;
      for (int k = 0; k < nh; ++k) acc += h[k] * pv(idx[k], i);
      ph[i] = acc;
    }
  } else {
    // p_ changes only with no pending terms (flush() or before any update).
    if (n_pend_ == 0) {
      for (int a = 0; a < kAmbState0; ++a) {
        auto& col = cols_[static_cast<std::size_t>(a)];
        for (int i = 0; i < kAmbState0; ++i) col[static_cast<std::size_t>(i)] = pv(i, a);
        for (int i = kAmbState0; i < n; ++i)
          col[static_cast<std::size_t>(i)] = p_[static_cast<std::size_t>(i)][static_cast<std::size_t>(a)];
      }
    }
    // The leading position-and-clock terms (up to four) in one pass, absent
    // ones weighted zero; the rest one pass each.
    constexpr int kFused = 4;
    const double* cp[kFused];
    double hw[kFused];
    int k0 = 0;
    for (; k0 < nh && k0 < kFused && idx[k0] < kAmbState0; ++k0) {
      cp[k0] = cols_[static_cast<std::size_t>(idx[k0])].data();
      hw[k0] = h[k0];
    }
    for (int z = k0; z < kFused; ++z) {
      cp[z] = cols_[0].data();
      hw[z] = 0.0;
    }
    for (int i = 0; i < n; ++i)
      ph[i] = ((hw[0] * cp[0][i] + hw[1] * cp[1][i]) + hw[2] * cp[2][i]) + hw[3] * cp[3][i];
    for (int k = k0; k < nh; ++k) {
      const double hk = h[k];
      const int c = idx[k];
      if (c < kAmbState0) {
        const auto& col = cols_[static_cast<std::size_t>(c)];
        for (int i = 0; i < n; ++i) ph[i] += hk * col[static_cast<std::size_t>(i)];
        continue;
      }
      const auto& row = p_[static_cast<std::size_t>(c)];
      const int e = std::min(c + 1, n);
      for (int i = 0; i < e; ++i) ph[i] += hk * row[static_cast<std::size_t>(i)];
      for (int i = c + 1; i < n; ++i) ph[i] += hk * p_[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)];
    }
  }
  for (int c = 0; c < n_pend_; ++c) {
    const auto& pc = pend_ph_[static_cast<std::size_t>(c)];
    double w = 0.0;
    for (int k = 0; k < nh; ++k) w += h[k] * pc[idx[k]];
    w *= pend_inv_[static_cast<std::size_t>(c)];
    if (w == 0.0) continue;
    for (int j = 0; j < n; ++j) ph[j] -= w * pc[j];
  }
  double s = r;
  for (int k = 0; k < nh; ++k) s += h[k] * ph[idx[k]];
  if (!(s > 0.0) || !std::isfinite(v) || v * v > gate2 * s) {
    // flush() adds every slot's terms (zero weight beyond the pending ones): no leftovers.
    if (!block) std::fill(ph, ph + n, 0.0);
    return false;
  }
  const double inv = 1.0 / s;
  for (int j = 0; j < n; ++j) x_[j] += ph[j] * inv * v;
  if (block) {
    for (int a = 0; a < n; ++a) {
      const double ka = ph[a] * inv;
      if (ka == 0.0) continue;
      auto& row = p_[static_cast<std::size_t>(a)];
      for (int j = 0; j <= a; ++j) row[j] -= ka * ph[j];
    }
    return true;
  }
  pend_inv_[static_cast<std::size_t>(n_pend_)] = inv;
  if (++n_pend_ == kPendingUpdates) flush();
  return true;
}

GNSSEMU_RTK_AVX2_CLONE void RtkEngine::flush() noexcept {
  if (n_pend_ == 0) return;
  const int n = n_states();
  const int np = n_pend_;
  n_pend_ = 0;
  for (int i = 0; i < n; ++i) {
    double a[kPendingUpdates] = {};
    bool any = false;
    for (int c = 0; c < np; ++c) {
      a[c] = pend_ph_[static_cast<std::size_t>(c)][i] * pend_inv_[static_cast<std::size_t>(c)];
      any |= a[c] != 0.0;
    }
    if (!any) continue;
    auto& row = p_[static_cast<std::size_t>(i)];
    // Terms beyond np: a = 0 and a zero vector (cleared below after each flush).
    static_assert(kPendingUpdates == 8, "the sum below spells out eight terms");
    const auto& q = pend_ph_;
    for (int j = 0; j <= i; ++j) {
      row[j] -= ((a[0] * q[0][j] + a[1] * q[1][j]) + (a[2] * q[2][j] + a[3] * q[3][j])) +
                ((a[4] * q[4][j] + a[5] * q[5][j]) + (a[6] * q[6][j] + a[7] * q[7][j]));
    }
  }
  for (int c = 0; c < np; ++c) pend_ph_[static_cast<std::size_t>(c)].fill(0.0);
}

GNSSEMU_RTK_AVX2_CLONE void RtkEngine::carry_code_block(const std::array<double, 3>& xp0, const Mat3& ppp0,
                                                        const Mat3& ppp0_inv) noexcept {
  // Code measurements see the block a = (position, clocks) only, so the
  // ambiguities b follow from b | a (Gaussian conditioning): with K = [J 0],
  // J = P_bp P_pp^-1 (the clocks start uncorrelated), x_b += J dx_p,
  // P_ba = J P'_pa, P_bb -= J (P_pp - P'_pp) J'. Exactly the sequential
  // updates' result at O(n_b^2) once instead of O(n^2) per measurement.
  const int n = n_states();
  const int nb = n - kAmbState0;
  if (nb <= 0) return;
  std::array<std::array<double, 3>, kMaxSlots> j{};
  std::array<std::array<double, 3>, kMaxSlots> jd{};
  std::array<std::array<double, kMaxSlots>, 3> jt{};  // j transposed: P_bb's rows vectorise
  Mat3 d{};
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) d[a][c] = ppp0[a][c] - pv(a, c);
  const double dx[3] = {x_[0] - xp0[0], x_[1] - xp0[1], x_[2] - xp0[2]};
  for (int b = 0; b < nb; ++b) {
    const auto& row = p_[static_cast<std::size_t>(kAmbState0 + b)];
    auto& jb = j[static_cast<std::size_t>(b)];
    for (int c = 0; c < 3; ++c) jb[c] = row[0] * ppp0_inv[0][c] + row[1] * ppp0_inv[1][c] + row[2] * ppp0_inv[2][c];
    x_[kAmbState0 + b] += jb[0] * dx[0] + jb[1] * dx[1] + jb[2] * dx[2];
    for (int c = 0; c < 3; ++c) jd[static_cast<std::size_t>(b)][c] = jb[0] * d[0][c] + jb[1] * d[1][c] + jb[2] * d[2][c];
    for (int c = 0; c < 3; ++c) jt[static_cast<std::size_t>(c)][static_cast<std::size_t>(b)] = jb[c];
  }
  for (int b = 0; b < nb; ++b) {
    auto& row = p_[static_cast<std::size_t>(kAmbState0 + b)];
    const auto& db = jd[static_cast<std::size_t>(b)];
    double* rb = row.data() + kAmbState0;
    for (int c = 0; c <= b; ++c) rb[c] -= db[0] * jt[0][c] + db[1] * jt[1][c] + db[2] * jt[2][c];
  }
  for (int b = 0; b < nb; ++b) {
    const auto& jb = j[static_cast<std::size_t>(b)];
    for (int a = 0; a < kAmbState0; ++a) {
      p_[kAmbState0 + b][a] = jb[0] * pv(0, a) + jb[1] * pv(1, a) + jb[2] * pv(2, a);
    }
  }
}

void RtkEngine::process_base(const Corrections& c, const world::SharedSky* sky) noexcept {
  ++base_stamp_;
  base_revision_ = c.revision;
  base_seen_ = true;
  const RawEpoch& b = c.obs;
  const Ecef& arp = c.station.arp_ecef_m;
  // The geometry once per satellite, as the rover's (solve): its band-1
  // measurement, which follows its band-0 one, takes that one's geometry.
  SatId last_sat{};
  bool last_valid = false;
  Range g{};
  double sat_clock_m = 0.0;
  for (int i = 0; i < b.num_meas; ++i) {
    const RawMeasurement& m = b.meas[static_cast<std::size_t>(i)];
    if (!m.pseudorange_valid) continue;
    const std::size_t k = static_cast<std::size_t>(m.sat.index());
    const orbit::Ephemeris* eph = eph_stamp_[k] == epoch_ ? eph_[k] : nullptr;
    if (eph == nullptr) {
      ++status_.unmatched;  // a satellite the rover does not see
      continue;
    }
    if (!last_valid || m.sat != last_sat) {
      const TransmitState ts = transmit_state(sky, *eph, b.t_rx, m.pseudorange_m);
      g = geometric_range(ts.state.pos_m, arp);
      sat_clock_m = kSpeedOfLight_m_s * ts.state.clk_bias_s;
      last_sat = m.sat;
      last_valid = true;
    }
    BaseSignal& bs = base_[static_cast<std::size_t>(key_of(m))];
    bs.stamp = base_stamp_;
    bs.code_omc_m = m.pseudorange_m - g.range_m + sat_clock_m;
    bs.phase = m.carrier_valid;
    bs.phase_omc_m = m.carrier_phase_cycles * wavelength_of(m) - g.range_m + sat_clock_m;
    // An unaligned base's GLONASS phase range plus its code-phase bias is an
    // aligned one, as the rover's own (RTCM 10403.3 DF421, DF423/DF425).
    if (m.sat.system == GnssSystem::kGlonass && !c.glonass_cpb_aligned)
      bs.phase_omc_m += c.glonass_cpb_m[signal_info(m.signal).band == 0 ? 0 : 2];
    bs.half_cycle = m.half_cycle_resolved;
    bs.lock_s = m.lock_time_s;
    bs.code_sigma_m = m.pseudorange_sigma_m;
  }
}

void RtkEngine::predict(double dt_s, const Vec3& shift_m, double shift_sigma_m) noexcept {
  const Vec3 dv = shift_m;
  x_[0] += dv.x;
  x_[1] += dv.y;
  x_[2] += dv.z;
  const double sv = shift_sigma_m;
  const double q = sv * sv + cfg_.pos_process_m_sqrt_s * cfg_.pos_process_m_sqrt_s * dt_s;
  for (int i = 0; i < 3; ++i) p_[i][i] += q;
  const double qa = cfg_.amb_process_cyc_sqrt_s * cfg_.amb_process_cyc_sqrt_s * dt_s;
  for (int s = 0; s < n_slots_; ++s) p_[kAmbState0 + s][kAmbState0 + s] += qa;
}

void RtkEngine::step(const RawEpoch& rover, const world::Observables& obs, const Corrections* corr,
                     Fix& fix) noexcept {
  if (!slot_map_ready_) reset();
  ++epoch_;
  const bool prev_early = last_early_;
  held_last_ = -1;
  last_early_ = false;
  clear_link_fields(fix);
  status_.num_code_sd = status_.num_phase_sd = status_.num_fixed_dd = 0;
  if (!is_gnss_fix(fix.type) || corr == nullptr || !corr->obs_valid || !corr->station.position_valid ||
      !rover.time_valid) {
    init_ = false;
    fixed_ = false;
    return;
  }
  const Corrections& c = *corr;
  const double age_s = rover.t_rx - c.obs.t_rx;
  if (!std::isfinite(age_s) || age_s > cfg_.dgnss_timeout_s || age_s < -1.0) {
    ++status_.stale;
    init_ = false;
    fixed_ = false;
    return;
  }

  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[i];
    const std::size_t k = static_cast<std::size_t>(o.sat.index());
    eph_[k] = o.eph;
    eph_stamp_[k] = epoch_;
  }
  for (int i = 0; i < fix.num_sats; ++i) el_rad_[static_cast<std::size_t>(fix.sats[i].sat.index())] = fix.sats[i].el_rad;
  if (c.station.moving) {
    step_moving(rover, obs, c, prev_early, fix);
    return;
  }
  // A fixed base: its newest epoch with its age (the base does not move in between).
  if (!base_seen_ || c.revision != base_revision_) process_base(c, obs.sky);
  solve(rover, NavSnapshot{fix.t, fix.pos_m, fix.vel_m_s, fix.speed_acc_m_s}, c, obs, fix);
}

void RtkEngine::step_moving(const RawEpoch& rover, const world::Observables& obs, const Corrections& c,
                            bool prev_early, Fix& fix) noexcept {
  // The rover solves the baseline only with the base's observations of the
  // same epoch (ZED-F9P integration manual UBX-18010802 §3.1.5.6: relPosValid
  // "if the rover managed to get the time-matched observations in time"):
  // it holds its own epoch until the base's arrives.
  held_last_ = held_next_;
  HeldEpoch& now = held_[static_cast<std::size_t>(held_next_)];
  held_next_ = (held_next_ + 1) % kMovingBaseHeldEpochs;
  now.pending = true;
  now.reported = false;
  now.raw = rover;
  now.nav = NavSnapshot{fix.t, fix.pos_m, fix.vel_m_s, fix.speed_acc_m_s};

  HeldEpoch* match = nullptr;
  if (!base_seen_ || c.revision != base_revision_) {
    for (HeldEpoch& h : held_) {
      if (h.pending && std::fabs(h.raw.t_rx - c.obs.t_rx) < kEpochMatch_s) match = &h;
    }
  }
  // Epochs the base can no longer match: older than the matched one (the
  // base's epochs arrive in order) or held past the limit.
  for (HeldEpoch& h : held_) {
    if (!h.pending || &h == match) continue;
    // Receiver times: whole epochs apart within the clocks' drift. < 0: time went back.
    const double held_s = rover.t_rx - h.raw.t_rx;
    if ((match != nullptr && h.raw.t_rx - match->raw.t_rx < 0.0) ||
        held_s > cfg_.moving_base_max_age_s + kEpochMatch_s ||
        held_s < 0.0) {
      h.pending = false;
      ++status_.moving_base_missed;
    }
  }
  if (match == nullptr) {
    fix.rel_pos.moving_base = true;
    fix.rel_pos.ref_station_id = c.station.station_id;
    fix.rel_pos.t = fix.t;
    if (prev_early) {
      // The base's last epoch came within its period: this one's RELPOSNED
      // goes out when its base epoch arrives (on_base_epoch), not now.
      fix.rel_pos.held = true;
      return;
    }
    // Nothing to solve this epoch: RELPOSNED without a baseline (refObsMiss).
    fix.rel_pos.ref_obs_miss = true;
    now.reported = true;
    return;
  }
  match->pending = false;
  ++status_.moving_base_matched;
  status_.moving_base_delay_s = fix.t - match->nav.t;
  process_base(c, obs.sky);
  solve(match->raw, match->nav, c, obs, fix);
  fix.rel_pos.moving_base = true;
  fix.rel_pos.ref_station_id = c.station.station_id;
  fix.rel_pos.t = match->nav.t;
  fix.rel_pos.late = fix.t - match->nav.t > 1e-6;
}

bool RtkEngine::on_base_epoch(const world::Observables& obs, const Corrections* corr, Fix& fix) noexcept {
  if (held_last_ < 0 || corr == nullptr) return false;
  const Corrections& c = *corr;
  HeldEpoch& h = held_[static_cast<std::size_t>(held_last_)];
  if (!c.station.moving || !c.obs_valid || !c.station.position_valid || !h.pending ||
      (base_seen_ && c.revision == base_revision_) || std::fabs(h.raw.t_rx - c.obs.t_rx) >= kEpochMatch_s) {
    return false;
  }
  // Only the last step's epoch: its ephemerides, elevations and sky are the
  // ones this engine holds; an older epoch waits for the next step.
  h.pending = false;
  held_last_ = -1;
  last_early_ = true;
  ++status_.moving_base_matched;
  ++status_.moving_base_early;
  status_.moving_base_delay_s = 0.0;
  status_.num_code_sd = status_.num_phase_sd = status_.num_fixed_dd = 0;
  const RelativePosition before = fix.rel_pos;
  fix.rel_pos = RelativePosition{};
  process_base(c, obs.sky);
  solve(h.raw, h.nav, c, obs, fix);
  fix.rel_pos.moving_base = true;
  fix.rel_pos.ref_station_id = c.station.station_id;
  fix.rel_pos.t = h.nav.t;
  if (h.reported) {
    fix.rel_pos = before;  // its refObsMiss already went out
    return false;
  }
  return true;
}

void RtkEngine::solve(const RawEpoch& rover, const NavSnapshot& nav, const Corrections& c,
                      const world::Observables& obs, Fix& fix) noexcept {
  const double age_s = rover.t_rx - c.obs.t_rx;
  double dt_s = init_ ? nav.t - t_last_ : 0.0;
  const Ecef nav_pos = nav.pos_m;
  if (!init_ || !std::isfinite(dt_s) || dt_s < 0.0 || dt_s > kMaxGap_s ||
      (Ecef(x_[0], x_[1], x_[2]) - nav_pos).norm() > kMaxJump_m) {
    reset_filter(nav_pos);
    dt_s = 0.0;
  }
  t_last_ = nav.t;
  if (c.station.moving) {
    // The baseline, not the rover's track, is what stays (nearly) still: the
    // rover's state follows the base's reported position, whose own
    // standalone noise then cancels (the double differences fix rover - base).
    const Vec3 shift = init_arp_ ? Vec3(c.station.arp_ecef_m - last_arp_m_) : Vec3{};
    // A turning vehicle swings the baseline about the base: as far as the
    // rover moved against the base since the last epoch (its own velocity
    // against the base's displacement), in a direction the turn decides, so
    // as variance (30 deg/s at 1 m and 1 Hz: 0.5 m).
    const double swing_m = init_arp_ ? (nav.vel_m_s * dt_s - shift).norm() : 0.0;
    predict(dt_s, shift, std::hypot(swing_m, nav.speed_acc_m_s * dt_s));
  } else {
    predict(dt_s, nav.vel_m_s * dt_s, nav.speed_acc_m_s * dt_s);
  }
  last_arp_m_ = c.station.arp_ecef_m;
  init_arp_ = true;
  x_lin_ = Ecef(x_[0], x_[1], x_[2]);

  const bool use_carrier = age_s <= cfg_.max_carrier_age_s;
  const double baseline_m = (x_lin_ - c.station.arp_ecef_m).norm();
  status_.baseline_m = baseline_m;
  if (baseline_m > cfg_.warn_baseline_m) ++status_.baseline_big;
  // GLONASS inter-frequency code-phase biases: no GLONASS fix without 1230 (IMF9 R02 §3.1).
  glonass_ar_ = c.glonass_cpb_valid;
  const double atmo_m = cfg_.baseline_sigma_m_m * baseline_m + cfg_.age_sigma_m_s * std::max(age_s, 0.0);
  for (int s = 0; s < n_slots_; ++s) slots_[static_cast<std::size_t>(s)].in_use = false;

  // The clock differences are white: a fresh state per system every epoch.
  std::array<bool, kNumSystems> clock_init{};
  for (int sys = 0; sys < kNumSystems; ++sys) zero_cross(kClockState0 + sys);

  // Pass 1: code, on the position-and-clock block, the ambiguities then
  // conditioned on it once (carry_code_block). Pass 2: carrier (new
  // ambiguities from the code-updated clock).
  for (int i = 0; i < rover.num_meas; ++i) geom_[static_cast<std::size_t>(i)].valid = false;
  const std::array<double, 3> xp0{x_[0], x_[1], x_[2]};
  Mat3 ppp0{}, ppp0_inv{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) ppp0[a][b] = pv(a, b);
  // A singular position covariance (never after predict): every update on the whole state.
  const int code_block = inverse3(ppp0, ppp0_inv) ? kAmbState0 : 0;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1 && code_block > 0) carry_code_block(xp0, ppp0, ppp0_inv);
    for (int i = 0; i < rover.num_meas; ++i) {
      const RawMeasurement& m = rover.meas[static_cast<std::size_t>(i)];
      const int key = key_of(m);
      const BaseSignal& bs = base_[static_cast<std::size_t>(key)];
      const std::size_t k = static_cast<std::size_t>(m.sat.index());
      if (bs.stamp != base_stamp_ || !m.pseudorange_valid || eph_stamp_[k] != epoch_ || eph_[k] == nullptr) continue;
      const double el = el_rad_[k];
      if (el < cfg_.elevation_mask_rad) continue;
      // The geometry once per satellite: its band-1 measurement follows its band-0 one.
      Geometry& geo = geom_[static_cast<std::size_t>(i)];
      if (pass == 0) {
        if (i > 0 && rover.meas[static_cast<std::size_t>(i - 1)].sat == m.sat && geom_[static_cast<std::size_t>(i - 1)].valid) {
          geo = geom_[static_cast<std::size_t>(i - 1)];
        } else {
          const TransmitState ts = transmit_state(obs.sky, *eph_[k], rover.t_rx, m.pseudorange_m);
          const Range gr = geometric_range(ts.state.pos_m, x_lin_);
          geo.range_m = gr.range_m;
          geo.e = gr.e;
          geo.sat_clock_m = kSpeedOfLight_m_s * ts.state.clk_bias_s;
          geo.valid = true;
        }
      } else if (!geo.valid) {
        continue;
      }
      const Range g{geo.range_m, geo.e};
      const double sat_clock_m = geo.sat_clock_m;
      const int sys = static_cast<int>(m.sat.system);
      const int ic = kClockState0 + sys;
      const double dpos = -(g.e.dot(Ecef(x_[0], x_[1], x_[2]) - x_lin_));
      if (pass == 0) {
        const double y = (m.pseudorange_m - g.range_m + sat_clock_m) - bs.code_omc_m;
        if (!clock_init[static_cast<std::size_t>(sys)]) {
          clock_init[static_cast<std::size_t>(sys)] = true;
          flush();  // pending whole-state code updates (a singular position block) and cols_ see the old P
          x_[ic] = y;
          p_[ic][ic] = kClockVar_m2;
        }
        const double v = y - dpos - x_[ic];
        if (std::fabs(v) > kMaxCodeInnovation_m) continue;
        const double sc = cfg_.code_sigma_m * inv_sin_el(el);
        const double r = 2.0 * sc * sc + m.pseudorange_sigma_m * m.pseudorange_sigma_m +
                         bs.code_sigma_m * bs.code_sigma_m + atmo_m * atmo_m;
        const int idx[4] = {0, 1, 2, ic};
        const double h[4] = {-g.e.x, -g.e.y, -g.e.z, 1.0};
        if (update(idx, h, 4, v, r, kCodeGate2, code_block)) ++status_.num_code_sd;
        continue;
      }
      if (!use_carrier || !m.carrier_valid || !bs.phase || !clock_init[static_cast<std::size_t>(sys)]) continue;
      const double lam = wavelength_of(m);
      const int s = slot_for(key, m.sat.system, signal_info(m.signal).band, lam);
      if (s < 0) continue;
      Slot& sl = slots_[static_cast<std::size_t>(s)];
      const double y = (m.carrier_phase_cycles * lam - g.range_m + sat_clock_m) - bs.phase_omc_m;
      const int ia = kAmbState0 + s;
      // A new arc on either side: lock time restarted or the half-cycle state changed.
      const bool restart = p_[ia][ia] == 0.0 || m.lock_time_s < sl.lock_r_s || bs.lock_s < sl.lock_b_s ||
                           m.half_cycle_resolved != sl.half_r || bs.half_cycle != sl.half_b;
      if (restart) {
        if (p_[ia][ia] != 0.0) ++status_.slips;
        reset_ambiguity(s, (y - dpos - x_[ic]) / lam, kInitAmbVar_m2 / (lam * lam));
      }
      sl.lock_r_s = m.lock_time_s;
      sl.lock_b_s = bs.lock_s;
      sl.half_r = m.half_cycle_resolved;
      sl.half_b = bs.half_cycle;
      const double sp = cfg_.phase_sigma_a_m + cfg_.phase_sigma_b_m * inv_sin_el(el);
      const double sr = m.carrier_sigma_cycles * lam;
      const double r = 2.0 * sp * sp + sr * sr + atmo_m * atmo_m;
      const int idx[5] = {0, 1, 2, ic, ia};
      const double h[5] = {-g.e.x, -g.e.y, -g.e.z, 1.0, lam};
      const double v = y - dpos - x_[ic] - lam * x_[ia];
      if (!update(idx, h, 5, v, r, kPhaseGate2)) {
        // Not explained by the float state: a slip the loops did not flag.
        ++status_.slips;
        reset_ambiguity(s, (y - dpos - x_[ic]) / lam, kInitAmbVar_m2 / (lam * lam));
        if (!update(idx, h, 5, y - dpos - x_[ic] - lam * x_[ia], r, 1.0e12)) continue;
      }
      sl.in_use = true;
      sl.y_m = y;
      sl.e = g.e;
      sl.var_m2 = r;
      sl.el_rad = el;
      ++status_.num_phase_sd;
    }
  }
  flush();
  for (int s = n_slots_ - 1; s >= 0; --s)
    if (!slots_[static_cast<std::size_t>(s)].in_use) free_slot(s);

  if (status_.num_code_sd < kMinCodeSats) {
    // Not enough common satellites: the standalone fix stands, and the
    // filter starts over with the next usable epoch rather than carry
    // ambiguities through an outage the code cannot check.
    fixed_ = false;
    init_ = false;
    return;
  }
  const bool carrier = status_.num_phase_sd >= kMinPhaseSats;
  if (!carrier) fixed_ = false;
  const double t_s = nav.t.week() * 604800.0 + nav.t.tow_s();
  bool fixed = false;
  Ecef pos(x_[0], x_[1], x_[2]);
  Mat3 cov{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) cov[a][b] = pv(a, b);
  if (carrier) {
    if (baseline_m > cfg_.max_fix_baseline_m) {
      ++status_.long_baseline;
      fixed_ = false;
    } else if (!cfg_.fix_ambiguities) {
      fixed_ = false;
    } else {
      if (fixed_) {
        Ecef fp;
        Mat3 fc;
        if (fixed_solution(fp, fc)) {
          pos = fp;
          cov = fc;
          fixed = true;
        } else {
          fixed_ = false;
          ++status_.fix_rejections;
        }
      }
      const double interval = fixed_ ? cfg_.refix_interval_s : cfg_.ar_interval_s;
      if (t_s - last_ar_s_ >= interval - 1e-6 && try_fix(t_s)) {
        Ecef fp;
        Mat3 fc;
        if (fixed_solution(fp, fc)) {
          if (!fixed_) ++status_.fixes;
          fixed_ = true;
          pos = fp;
          cov = fc;
          fixed = true;
        }
      }
    }
  }
  write_output(c, age_s, carrier, fixed, pos, cov, fix);
}

bool RtkEngine::try_fix(double t_s) noexcept {
  last_ar_s_ = t_s;
  ++status_.ar_attempts;
  // Candidates: ambiguities locked long enough with the half cycle resolved on both sides.
  std::array<int, kMaxSlots> cand{};
  int nc = 0;
  for (int s = 0; s < n_slots_; ++s) {
    const Slot& sl = slots_[static_cast<std::size_t>(s)];
    if (sl.system == GnssSystem::kGlonass && !glonass_ar_) continue;
    if (sl.in_use && sl.half_r && sl.half_b && sl.lock_r_s >= cfg_.min_lock_s && sl.lock_b_s >= cfg_.min_lock_s)
      cand[static_cast<std::size_t>(nc++)] = s;
  }
  // Highest first: the references and the partial sets keep the best satellites.
  std::sort(cand.begin(), cand.begin() + nc, [this](int a, int b) {
    return slots_[static_cast<std::size_t>(a)].el_rad > slots_[static_cast<std::size_t>(b)].el_rad;
  });
  for (int drop = 0; drop < 3; ++drop) {
    const int use = nc - drop;
    // Double differences per system and band against the group's highest satellite.
    std::array<int, kNumSystems * kNumBands> ref{};
    ref.fill(-1);
    int m = 0;
    for (int c = 0; c < use && m < kMaxAmbiguities; ++c) {
      const int s = cand[static_cast<std::size_t>(c)];
      const Slot& sl = slots_[static_cast<std::size_t>(s)];
      int& r = ref[static_cast<std::size_t>(static_cast<int>(sl.system) * kNumBands + sl.band)];
      if (r < 0) {
        r = s;
        continue;
      }
      dd_slot_[static_cast<std::size_t>(m)] = s;
      dd_ref_[static_cast<std::size_t>(m++)] = r;
    }
    if (m < cfg_.min_fix_ambiguities) return false;
    for (int i = 0; i < m; ++i) {
      const int a = kAmbState0 + dd_slot_[static_cast<std::size_t>(i)];
      const int ra = kAmbState0 + dd_ref_[static_cast<std::size_t>(i)];
      a_dd_[static_cast<std::size_t>(i)] = x_[a] - x_[ra];
      for (int j = 0; j <= i; ++j) {
        const int b = kAmbState0 + dd_slot_[static_cast<std::size_t>(j)];
        const int rb = kAmbState0 + dd_ref_[static_cast<std::size_t>(j)];
        q_dd_[i][j] = q_dd_[j][i] = pv(a, b) - pv(a, rb) - pv(ra, b) + pv(ra, rb);
      }
    }
    const LambdaResult& res = lambda_.solve(a_dd_, q_dd_, m);
    if (!res.ok) return false;
    status_.ratio = res.ratio();
    if (status_.ratio < cfg_.ratio_threshold) continue;
    for (int s = 0; s < n_slots_; ++s) slots_[static_cast<std::size_t>(s)].held = false;
    for (int i = 0; i < m; ++i) {
      Slot& sl = slots_[static_cast<std::size_t>(dd_slot_[static_cast<std::size_t>(i)])];
      Slot& rs = slots_[static_cast<std::size_t>(dd_ref_[static_cast<std::size_t>(i)])];
      sl.held = rs.held = true;
      sl.held_dd = res.best[static_cast<std::size_t>(i)];
      rs.held_dd = 0.0;
      sl.held_ref_key = rs.held_ref_key = rs.key;
      sl.held_ref_arc = rs.held_ref_arc = rs.arc;
    }
    return true;
  }
  return false;
}

bool RtkEngine::fixed_solution(Ecef& pos, Mat3& cov) noexcept {
  // Normal equations with one bias per system and band eliminated (the
  // reference's float ambiguity and the clock difference).
  constexpr int kGroups = kNumSystems * kNumBands;
  std::array<double, kGroups> sw{};
  std::array<Vec3, kGroups> swh{};
  std::array<double, kGroups> swv{};
  Mat3 n{};
  Vec3 rhs{};
  double svv = 0.0;
  int m = 0;
  const Vec3 dx = Ecef(x_[0], x_[1], x_[2]) - x_lin_;
  for (int s = 0; s < n_slots_; ++s) {
    const Slot& sl = slots_[static_cast<std::size_t>(s)];
    if (!sl.held || !sl.in_use) continue;
    const int rs = slot_of_[static_cast<std::size_t>(sl.held_ref_key)];
    if (rs < 0 || slots_[static_cast<std::size_t>(rs)].arc != sl.held_ref_arc || !slots_[static_cast<std::size_t>(rs)].in_use)
      continue;
    const double n_cyc = x_[kAmbState0 + rs] + sl.held_dd;
    // Residual at the float position, so that the solution is a small correction to it.
    const double v = sl.y_m - sl.wavelength_m * n_cyc + sl.e.dot(dx);
    const double w = 1.0 / sl.var_m2;
    const Vec3 h = -sl.e;
    const std::size_t g = static_cast<std::size_t>(static_cast<int>(sl.system) * kNumBands + sl.band);
    sw[g] += w;
    swh[g] += h * w;
    swv[g] += w * v;
    const double hv[3] = {h.x, h.y, h.z};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) n[a][b] += w * hv[a] * hv[b];
    rhs += h * (w * v);
    svv += w * v * v;
    ++m;
  }
  int groups = 0;
  for (int g = 0; g < kGroups; ++g) {
    if (sw[static_cast<std::size_t>(g)] <= 0.0) continue;
    ++groups;
    const double inv = 1.0 / sw[static_cast<std::size_t>(g)];
    const Vec3 a = swh[static_cast<std::size_t>(g)];
    const double av[3] = {a.x, a.y, a.z};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) n[i][j] -= av[i] * av[j] * inv;
    rhs -= a * (swv[static_cast<std::size_t>(g)] * inv);
    svv -= swv[static_cast<std::size_t>(g)] * swv[static_cast<std::size_t>(g)] * inv;
  }
  status_.num_fixed_dd = m - groups;
  if (m - groups < cfg_.min_fix_ambiguities) return false;
  Mat3 ninv{};
  if (!inverse3(n, ninv)) return false;
  const Vec3 d{ninv[0][0] * rhs.x + ninv[0][1] * rhs.y + ninv[0][2] * rhs.z,
               ninv[1][0] * rhs.x + ninv[1][1] * rhs.y + ninv[1][2] * rhs.z,
               ninv[2][0] * rhs.x + ninv[2][1] * rhs.y + ninv[2][2] * rhs.z};
  // Weighted residual sum after the fit, and the largest normalised residual.
  const double chi2 = svv - d.dot(rhs);
  const int dof = m - groups - 3;
  double worst = 0.0;
  std::array<double, kGroups> bias{};
  for (int g = 0; g < kGroups; ++g)
    if (sw[static_cast<std::size_t>(g)] > 0.0)
      bias[static_cast<std::size_t>(g)] = (swv[static_cast<std::size_t>(g)] - swh[static_cast<std::size_t>(g)].dot(d)) / sw[static_cast<std::size_t>(g)];
  for (int s = 0; s < n_slots_; ++s) {
    const Slot& sl = slots_[static_cast<std::size_t>(s)];
    if (!sl.held || !sl.in_use) continue;
    const int rs = slot_of_[static_cast<std::size_t>(sl.held_ref_key)];
    if (rs < 0 || slots_[static_cast<std::size_t>(rs)].arc != sl.held_ref_arc || !slots_[static_cast<std::size_t>(rs)].in_use)
      continue;
    const double v = sl.y_m - sl.wavelength_m * (x_[kAmbState0 + rs] + sl.held_dd) + sl.e.dot(dx);
    const std::size_t g = static_cast<std::size_t>(static_cast<int>(sl.system) * kNumBands + sl.band);
    const double r = v - (-sl.e).dot(d) - bias[g];
    worst = std::max(worst, std::fabs(r) / std::sqrt(sl.var_m2));
  }
  if (worst > kMaxNormResidual || (dof > 0 && chi2 / dof > kMaxChi2PerDof)) return false;
  pos = Ecef(Vec3(x_[0], x_[1], x_[2]) + d);
  cov = ninv;
  return true;
}

void RtkEngine::write_output(const Corrections& c, double age_s, bool carrier, bool fixed,
                             const Ecef& pos, const Mat3& cov_ecef, Fix& fix) const noexcept {
  const CarrierSolution cs = fixed ? CarrierSolution::kFixed : carrier ? CarrierSolution::kFloat : CarrierSolution::kNone;
  const Lla base_lla = geo::lla_from_ecef(c.station.arp_ecef_m);
  RelativePosition& rp = fix.rel_pos;
  rp.valid = true;
  rp.t = fix.t;
  rp.moving_base = c.station.moving;
  rp.carr_soln = cs;
  rp.ref_station_id = c.station.station_id;
  const Enu b = geo::ecef_to_enu_vector(pos - c.station.arp_ecef_m, base_lla.lat_rad, base_lla.lon_rad);
  rp.n_m = b.y;
  rp.e_m = b.x;
  rp.d_m = -b.z;
  rp.length_m = b.norm();
  const Mat3 ce = to_enu(cov_ecef, base_lla);
  rp.acc_e_m = std::sqrt(std::max(ce[0][0], 0.0));
  rp.acc_n_m = std::sqrt(std::max(ce[1][1], 0.0));
  rp.acc_d_m = std::sqrt(std::max(ce[2][2], 0.0));
  if (rp.length_m > 0.0) {
    const double u[3] = {b.x / rp.length_m, b.y / rp.length_m, b.z / rp.length_m};
    double var = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) var += u[i] * ce[i][j] * u[j];
    rp.acc_length_m = std::sqrt(std::max(var, 0.0));
  }
  const double h2 = b.x * b.x + b.y * b.y;
  if (h2 > 0.0) {
    double hd = std::atan2(b.x, b.y);
    if (hd < 0.0) hd += 2.0 * kPi;
    rp.heading_rad = hd;
    // d(heading) = (n de - e dn) / h^2.
    const double gx = b.y / h2, gy = -b.x / h2;
    const double var = gx * gx * ce[0][0] + 2.0 * gx * gy * ce[0][1] + gy * gy * ce[1][1];
    rp.acc_heading_rad = std::sqrt(std::max(var, 0.0));
    // RELPOSNED relPosHeadingValid: a moving base with a carrier solution.
    rp.heading_valid = c.station.moving && cs != CarrierSolution::kNone;
  }
  fix.ref_station_id = c.station.station_id;
  fix.corr_age_s = age_s;
  if (c.station.moving) return;  // the rover's own position stays standalone
  fix.diff_soln = true;
  fix.carr_soln = cs;
  fix.pos_m = pos;
  fix.lla = geo::lla_from_ecef(pos);
  const Mat3 cl = to_enu(cov_ecef, fix.lla);
  fix.sigma_e_m = std::sqrt(std::max(cl[0][0], 0.0));
  fix.sigma_n_m = std::sqrt(std::max(cl[1][1], 0.0));
  fix.sigma_u_m = std::sqrt(std::max(cl[2][2], 0.0));
  fix.cov_en_m2 = cl[0][1];
  fix.h_acc_m = std::hypot(fix.sigma_e_m, fix.sigma_n_m);
  fix.v_acc_m = fix.sigma_u_m;
}

}  // namespace gnssemu::receiver::rtk

// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/tracking/spoof_monitor.hpp"

#include <algorithm>
#include <cmath>

#include "core/receiver/solution/small_matrix.hpp"

namespace gnssemu::receiver {

namespace {
// Authentic C/N0 follows the antenna gain with elevation, so satellites
// spread over this much elevation differ by several dB; only then is a
// uniform C/N0 suspicious.
constexpr double kUniformMinElevationSpread_rad = 30.0 * kDegToRad;
// The position correction one group's residuals ask for, ENU m; false when
// it has too few satellites or a singular geometry.
bool group_correction(const Fix& fix, bool gps, Enu& dx) noexcept {
  Mat4 n{};
  Vec4 b{};
  int count = 0;
  for (int i = 0; i < fix.num_sats; ++i) {
    const SatInfo& s = fix.sats[i];
    if (!s.used || (s.sat.system == GnssSystem::kGps) != gps) continue;
    const double ce = std::cos(s.el_rad);
    const std::array<double, 4> h{-std::sin(s.az_rad) * ce, -std::cos(s.az_rad) * ce, -std::sin(s.el_rad), 1.0};
    for (int r = 0; r < 4; ++r) {
      b[r] += h[r] * s.residual_m;
      for (int c = 0; c < 4; ++c) n[r][c] += h[r] * h[c];
    }
    ++count;
  }
  Mat4 inv{};
  if (count < kSystemGroupMinSats || !spd_inverse4(n, inv)) return false;
  const Vec4 x = mul4(inv, b);
  dx = Enu(x[0], x[1], x[2]);
  return true;
}

}  // namespace

std::optional<double> system_disagreement_m(const Fix& fix) noexcept {
  Enu gps, others;
  if (!group_correction(fix, true, gps) || !group_correction(fix, false, others)) return std::nullopt;
  return (gps - others).norm();
}

bool one_group_excluded(const Fix& fix) noexcept {
  std::array<int, 2> tracked{}, excluded{};  // [0] GPS, [1] the others
  for (int i = 0; i < fix.num_sats; ++i) {
    const SatInfo& s = fix.sats[i];
    const std::size_t g = s.sat.system == GnssSystem::kGps ? 0 : 1;
    tracked[g] += s.tracked ? 1 : 0;
    excluded[g] += s.excluded ? 1 : 0;
  }
  for (std::size_t g = 0; g < 2; ++g) {
    if (excluded[g] >= kSystemExclusionMinSats && 2 * excluded[g] >= tracked[g] && excluded[1 - g] == 0 &&
        tracked[1 - g] > 0)
      return true;
  }
  return false;
}

void validate(const SpoofDetectionConfig& c) {
  using R = SpoofDetectionRanges;
  check_ranges("receiver spoof_detection", {{c.cn0_jump_db, R::cn0_jump_db, "cn0_jump_db"},
                                            {static_cast<double>(c.cn0_jump_sats), R::cn0_jump_sats, "cn0_jump_sats"},
                                            {c.clock_jump_m, R::clock_jump_m, "clock_jump_m"},
                                            {c.uniform_std_db, R::uniform_std_db, "uniform_std_db"},
                                            {static_cast<double>(c.uniform_min_sats), R::uniform_min_sats,
                                             "uniform_min_sats"},
                                            {c.system_disagreement_m, R::system_disagreement_m,
                                             "system_disagreement_m"},
                                            {c.hold_s, R::hold_s, "hold_s"}});
}

void SpoofMonitor::reset() noexcept {
  prev_cn0_.fill(0.0);
  have_clock_ = false;
  last_seen_s_.fill(-1e30);
  held_ = 0;
}

std::uint8_t SpoofMonitor::update(const Fix& fix) noexcept {
  if (!c_.enabled) return 0;
  const double now_s = fix.t.total_s();
  std::uint8_t fired = 0;
  // C/N0: simultaneous jumps and the spread across tracked satellites.
  int jumps = 0, n = 0;
  double sum = 0.0, sum2 = 0.0, el_min = kPi, el_max = -kPi;
  std::array<double, kNumSats> cn0{};
  for (int i = 0; i < fix.num_sats; ++i) {
    const SatInfo& s = fix.sats[i];
    if (!s.tracked) continue;
    cn0[static_cast<std::size_t>(s.sat.index())] = s.cn0_dbhz;
    const double before = prev_cn0_[static_cast<std::size_t>(s.sat.index())];
    if (before > 0.0 && s.cn0_dbhz - before >= c_.cn0_jump_db) ++jumps;
    ++n;
    sum += s.cn0_dbhz;
    sum2 += s.cn0_dbhz * s.cn0_dbhz;
    el_min = std::min(el_min, s.el_rad);
    el_max = std::max(el_max, s.el_rad);
  }
  prev_cn0_ = cn0;
  if (jumps >= c_.cn0_jump_sats) fired |= kSpoofCn0Jump;
  if (n >= c_.uniform_min_sats && el_max - el_min >= kUniformMinElevationSpread_rad) {
    const double mean = sum / n;
    const double var = std::max(sum2 / n - mean * mean, 0.0);
    if (std::sqrt(var) < c_.uniform_std_db) fired |= kSpoofCn0Uniform;
  }
  // Systems: the GPS satellites and the others point to different places.
  if (c_.system_disagreement_m > 0.0 && is_gnss_fix(fix.type)) {
    const std::optional<double> d = system_disagreement_m(fix);
    if ((d && *d > c_.system_disagreement_m) || one_group_excluded(fix)) fired |= kSpoofSystemDisagreement;
  }
  // Clock: the solution's bias against what its drift predicted.
  if (fix.type != FixType::kNone) {
    const double clock_m = fix.clock_bias_s * kSpeedOfLight_m_s;
    const double drift_m_s = fix.clock_drift_s_s * kSpeedOfLight_m_s;
    if (have_clock_) {
      const double dt_s = fix.t - prev_t_;
      if (std::isfinite(dt_s) && dt_s > 0.0 && dt_s < 60.0 &&
          std::fabs(clock_m - (prev_clock_m_ + prev_drift_m_s_ * dt_s)) > c_.clock_jump_m) {
        fired |= kSpoofClockJump;
      }
    }
    have_clock_ = true;
    prev_t_ = fix.t;
    prev_clock_m_ = clock_m;
    prev_drift_m_s_ = drift_m_s;
  }
  held_ = 0;
  for (int k = 0; k < kSpoofCriteria; ++k) {
    if (fired & (1u << k)) last_seen_s_[k] = now_s;
    if (now_s - last_seen_s_[k] <= c_.hold_s) held_ = static_cast<std::uint8_t>(held_ | (1u << k));
  }
  int count = 0;
  for (int k = 0; k < kSpoofCriteria; ++k) count += (held_ >> k) & 1;
  return count == 0 ? 1 : count == 1 ? 2 : 3;
}

}  // namespace gnssemu::receiver

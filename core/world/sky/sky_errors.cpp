// SPDX-License-Identifier: Apache-2.0
#include "core/world/sky/sky_errors.hpp"

#include <algorithm>
#include <cmath>

#include "core/world/world_config.hpp"

namespace gnssemu::world {

namespace {

static_assert(kSkyFineStep_s == 1.0, "fine nodes are GPS seconds");

constexpr int64_t kSecondsPerWeek = 604800;

/// floor(a / b) for b > 0.
int64_t floor_div(int64_t a, int64_t b) noexcept { return a / b - (a % b < 0 ? 1 : 0); }

/// Stream of process p of sat (regional processes: sat invalid, number 0):
/// the process in bits 12 and up, clear of every satellite stream.
uint64_t stream_of(int p, SatId sat) noexcept {
  return (static_cast<uint64_t>(p + 1) << 12) | (sat.valid() ? sat_stream(sat) : 0);
}

/// 1 - exp(-2 dt / tau), accurate for dt << tau.
double one_minus_phi2(double dt_s, double tau_s) noexcept { return -std::expm1(-2.0 * dt_s / tau_s); }

}  // namespace

SkyErrorsConfig sky_errors_config(const WorldConfig& c) noexcept {
  SkyErrorsConfig s;
  s.seed = sky_seed(c);
  const auto tau = [](bool on, double tau_s) { return on ? tau_s : 0.0; };
  const bool iono = c.atmosphere.ionosphere.enabled;
  const bool tropo = c.atmosphere.troposphere.enabled;
  const ErrorModelConfig& e = c.errors;
  s.tau_s[static_cast<std::size_t>(SkyProcess::kOrbitClock)] = tau(e.orbit_clock.sigma_m > 0.0, e.orbit_clock.tau_s);
  const auto& ip = c.atmosphere.ionosphere.perturbation;
  s.tau_s[static_cast<std::size_t>(SkyProcess::kIono)] = tau(iono && ip.sigma > 0.0, ip.tau_s);
  s.tau_s[static_cast<std::size_t>(SkyProcess::kIonoScale)] =
      tau(iono && e.iono_scale.sigma > 0.0, e.iono_scale.tau_s);
  const double grad_tau = tau(e.gradient.process.sigma_m > 0.0, e.gradient.process.tau_s);
  s.tau_s[static_cast<std::size_t>(SkyProcess::kGradientNorth)] = grad_tau;
  s.tau_s[static_cast<std::size_t>(SkyProcess::kGradientEast)] = grad_tau;
  const GaussMarkovConfig& z = c.atmosphere.zwd_perturbation;
  s.tau_s[static_cast<std::size_t>(SkyProcess::kZwd)] = tau(tropo && z.sigma_m > 0.0, z.tau_s);
  return s;
}

SkyErrors::SkyErrors(const SkyErrorsConfig& config) noexcept : config_(config), rng_(config.seed) {
  for (std::size_t p = 0; p < coef_.size(); ++p) {
    const double tau_s = config_.tau_s[p];
    Coefficients& k = coef_[p];
    k.on = tau_s > 0.0 && std::isfinite(tau_s);
    if (!k.on) continue;
    k.tau_s = tau_s;
    k.phi_coarse = std::exp(-kSkyCoarseStep_s / tau_s);
    k.sd_coarse = std::sqrt(one_minus_phi2(kSkyCoarseStep_s, tau_s));
    k.block = std::clamp(static_cast<int64_t>(std::ceil(kSkyBlockTaus * tau_s / kSkyCoarseStep_s)), int64_t{1},
                         kSkyMaxBlock);
    // Node j+1 given node j and the coarse node at kSkyFinePerCoarse: with
    // phi_a over the step, phi_r over the rest and phi_b over both, the
    // conditional mean is a f_j + b c1 and the variance below.
    const double phi_a = std::exp(-kSkyFineStep_s / tau_s);
    const double q_a = one_minus_phi2(kSkyFineStep_s, tau_s);
    for (int j = 0; j < kSkyFinePerCoarse; ++j) {
      const double rest_s = kSkyFineStep_s * (kSkyFinePerCoarse - j - 1);
      const double phi_r = std::exp(-rest_s / tau_s);
      const double q_r = one_minus_phi2(rest_s, tau_s);
      const double q_b = one_minus_phi2(rest_s + kSkyFineStep_s, tau_s);
      const auto i = static_cast<std::size_t>(j);
      k.a[i] = phi_a * q_r / q_b;
      k.b[i] = phi_r * q_a / q_b;
      k.sd[i] = std::sqrt(std::max(q_a * q_r / q_b, 0.0));
    }
    // Slow processes: the bridge's mean alone, scaled back to unit variance
    // by the variance the mean carries, 1 - q(t) q(T - t) / q(T) at node j.
    k.smooth = tau_s >= kSkySmoothTaus * kSkyCoarseStep_s;
    if (k.smooth) {
      const double q_t = one_minus_phi2(kSkyCoarseStep_s, tau_s);
      for (int j = 0; j <= kSkyFinePerCoarse; ++j) {
        const double t_s = kSkyFineStep_s * j;
        const double v = one_minus_phi2(t_s, tau_s) * one_minus_phi2(kSkyCoarseStep_s - t_s, tau_s) / q_t;
        k.scale[static_cast<std::size_t>(j)] = 1.0 / std::sqrt(std::max(1.0 - v, 1e-12));
        if (j < kSkyFinePerCoarse) k.sd[static_cast<std::size_t>(j)] = 0.0;
      }
    }
  }
}

double SkyErrors::coarse_next(double x, const Coefficients& k, uint64_t stream, int64_t n) const noexcept {
  return k.phi_coarse * x + k.sd_coarse * rng_.normal(stream, static_cast<uint64_t>(n + 1), Purpose::kSkyCoarse);
}

void SkyErrors::coarse_to(Grid& g, const Coefficients& k, uint64_t stream) const noexcept {
  const int64_t n = floor_div(node_, kSkyFinePerCoarse);
  if (g.started && g.coarse == n) return;
  const int64_t block = floor_div(n, k.block);
  if (g.started && g.coarse < n && floor_div(g.coarse, k.block) + 1 >= block && n - g.coarse <= k.block) {
    // Node by node (the same steps as a cold start's walks).
    while (g.coarse < n) {
      const int64_t m = ++g.coarse;
      g.c0 = g.c1;
      if (floor_div(m, k.block) * k.block == m) {
        // m starts a block: the walk from the last block's start takes over, a new one starts.
        g.c0 = g.next1;
        g.next1 = rng_.normal(stream, static_cast<uint64_t>(m), Purpose::kSkyInit);
      }
      g.c1 = coarse_next(g.c0, k, stream, m);
      g.next1 = coarse_next(g.next1, k, stream, m);
    }
    g.fine = -1;
    return;
  }
  // Cold start (or a jump): walk from the block before n's, and from n's block's start.
  const int64_t anchor = (block - 1) * k.block;
  double x = rng_.normal(stream, static_cast<uint64_t>(anchor), Purpose::kSkyInit);
  for (int64_t m = anchor; m < n; ++m) x = coarse_next(x, k, stream, m);
  const int64_t start = block * k.block;
  double y = rng_.normal(stream, static_cast<uint64_t>(start), Purpose::kSkyInit);
  for (int64_t m = start; m <= n; ++m) y = coarse_next(y, k, stream, m);
  g.started = true;
  g.coarse = n;
  g.c0 = x;
  g.c1 = coarse_next(x, k, stream, n);
  g.next1 = y;
  g.fine = -1;
}

void SkyErrors::fine_to(Grid& g, const Coefficients& k, uint64_t stream) const noexcept {
  const int j = static_cast<int>(node_ - floor_div(node_, kSkyFinePerCoarse) * kSkyFinePerCoarse);
  const uint64_t base = static_cast<uint64_t>(g.coarse) * kSkyFinePerCoarse;
  const auto next = [&](int i, double f) {
    const auto u = static_cast<std::size_t>(i);
    const double mean = k.a[u] * f + k.b[u] * g.c1;
    return k.sd[u] > 0.0 ? mean + k.sd[u] * rng_.normal(stream, base + static_cast<uint64_t>(i + 1), Purpose::kSkyFine)
                         : mean;
  };
  if (g.fine < 0 || g.fine > j) {
    g.fine = 0;
    g.f0 = g.c0;
    g.f1 = next(0, g.f0);
  }
  while (g.fine < j) {
    g.f0 = g.f1;
    ++g.fine;
    g.f1 = next(g.fine, g.f0);
  }
  if (k.smooth) {
    const double v0 = g.f0 * k.scale[static_cast<std::size_t>(j)], v1 = g.f1 * k.scale[static_cast<std::size_t>(j + 1)];
    g.value = v0 + frac_ * (v1 - v0);
  } else {
    g.value = g.f0 + frac_ * (g.f1 - g.f0);
  }
}

void SkyErrors::begin(const time::GpsTime& t, std::span<const SatId> sats, long sats_revision) noexcept {
  const double tow_s = t.tow_s();
  const double whole_s = std::floor(tow_s);
  const int64_t node = static_cast<int64_t>(t.week()) * kSecondsPerWeek + static_cast<int64_t>(whole_s);
  const double frac = tow_s - whole_s;
  if (started_ && (node < node_ || (node == node_ && frac < frac_))) return;  // time going back: hold
  started_ = true;
  node_ = node;
  frac_ = frac;
  const int64_t coarse = floor_div(node_, kSkyFinePerCoarse);
  if (coarse != chains_at_ || sats_revision != chains_revision_) {
    for (int p = 0; p < kNumSatProcesses; ++p) {
      const Coefficients& k = coef_[static_cast<std::size_t>(p)];
      if (!k.on) continue;
      auto& grids = sat_[static_cast<std::size_t>(p)];
      for (const SatId sat : sats) coarse_to(grids[static_cast<std::size_t>(sat.index())], k, stream_of(p, sat));
    }
    chains_at_ = coarse;
    chains_revision_ = sats_revision;
  }
  for (int p = kNumSatProcesses; p < kNumSkyProcesses; ++p) {
    const Coefficients& k = coef_[static_cast<std::size_t>(p)];
    if (!k.on) continue;
    Grid& g = regional_[static_cast<std::size_t>(p)];
    const uint64_t stream = stream_of(p, SatId{});
    coarse_to(g, k, stream);
    fine_to(g, k, stream);
  }
}

void SkyErrors::step(SatId sat) noexcept {
  for (int p = 0; p < kNumSatProcesses; ++p) {
    const Coefficients& k = coef_[static_cast<std::size_t>(p)];
    if (!k.on) continue;
    Grid& g = sat_[static_cast<std::size_t>(p)][static_cast<std::size_t>(sat.index())];
    if (!g.started) continue;  // not in the sky's list
    fine_to(g, k, stream_of(p, sat));
  }
}

}  // namespace gnssemu::world

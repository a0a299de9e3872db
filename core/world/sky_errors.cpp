// SPDX-License-Identifier: Apache-2.0
#include "core/world/sky_errors.hpp"

#include <algorithm>
#include <cmath>

#include "core/world/world_config.hpp"

namespace gnssemu::world {

namespace {

// A time jump of more coarse steps than this (about 4.5 h) is crossed in one
// exact step instead of node by node.
constexpr int64_t kMaxCoarseCatchUp = 256;

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
  }
}

void SkyErrors::coarse_to(Grid& g, const Coefficients& k, uint64_t stream) const noexcept {
  const int64_t n = node_ / kSkyFinePerCoarse;
  if (g.coarse < 0) {
    g.coarse = n;
    g.c0 = rng_.normal(stream, static_cast<uint64_t>(n), Purpose::kSkyInit);
    g.c1 = k.phi_coarse * g.c0 + k.sd_coarse * rng_.normal(stream, static_cast<uint64_t>(n + 1), Purpose::kSkyCoarse);
    g.fine = -1;
    return;
  }
  if (g.coarse >= n) return;
  if (n - g.coarse > kMaxCoarseCatchUp) {
    // c1 is node coarse + 1; one exact step from it to node n.
    const double gap_s = kSkyCoarseStep_s * static_cast<double>(n - g.coarse - 1);
    g.c1 = std::exp(-gap_s / k.tau_s) * g.c1 +
           std::sqrt(one_minus_phi2(gap_s, k.tau_s)) * rng_.normal(stream, static_cast<uint64_t>(n), Purpose::kSkyJump);
    g.coarse = n - 1;
  }
  while (g.coarse < n) {
    g.c0 = g.c1;
    ++g.coarse;
    g.c1 = k.phi_coarse * g.c0 +
           k.sd_coarse * rng_.normal(stream, static_cast<uint64_t>(g.coarse + 1), Purpose::kSkyCoarse);
  }
  g.fine = -1;
}

void SkyErrors::fine_to(Grid& g, const Coefficients& k, uint64_t stream) const noexcept {
  const int j = static_cast<int>(node_ % kSkyFinePerCoarse);
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
  g.value = g.f0 + frac_ * (g.f1 - g.f0);
}

void SkyErrors::begin(const time::GpsTime& t, std::span<const SatId> sats, long sats_revision) noexcept {
  if (!started_) {
    origin_ = t;
    started_ = true;
  }
  const double s = (t - origin_) / kSkyFineStep_s;
  if (!std::isfinite(s) || s < static_cast<double>(node_) + frac_) return;  // time going back: hold
  node_ = static_cast<int64_t>(std::floor(s));
  frac_ = s - static_cast<double>(node_);
  const int64_t coarse = node_ / kSkyFinePerCoarse;
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
    if (g.coarse < 0) continue;  // not in the sky's list
    fine_to(g, k, stream_of(p, sat));
  }
}

}  // namespace gnssemu::world

// SPDX-License-Identifier: Apache-2.0
#include "core/atmosphere/shells.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"

namespace gnssemu::atmosphere {
namespace {

// Specific gas constant of dry air (J/(kg K)) over standard gravity (m/s^2):
// R T / (g M) = kRdOverG * T is the isothermal scale height, m.
constexpr double kRdOverG_m_k = 287.053 / 9.80665;
constexpr double kMinHeight_m = -1000.0;

// 4-point Gauss–Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun 25.4.30).
constexpr double kGlX[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
constexpr double kGlW[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
constexpr int kPanels = 16;

// A ray in tangent-point coordinates: r(u) = sqrt(p^2 + u^2), receiver at u0,
// travelling towards +u.
struct Ray {
  double p = 0.0;      // impact parameter (closest radius), m
  double r0_minus_p = 0.0;
  double u0 = 0.0;
};

Ray make_ray(double rx_height_m, double el_rad, double earth_radius_m) noexcept {
  const double h = std::max(rx_height_m, kMinHeight_m);
  const double r0 = earth_radius_m + h;
  const double e = std::clamp(el_rad, -0.5 * kPi, 0.5 * kPi);
  const double se = std::sin(0.5 * e);
  Ray ray;
  ray.p = r0 * std::cos(e);
  ray.r0_minus_p = 2.0 * r0 * se * se;
  ray.u0 = r0 * std::sin(e);
  if (e < 0.0 && ray.p < earth_radius_m && h > 0.0) {
    // Would hit the ground: graze the surface instead.
    ray.p = earth_radius_m;
    ray.r0_minus_p = h;
    ray.u0 = -std::sqrt(h * (r0 + earth_radius_m));
  } else if (e < 0.0 && h <= 0.0) {
    ray.p = r0;
    ray.r0_minus_p = 0.0;
    ray.u0 = 0.0;
  }
  return ray;
}

// |u| at which the ray is at radius r0 + dh (dh relative to the receiver), >= 0.
double chord(const Ray& ray, double r0, double dh) noexcept {
  const double r_minus_p = dh + ray.r0_minus_p;
  if (!(r_minus_p > 0.0)) return 0.0;
  return std::sqrt(r_minus_p * (r0 + dh + ray.p));
}

// Up to two u-intervals of the ray inside [bottom, top].
struct Intervals {
  double a[2] = {0.0, 0.0};
  double b[2] = {0.0, 0.0};
  int n = 0;
};

Intervals shell_intervals(const Ray& ray, double r0, double rx_height_m, double bottom_m, double top_m) noexcept {
  Intervals iv;
  if (!(top_m > bottom_m)) return iv;
  const double h0 = std::max(rx_height_m, kMinHeight_m);
  // A shell reaching the surface also holds a receiver below the surface (e.g. -400 m).
  if (bottom_m <= 0.0) bottom_m = std::min(bottom_m, h0);
  const double cb = chord(ray, r0, bottom_m - h0);
  const double ct = chord(ray, r0, top_m - h0);
  // Outward branch [cb, ct] and inward branch [-ct, -cb], clipped to u >= u0.
  const double lo_out = std::max(cb, ray.u0);
  if (ct > lo_out) { iv.a[iv.n] = lo_out; iv.b[iv.n] = ct; ++iv.n; }
  const double lo_in = std::max(-ct, ray.u0);
  if (-cb > lo_in) { iv.a[iv.n] = lo_in; iv.b[iv.n] = -cb; ++iv.n; }
  return iv;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("atmosphere shells config", 0, what);
}

std::string shell_name(std::size_t i) { return std::string(kShellNames[i]); }

}  // namespace

double slant_path_in_shell_m(double rx_height_m, double el_rad, double bottom_m, double top_m,
                             double earth_radius_m) noexcept {
  if (!std::isfinite(rx_height_m) || !std::isfinite(el_rad) || !std::isfinite(bottom_m) || !std::isfinite(top_m) ||
      !(earth_radius_m > 0.0))
    return 0.0;
  const Ray ray = make_ray(rx_height_m, el_rad, earth_radius_m);
  const double r0 = earth_radius_m + std::max(rx_height_m, kMinHeight_m);
  const Intervals iv = shell_intervals(ray, r0, rx_height_m, bottom_m, top_m);
  double len = 0.0;
  for (int k = 0; k < iv.n; ++k) len += iv.b[k] - iv.a[k];
  return len;
}

double oxygen_specific_attenuation_db_km(double f) noexcept {
  const double d = f - 57.0;
  return (7.19e-3 + 6.09 / (f * f + 0.227) + 4.81 / (d * d + 1.50)) * f * f * 1e-3;
}

double water_vapour_specific_attenuation_db_km(double f, double rho) noexcept {
  const double d1 = f - 22.2, d2 = f - 183.3, d3 = f - 325.4;
  return (0.050 + 0.0021 * rho + 3.6 / (d1 * d1 + 8.5) + 10.6 / (d2 * d2 + 9.0) + 8.9 / (d3 * d3 + 26.3)) * f * f *
         rho * 1e-4;
}

std::optional<Violation> check_thickness(const Shell& s) {
  if (!(s.top_m < s.bottom_m)) return std::nullopt;
  return Violation{"top_m", "bottom_m",
                   "negative thickness (top_m " + format_number(s.top_m) + " m < bottom_m " + format_number(s.bottom_m) +
                       " m)"};
}

std::optional<Violation> check_overlap(const ShellsConfig& cfg) {
  const auto neutral = [](std::size_t i) { return static_cast<ShellKind>(i) != ShellKind::kIonosphere; };
  for (std::size_t i = 0; i < kShellCount; ++i) {
    for (std::size_t j = 0; j < kShellCount; ++j) {
      const Shell& a = cfg.shells[i];
      const Shell& b = cfg.shells[j];
      if (i == j || !neutral(i) || !neutral(j) || !a.enabled || !b.enabled) continue;
      if (!(a.bottom_m <= b.bottom_m && b.bottom_m < a.top_m && b.top_m > b.bottom_m)) continue;
      return Violation{kShellNames[j], kShellNames[i],
                       shell_name(i) + " (" + format_number(a.bottom_m) + "-" + format_number(a.top_m) + " m) and " +
                           shell_name(j) + " (" + format_number(b.bottom_m) + "-" + format_number(b.top_m) +
                           " m) overlap"};
    }
  }
  return std::nullopt;
}

void validate(const ShellsConfig& cfg) {
  const std::string what = "atmosphere shells config";
  for (std::size_t i = 0; i < kShellCount; ++i) {
    const Shell& s = cfg.shells[i];
    const std::string n = shell_name(i);
    check_ranges(what, {{s.bottom_m, ShellRanges::bottom_m, n + ".bottom_m"}, {s.top_m, ShellRanges::top_m, n + ".top_m"}});
    require(!check_thickness(s), n + ": negative thickness (bottom " + std::to_string(s.bottom_m) + " m, top " +
                                       std::to_string(s.top_m) + " m)");
    check_range(s.temperature_k, ShellRanges::temperature_k, what, n + ".temperature_k");
  }
  const GasConfig& g = cfg.gas;
  check_ranges(what, {{g.freq_hz, GasRanges::freq_hz, "gas.freq_hz"},
                      {g.water_vapour_density_g_m3, GasRanges::water_vapour_density_g_m3, "gas.water_vapour_density_g_m3"},
                      {g.water_vapour_scale_height_m, GasRanges::water_vapour_scale_height_m,
                       "gas.water_vapour_scale_height_m"}});
  if (const std::optional<Violation> v = check_overlap(cfg)) require(false, v->reason);
}

AtmosphereShells::AtmosphereShells(const ShellsConfig& cfg) : cfg_(cfg) {
  validate(cfg);
  const GasConfig& g = cfg.gas;
  const double f_ghz = g.freq_hz * 1e-9;
  gamma_o_db_m_ = oxygen_specific_attenuation_db_km(f_ghz) * 1e-3;
  gamma_w_db_m_ = water_vapour_specific_attenuation_db_km(f_ghz, g.water_vapour_density_g_m3) * 1e-3;

  // Dry-air chain: every neutral shell, sorted by bottom.
  std::array<std::size_t, kShellCount> idx{};
  for (std::size_t i = 0; i < kShellCount; ++i) {
    if (static_cast<ShellKind>(i) == ShellKind::kIonosphere) continue;
    idx[chain_n_++] = i;
  }
  for (std::size_t a = 1; a < chain_n_; ++a)  // insertion sort by bottom (at most 4 entries)
    for (std::size_t b = a; b > 0 && cfg.shells[idx[b]].bottom_m < cfg.shells[idx[b - 1]].bottom_m; --b)
      std::swap(idx[b], idx[b - 1]);
  for (std::size_t k = 0; k < chain_n_; ++k) {
    const Shell& s = cfg.shells[idx[k]];
    chain_bottom_m_[k] = s.bottom_m;
    chain_scale_m_[k] = kRdOverG_m_k * s.temperature_k;
    chain_ratio_[k] = k == 0 ? std::exp(-s.bottom_m / chain_scale_m_[0])
                             : chain_ratio_[k - 1] *
                                   std::exp(-(s.bottom_m - chain_bottom_m_[k - 1]) / chain_scale_m_[k - 1]);
  }
}

double AtmosphereShells::dry_density_ratio(double height_m) const noexcept {
  if (chain_n_ == 0 || !std::isfinite(height_m)) return 0.0;
  std::size_t k = 0;
  while (k + 1 < chain_n_ && height_m >= chain_bottom_m_[k + 1]) ++k;
  return chain_ratio_[k] * std::exp(-(height_m - chain_bottom_m_[k]) / chain_scale_m_[k]);
}

ShellAttenuation AtmosphereShells::gas_attenuation(double rx_height_m, double el_rad) const noexcept {
  ShellAttenuation out;
  if (!std::isfinite(rx_height_m) || !std::isfinite(el_rad)) return out;
  const double R = kMeanEarthRadius_m;
  const Ray ray = make_ray(rx_height_m, el_rad, R);
  const double h0 = std::max(rx_height_m, kMinHeight_m);
  const double r0 = R + h0;
  const double hw = cfg_.gas.water_vapour_scale_height_m;
  for (std::size_t i = 0; i < kShellCount; ++i) {
    const Shell& s = cfg_.shells[i];
    const Intervals iv = shell_intervals(ray, r0, h0, s.bottom_m, s.top_m);
    double path = 0.0, db = 0.0;
    for (int k = 0; k < iv.n; ++k) {
      path += iv.b[k] - iv.a[k];
      if (!s.enabled || !s.gas_absorption) continue;
      const double panel = (iv.b[k] - iv.a[k]) / kPanels;
      for (int j = 0; j < kPanels; ++j) {
        const double mid = iv.a[k] + (j + 0.5) * panel;
        for (int q = 0; q < 4; ++q) {
          const double u = mid + 0.5 * panel * kGlX[q];
          const double h = std::sqrt(ray.p * ray.p + u * u) - R;
          const double g = gamma_o_db_m_ * dry_density_ratio(h) + gamma_w_db_m_ * std::exp(-h / hw);
          db += 0.5 * panel * kGlW[q] * g;
        }
      }
    }
    out.path_m[i] = path;
    out.gas_db[i] = db;
    out.total_db += db;
  }
  return out;
}

}  // namespace gnssemu::atmosphere

// SPDX-License-Identifier: Apache-2.0
#include "core/atmosphere/ionosphere.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/atmosphere/klobuchar.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"

namespace gnssemu::atmosphere {
namespace {

// 40.3 m^3/s^2 per electron/m^2 (first-order group delay constant) times 1e16.
constexpr double kIonoConstant = 40.3e16;

double clamp_el(double el_rad) noexcept {
  if (!(el_rad > 0.0)) return 0.0;
  return std::min(el_rad, 0.5 * kPi);
}

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("ionosphere config", 0, what);
}

}  // namespace

double iono_m_per_tecu(double freq_hz) noexcept {
  if (!(freq_hz > 0.0)) return 0.0;
  return kIonoConstant / (freq_hz * freq_hz);
}

double iono_obliquity_factor(double el_rad, double pivot_deg) noexcept {
  const double d = pivot_deg - clamp_el(el_rad) * kRadToDeg;
  return 1.0 + 16.0 * d * d * d / (180.0 * 180.0 * 180.0);
}

double iono_thin_shell_mapping(double el_rad, double shell_height_m, double earth_radius_m) noexcept {
  const double s = earth_radius_m / (earth_radius_m + std::max(shell_height_m, 1.0)) * std::cos(clamp_el(el_rad));
  return 1.0 / std::sqrt(std::max(1.0 - s * s, 1e-12));
}

void validate(const IonosphereConfig& cfg) {
  using R = IonosphereRanges;
  check_ranges("ionosphere config",
               {{cfg.vtec_tecu, R::vtec_tecu, "vtec_tecu"}, {cfg.klobuchar_scale, R::klobuchar_scale, "klobuchar_scale"},
                {cfg.obliquity_pivot_deg, R::obliquity_pivot_deg, "obliquity_pivot_deg"},
                {cfg.shell_height_m, R::shell_height_m, "shell_height_m"}, {cfg.freq_hz, R::freq_hz, "freq_hz"},
                {cfg.perturbation.sigma, R::perturbation_sigma_tecu, "perturbation.sigma_tecu"},
                {cfg.perturbation.tau_s, R::perturbation_tau_s, "perturbation.tau_s"}});
  for (double v : cfg.shape.alpha) require(std::isfinite(v), "Klobuchar alpha must be finite");
  for (double v : cfg.shape.beta) require(std::isfinite(v), "Klobuchar beta must be finite");
}

Ionosphere::Ionosphere(const IonosphereConfig& cfg) : cfg_(cfg) {
  validate(cfg);
  if (!cfg_.shape.valid) cfg_.shape = rtklib_default_klobuchar();
  m_per_tecu_ = iono_m_per_tecu(cfg.freq_hz);
}

double Ionosphere::vtec_tecu(double lat_rad, double lon_rad, double az_rad, double el_rad,
                             double tow_s) const noexcept {
  if (cfg_.source == VtecSource::kFixed) return cfg_.vtec_tecu;
  const double vertical_m = klobuchar_vertical_delay_l1_m(cfg_.shape, lat_rad, lon_rad, az_rad, el_rad, tow_s);
  return cfg_.klobuchar_scale * vertical_m / iono_m_per_tecu(kL1Freq_hz);
}

double Ionosphere::mapping(double el_rad) const noexcept {
  return cfg_.mapping == IonoMapping::kThinShell ? iono_thin_shell_mapping(el_rad, cfg_.shell_height_m)
                                                 : iono_obliquity_factor(el_rad, cfg_.obliquity_pivot_deg);
}

double Ionosphere::slant_delay_m(double lat_rad, double lon_rad, double az_rad, double el_rad, double tow_s,
                                 double perturbation_tecu) const noexcept {
  if (!cfg_.enabled) return 0.0;
  double vtec = vtec_tecu(lat_rad, lon_rad, az_rad, el_rad, tow_s);
  if (std::isfinite(perturbation_tecu)) vtec += perturbation_tecu;
  if (!(vtec > 0.0)) return 0.0;
  return vtec * mapping(el_rad) * m_per_tecu_;
}

GaussMarkov::GaussMarkov(const GaussMarkovParams& p) : p_(p) {
  require(std::isfinite(p.sigma) && p.sigma >= 0.0,
          "Gauss-Markov sigma must be >= 0, got " + std::to_string(p.sigma));
  require(std::isfinite(p.tau_s) && p.tau_s > 0.0,
          "Gauss-Markov tau_s must be > 0 s, got " + std::to_string(p.tau_s));
}

void GaussMarkov::reset(double w0) noexcept { x_ = std::isfinite(w0) ? p_.sigma * w0 : 0.0; }

void GaussMarkov::step(double dt_s, double w) noexcept {
  if (!(dt_s > 0.0) || !std::isfinite(w)) return;
  const double phi = std::exp(-dt_s / p_.tau_s);
  x_ = phi * x_ + p_.sigma * std::sqrt(1.0 - phi * phi) * w;
}

}  // namespace gnssemu::atmosphere

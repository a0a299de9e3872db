// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/solution/weight_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace gnssemu::receiver {

namespace {

// IS-GPS-200 20.3.3.3.1.1: upper bound of URA index N = 0..14, m.
constexpr std::array<double, 15> kUraBound_m{2.4,   3.4,   4.85,  6.85,   9.65,   13.65,  24.0,  48.0,
                                             96.0,  192.0, 384.0, 768.0,  1536.0, 3072.0, 6144.0};
constexpr double kMaxCn0_dbhz = 70.0;

}  // namespace

double ura_bound_m(double ura_m) noexcept {
  if (!std::isfinite(ura_m)) return kUraBound_m.back();
  for (double b : kUraBound_m)
    if (ura_m <= b) return b;
  return kUraBound_m.back();
}

double satellite_variance_m2(const SolverConfig& cfg, double cn0_dbhz, double ura_m) noexcept {
  if (cfg.weights == WeightModel::kRtklib) {
    const double ura = ura_bound_m(ura_m);
    return ura * ura + cfg.code_bias_sigma_m * cfg.code_bias_sigma_m;
  }
  const double c2 = cfg.sigma_c_m_sqrt_hz * cfg.sigma_c_m_sqrt_hz;
  if (!(c2 > 0.0 && cn0_dbhz > 0.0)) return 0.0;  // NaN C/N0: no term
  return c2 * std::pow(10.0, -std::min(cn0_dbhz, kMaxCn0_dbhz) / 10.0);
}

double rtklib_ephemeris_sigma_m(GnssSystem sys, double ura_m) noexcept {
  if (sys == GnssSystem::kGlonass) return 5.0;
  if (sys != GnssSystem::kGalileo) return ura_bound_m(ura_m);
  // SISA index as the RINEX value is truncated to it, then its value.
  if (!(ura_m >= 0.0 && ura_m <= 6.0)) return 500.0;
  if (ura_m <= 0.5) return static_cast<int>(ura_m / 0.01) * 0.01;
  if (ura_m <= 1.0) return 0.5 + static_cast<int>((ura_m - 0.5) / 0.02) * 0.02;
  if (ura_m <= 2.0) return 1.0 + static_cast<int>((ura_m - 1.0) / 0.04) * 0.04;
  const int i = static_cast<int>((ura_m - 2.0) / 0.16);
  return i <= 25 ? 2.0 + i * 0.16 : 500.0;
}

double satellite_variance_m2(const SolverConfig& cfg, double cn0_dbhz, double ura_m, GnssSystem sys) noexcept {
  if (cfg.weights != WeightModel::kRtklib || sys == GnssSystem::kGps) return satellite_variance_m2(cfg, cn0_dbhz, ura_m);
  const double e = rtklib_ephemeris_sigma_m(sys, ura_m);
  return e * e + cfg.code_bias_sigma_m * cfg.code_bias_sigma_m;
}

double measurement_variance_m2(const SolverConfig& cfg, double sin_el, double cn0_dbhz, double ura_m) noexcept {
  return elevation_variance_m2(cfg, sin_el) + satellite_variance_m2(cfg, cn0_dbhz, ura_m);
}

double correction_variance_m2(const SolverConfig& cfg, double iono_m, double sin_el) noexcept {
  double v = 0.0;
  if (cfg.iono != atmosphere::IonoCorrection::kNone) {
    const double i = cfg.iono_model_fraction * iono_m;
    v += i * i;
  }
  if (cfg.tropo != atmosphere::TropoCorrection::kNone) {
    const double t = cfg.tropo_model_sigma_m / (std::max(sin_el, 0.0) + 0.1);
    v += t * t;
  }
  return v;
}

}  // namespace gnssemu::receiver

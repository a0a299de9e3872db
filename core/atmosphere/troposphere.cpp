// SPDX-License-Identifier: Apache-2.0
#include "core/atmosphere/troposphere.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/common/constants.hpp"

namespace gnssemu::atmosphere {
namespace {

constexpr double kMinHeight_m = -1000.0;
constexpr double kMaxHeight_m = 100000.0;
constexpr double kTropopause_m = 11000.0;    // US Standard Atmosphere 1976
constexpr double kT0_k = 288.15;
constexpr double kLapse_k_m = 6.5e-3;
constexpr double kTropopauseT_k = kT0_k - kLapse_k_m * kTropopause_m;  // 216.65 K
// Specific gas constant of dry air (J/(kg K)) over standard gravity (m/s^2), m/K.
constexpr double kRdOverG_m_k = 287.053 / 9.80665;
constexpr double kMinMappingEl_rad = 1.0 * kDegToRad;

double clamp_height(double h) noexcept {
  if (!std::isfinite(h)) return 0.0;
  return std::clamp(h, kMinHeight_m, kMaxHeight_m);
}

double pressure_below_tropopause_hpa(double h) noexcept {
  return 1013.25 * std::pow(1.0 - 2.2557e-5 * h, 5.2568);
}

// Niell (1996) Table 3, rows at |lat| = 15, 30, 45, 60, 75 deg.
constexpr std::array<std::array<double, 5>, 3> kHydroAvg{{
    {1.2769934e-3, 1.2683230e-3, 1.2465397e-3, 1.2196049e-3, 1.2045996e-3},
    {2.9153695e-3, 2.9152299e-3, 2.9288445e-3, 2.9022565e-3, 2.9024912e-3},
    {62.610505e-3, 62.837393e-3, 63.721774e-3, 63.824265e-3, 64.258455e-3},
}};
constexpr std::array<std::array<double, 5>, 3> kHydroAmp{{
    {0.0, 1.2709626e-5, 2.6523662e-5, 3.4000452e-5, 4.1202191e-5},
    {0.0, 2.1414979e-5, 3.0160779e-5, 7.2562722e-5, 11.723375e-5},
    {0.0, 9.0128400e-5, 4.3497037e-5, 84.795348e-5, 170.37206e-5},
}};
constexpr std::array<std::array<double, 5>, 3> kWet{{
    {5.8021897e-4, 5.6794847e-4, 5.8118019e-4, 5.9727542e-4, 6.1641693e-4},
    {1.4275268e-3, 1.5138625e-3, 1.4572752e-3, 1.5007428e-3, 1.7599082e-3},
    {4.3472961e-2, 4.6729510e-2, 4.3908931e-2, 4.4626982e-2, 5.4736038e-2},
}};
constexpr double kAht = 2.53e-5, kBht = 5.49e-3, kCht = 1.14e-3;

// Linear interpolation of a 15-deg-spaced row in |lat| (deg), held outside.
double interp_row(const std::array<double, 5>& row, double abs_lat_deg) noexcept {
  const double t = std::clamp((abs_lat_deg - 15.0) / 15.0, 0.0, 4.0);
  const int i = std::min(static_cast<int>(t), 3);
  const double f = t - i;
  return row[i] + (row[i + 1] - row[i]) * f;
}

double marini(double sin_el, double a, double b, double c) noexcept {
  return (1.0 + a / (1.0 + b / (1.0 + c))) / (sin_el + a / (sin_el + b / (sin_el + c)));
}

}  // namespace

Meteo standard_atmosphere(double height_m, double rel_humidity) noexcept {
  const double h = clamp_height(height_m);
  Meteo m;
  if (h <= kTropopause_m) {
    m.pressure_hpa = pressure_below_tropopause_hpa(h);
    m.temperature_k = kT0_k - kLapse_k_m * h;
  } else {
    m.pressure_hpa = pressure_below_tropopause_hpa(kTropopause_m) *
                     std::exp(-(h - kTropopause_m) / (kRdOverG_m_k * kTropopauseT_k));
    m.temperature_k = kTropopauseT_k;
  }
  const double rh = std::isfinite(rel_humidity) ? std::clamp(rel_humidity, 0.0, 1.0) : 0.0;
  const double t = m.temperature_k;
  m.water_vapour_hpa = 6.108 * rh * std::exp((17.15 * t - 4684.0) / (t - 38.45));
  return m;
}

double saastamoinen_zhd_m(double pressure_hpa, double lat_rad, double height_m) noexcept {
  const double p = std::isfinite(pressure_hpa) ? std::max(pressure_hpa, 0.0) : 0.0;
  const double lat = std::isfinite(lat_rad) ? lat_rad : 0.0;
  return 0.0022768 * p / (1.0 - 0.00266 * std::cos(2.0 * lat) - 0.00028 * clamp_height(height_m) * 1e-3);
}

double saastamoinen_zwd_m(double temperature_k, double water_vapour_hpa) noexcept {
  if (!(temperature_k > 0.0) || !(water_vapour_hpa > 0.0)) return 0.0;
  return 0.002277 * (1255.0 / temperature_k + 0.05) * water_vapour_hpa;
}

double exponential_zhd_m(double height_m, double a_m, double b_per_m) noexcept {
  return a_m * std::exp(-b_per_m * clamp_height(height_m));
}

NiellAt::NiellAt(double lat_rad, double height_m, double doy) noexcept {
  const double lat = std::isfinite(lat_rad) ? std::clamp(lat_rad, -0.5 * kPi, 0.5 * kPi) : 0.0;
  const double abs_lat_deg = std::fabs(lat) * kRadToDeg;
  const double day = std::isfinite(doy) ? doy : 28.0;

  double y = (day - 28.0) / 365.25;
  if (lat < 0.0) y += 0.5;  // southern hemisphere: half a year
  const double cosy = std::cos(2.0 * kPi * y);

  for (int k = 0; k < 3; ++k) {
    ah_[k] = interp_row(kHydroAvg[k], abs_lat_deg) - interp_row(kHydroAmp[k], abs_lat_deg) * cosy;
    aw_[k] = interp_row(kWet[k], abs_lat_deg);
  }
  h_km_ = clamp_height(height_m) * 1e-3;
}

NiellMapping NiellAt::operator()(double el_rad) const noexcept {
  const double el = std::isfinite(el_rad) ? std::clamp(el_rad, kMinMappingEl_rad, 0.5 * kPi) : 0.5 * kPi;
  const double sin_el = std::sin(el);
  NiellMapping m;
  m.hydro = marini(sin_el, ah_[0], ah_[1], ah_[2]) + (1.0 / sin_el - marini(sin_el, kAht, kBht, kCht)) * h_km_;
  m.wet = marini(sin_el, aw_[0], aw_[1], aw_[2]);
  return m;
}

NiellMapping niell_mapping(double el_rad, double lat_rad, double height_m, double doy) noexcept {
  return NiellAt(lat_rad, height_m, doy)(el_rad);
}

void validate(const TroposphereConfig& cfg) {
  using R = TroposphereRanges;
  check_ranges("troposphere config",
               {{cfg.zhd_a_m, R::zhd_a_m, "zhd_a_m"}, {cfg.zhd_b_per_m, R::zhd_b_per_m, "zhd_b_per_m"},
                {cfg.zwd_m, R::zwd_m, "zwd_m"}, {cfg.zwd_scale_height_m, R::zwd_scale_height_m, "zwd_scale_height_m"},
                {cfg.rel_humidity, R::rel_humidity, "rel_humidity"}});
}

Troposphere::Troposphere(const TroposphereConfig& cfg) : cfg_(cfg) { validate(cfg); }

double Troposphere::zhd_m(double lat_rad, double height_m) const noexcept {
  if (cfg_.zhd_model == ZhdModel::kExponential) return exponential_zhd_m(height_m, cfg_.zhd_a_m, cfg_.zhd_b_per_m);
  return saastamoinen_zhd_m(standard_atmosphere(height_m).pressure_hpa, lat_rad, height_m);
}

double Troposphere::zwd_m(double height_m) const noexcept {
  if (cfg_.zwd_model == ZwdModel::kFixed)
    return cfg_.zwd_m * std::exp(-std::max(clamp_height(height_m), 0.0) / cfg_.zwd_scale_height_m);
  const Meteo m = standard_atmosphere(height_m, cfg_.rel_humidity);
  return saastamoinen_zwd_m(m.temperature_k, m.water_vapour_hpa);
}

double Troposphere::slant_delay_m(double lat_rad, double height_m, double el_rad, double doy) const noexcept {
  if (!cfg_.enabled) return 0.0;
  const NiellMapping m = niell_mapping(el_rad, lat_rad, height_m, doy);
  return zhd_m(lat_rad, height_m) * m.hydro + zwd_m(height_m) * m.wet;
}

StandardTroposphereAt::StandardTroposphereAt(double lat_rad, double height_m, double doy) noexcept
    : niell_(lat_rad, height_m, doy) {
  const Meteo met = standard_atmosphere(height_m, 0.7);
  zhd_m_ = saastamoinen_zhd_m(met.pressure_hpa, lat_rad, height_m);
  zwd_m_ = saastamoinen_zwd_m(met.temperature_k, met.water_vapour_hpa);
}

double StandardTroposphereAt::correction_m(double el_rad) const noexcept {
  const NiellMapping m = niell_(el_rad);
  return zhd_m_ * m.hydro + zwd_m_ * m.wet;
}

double standard_troposphere_correction_m(double lat_rad, double height_m, double el_rad, double doy) noexcept {
  return StandardTroposphereAt(lat_rad, height_m, doy).correction_m(el_rad);
}

double standard_troposphere_cosz_m(double lat_rad, double height_m, double el_rad) noexcept {
  const Meteo met = standard_atmosphere(height_m, 0.7);
  const double zenith_m =
      saastamoinen_zhd_m(met.pressure_hpa, lat_rad, height_m) + saastamoinen_zwd_m(met.temperature_k, met.water_vapour_hpa);
  const double el = std::isfinite(el_rad) ? std::clamp(el_rad, kMinMappingEl_rad, 0.5 * kPi) : 0.5 * kPi;
  return zenith_m / std::sin(el);
}

}  // namespace gnssemu::atmosphere

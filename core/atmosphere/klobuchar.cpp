// SPDX-License-Identifier: Apache-2.0
#include "core/atmosphere/klobuchar.hpp"

#include <algorithm>
#include <cmath>

#include "core/common/constants.hpp"

namespace gnssemu::atmosphere {
namespace {

// Night-time constant delay, s (IS-GPS-200 Fig. 20-4).
constexpr double kNightDelay_s = 5.0e-9;
// Minimum period, s, and phase of the daily maximum, s of local time.
constexpr double kMinPeriod_s = 72000.0;
constexpr double kPeakLocalTime_s = 50400.0;

double clamp_el(double el_rad) noexcept {
  if (!(el_rad > 0.0)) return 0.0;  // also maps NaN to 0
  return std::min(el_rad, 0.5 * kPi);
}

// Returns the vertical delay in seconds and the slant factor.
struct KlobucharParts {
  double vertical_s = 0.0;
  double slant_factor = 1.0;
};

KlobucharParts evaluate(const orbit::KlobucharParams& p, double lat_rad, double lon_rad, double az_rad,
                        double el_rad, double tow_s) noexcept {
  const double e_sc = clamp_el(el_rad) / kPiGps;
  const double lat_sc = std::clamp(std::isfinite(lat_rad) ? lat_rad : 0.0, -0.5 * kPi, 0.5 * kPi) / kPiGps;
  const double lon_sc = (std::isfinite(lon_rad) ? lon_rad : 0.0) / kPiGps;
  const double az = std::isfinite(az_rad) ? az_rad : 0.0;

  const double psi = 0.0137 / (e_sc + 0.11) - 0.022;  // earth-centred angle, sc
  const double phi_i = std::clamp(lat_sc + psi * std::cos(az), -0.416, 0.416);
  const double lam_i = lon_sc + psi * std::sin(az) / std::cos(phi_i * kPiGps);
  const double phi_m = phi_i + 0.064 * std::cos((lam_i - 1.617) * kPiGps);

  double t = 43200.0 * lam_i + (std::isfinite(tow_s) ? tow_s : 0.0);
  t -= std::floor(t / kSecondsPerDay) * kSecondsPerDay;

  const double f = 1.0 + 16.0 * std::pow(0.53 - e_sc, 3);
  double amp = p.alpha[0] + phi_m * (p.alpha[1] + phi_m * (p.alpha[2] + phi_m * p.alpha[3]));
  double per = p.beta[0] + phi_m * (p.beta[1] + phi_m * (p.beta[2] + phi_m * p.beta[3]));
  if (!(amp > 0.0)) amp = 0.0;
  if (!(per >= kMinPeriod_s)) per = kMinPeriod_s;

  const double x = 2.0 * kPi * (t - kPeakLocalTime_s) / per;
  double vertical_s = kNightDelay_s;
  if (std::fabs(x) < 1.57) {
    const double x2 = x * x;
    vertical_s += amp * (1.0 - x2 / 2.0 + x2 * x2 / 24.0);
  }
  return {vertical_s, f};
}

}  // namespace

orbit::KlobucharParams rtklib_default_klobuchar() noexcept {
  orbit::KlobucharParams p;
  p.alpha = {0.1118e-07, -0.7451e-08, -0.5961e-07, 0.1192e-06};
  p.beta = {0.1167e+06, -0.2294e+06, -0.1311e+06, 0.1049e+07};
  p.valid = true;
  return p;
}

double klobuchar_slant_factor(double el_rad) noexcept {
  const double e_sc = clamp_el(el_rad) / kPiGps;
  return 1.0 + 16.0 * std::pow(0.53 - e_sc, 3);
}

double klobuchar_vertical_delay_l1_m(const orbit::KlobucharParams& p, double lat_rad, double lon_rad,
                                     double az_rad, double el_rad, double tow_s) noexcept {
  return evaluate(p, lat_rad, lon_rad, az_rad, el_rad, tow_s).vertical_s * kSpeedOfLight_m_s;
}

double klobuchar_delay_l1_m(const orbit::KlobucharParams& p, double lat_rad, double lon_rad, double az_rad,
                            double el_rad, double tow_s) noexcept {
  const KlobucharParts k = evaluate(p, lat_rad, lon_rad, az_rad, el_rad, tow_s);
  return k.slant_factor * k.vertical_s * kSpeedOfLight_m_s;
}

double iono_delay_at_freq_m(double delay_l1_m, double freq_hz) noexcept {
  if (!(freq_hz > 0.0)) return 0.0;
  const double r = kL1Freq_hz / freq_hz;
  return delay_l1_m * r * r;
}

}  // namespace gnssemu::atmosphere

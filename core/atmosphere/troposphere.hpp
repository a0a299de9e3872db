// SPDX-License-Identifier: Apache-2.0
#pragma once
// Tropospheric delay: standard atmosphere, Saastamoinen zenith delays, the
// seed's exponential zenith hydrostatic delay, and the Niell (1996) mapping
// functions. Reference: shared/reference/atmosphere.md §2.
#include "core/common/range.hpp"

namespace gnssemu::atmosphere {

/// Surface meteorology of a standard atmosphere at a height.
struct Meteo {
  double pressure_hpa = 0.0;
  double temperature_k = 0.0;
  double water_vapour_hpa = 0.0;  ///< partial pressure of water vapour
};

/// Standard atmosphere at height_m (ellipsoidal, clamped to [-1000, 100000] m):
/// below 11 km P = 1013.25 (1 - 2.2557e-5 h)^5.2568 hPa (RTKLIB tropmodel) and
/// T = 288.15 - 6.5e-3 h K; above 11 km an isothermal layer at 216.65 K with
/// the barometric decay (US Standard Atmosphere 1976). Water vapour pressure
/// e = 6.108 RH exp((17.15 T - 4684) / (T - 38.45)) hPa (RTKLIB), with
/// relative humidity rel_humidity in [0, 1] (clamped).
Meteo standard_atmosphere(double height_m, double rel_humidity = 0.7) noexcept;

/// Saastamoinen zenith hydrostatic delay, m: 0.0022768 P / (1 - 0.00266 cos 2 lat
/// - 0.00028 h_km) (Davis et al. 1985 eq. A11). pressure_hpa, lat_rad, height_m.
double saastamoinen_zhd_m(double pressure_hpa, double lat_rad, double height_m) noexcept;

/// Saastamoinen zenith wet delay, m: 0.002277 (1255 / T + 0.05) e (RTKLIB).
double saastamoinen_zwd_m(double temperature_k, double water_vapour_hpa) noexcept;

/// Seed zenith hydrostatic delay a exp(-b h), m. a_m: sea-level ZHD, m;
/// b_per_m: inverse scale height, 1/m; height_m clamped to [-1000, 100000].
/// Defaults a = 2.31 m, b = 1.2e-4 1/m fit Saastamoinen within 2 cm to 3 km
/// (reference §2.1).
double exponential_zhd_m(double height_m, double a_m = 2.31, double b_per_m = 1.2e-4) noexcept;

/// Niell hydrostatic and wet mapping factors (dimensionless).
struct NiellMapping {
  double hydro = 1.0;
  double wet = 1.0;
};

/// Niell (1996) mapping functions, Table 3 coefficients, Marini continued
/// fraction; linear interpolation in |lat| (held outside 15..75 deg); seasonal
/// term cos(2 pi (doy - 28) / 365.25), shifted half a year south of the
/// equator; hydrostatic height correction with height in km.
/// el_rad clamped to [1 deg, 90 deg] (NMF is validated down to 3 deg);
/// lat_rad clamped to [-pi/2, pi/2]; height_m: ellipsoidal, clamped to
/// [-1000, 100000] m; doy: day of year, fractional allowed (1..366.99).
NiellMapping niell_mapping(double el_rad, double lat_rad, double height_m, double doy) noexcept;

/// niell_mapping() at one place and day for many elevations: the
/// coefficients interpolated once, the same arithmetic (the same bits).
class NiellAt {
public:
  NiellAt(double lat_rad, double height_m, double doy) noexcept;
  NiellMapping operator()(double el_rad) const noexcept;

private:
  double ah_[3], aw_[3];
  double h_km_;
};

enum class ZhdModel {
  kExponential,   ///< exponential_zhd_m(h, zhd_a_m, zhd_b_per_m)
  kSaastamoinen,  ///< saastamoinen_zhd_m(standard_atmosphere(h))
};

enum class ZwdModel {
  kFixed,         ///< zwd_m at zero height, scaled by exp(-h / zwd_scale_height_m)
  kSaastamoinen,  ///< saastamoinen_zwd_m(standard_atmosphere(h, rel_humidity))
};

/// World troposphere configuration (what the signal really suffers).
struct TroposphereConfig {
  bool enabled = true;
  ZhdModel zhd_model = ZhdModel::kExponential;
  double zhd_a_m = 2.31;         ///< kExponential: ZHD at h = 0, m (>= 0)
  double zhd_b_per_m = 1.2e-4;   ///< kExponential: inverse scale height, 1/m (>= 0)
  ZwdModel zwd_model = ZwdModel::kFixed;
  double zwd_m = 0.10;           ///< kFixed: ZWD at h = 0, m (>= 0); mid-latitude typical 0.05-0.3
  double zwd_scale_height_m = 2000.0;  ///< kFixed: water vapour scale height, m (> 0)
  double rel_humidity = 0.7;     ///< kSaastamoinen: [0, 1]
};

/// Valid values of TroposphereConfig's fields.
struct TroposphereRanges {
  static constexpr Range zhd_a_m{0.0, 10.0, "m"};
  static constexpr Range zhd_b_per_m{0.0, 1.0e-2, "1/m", false, true};
  static constexpr Range zwd_m{0.0, 1.0, "m"};
  static constexpr Range zwd_scale_height_m{0.0, 20000.0, "m", true};
  static constexpr Range rel_humidity{0.0, 1.0, ""};
};

/// Throws gnssemu::Error for a value out of its range.
void validate(const TroposphereConfig& cfg);

/// Validated world troposphere. Construction throws gnssemu::Error on bad values.
class Troposphere {
public:
  explicit Troposphere(const TroposphereConfig& cfg);

  const TroposphereConfig& config() const noexcept { return cfg_; }

  /// Zenith hydrostatic and wet delays at height_m, m.
  double zhd_m(double lat_rad, double height_m) const noexcept;
  double zwd_m(double height_m) const noexcept;

  /// Slant delay ZHD m_h + ZWD m_w, m (0 when disabled). Arguments as niell_mapping.
  double slant_delay_m(double lat_rad, double height_m, double el_rad, double doy) const noexcept;

private:
  TroposphereConfig cfg_;
};

/// The receiver's own correction: Saastamoinen ZHD + ZWD with the standard
/// atmosphere (RH 0.7, as RTKLIB) mapped with Niell, m.
double standard_troposphere_correction_m(double lat_rad, double height_m, double el_rad, double doy) noexcept;

/// standard_troposphere_correction_m() at one place and day for many
/// elevations: zenith delays and mapping coefficients computed once.
class StandardTroposphereAt {
public:
  StandardTroposphereAt(double lat_rad, double height_m, double doy) noexcept;
  double correction_m(double el_rad) const noexcept;
  const NiellAt& niell() const noexcept { return niell_; }

private:
  NiellAt niell_;
  double zhd_m_, zwd_m_;
};

/// The same zenith delays mapped with 1/sin(el) (= 1/cos z, RTKLIB tropmodel), m.
/// el_rad held at >= 1 deg.
double standard_troposphere_cosz_m(double lat_rad, double height_m, double el_rad) noexcept;

}  // namespace gnssemu::atmosphere

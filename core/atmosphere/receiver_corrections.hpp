// SPDX-License-Identifier: Apache-2.0
#pragma once
// What a receiver subtracts from its pseudoranges: the broadcast Klobuchar
// ionosphere and a standard-atmosphere troposphere. Plain functions so that
// the emulated receiver (core/receiver), `gnssemu spp` and `calibrate` share
// one implementation. Never throw, never NaN for finite inputs.
#include "core/atmosphere/troposphere.hpp"
#include "core/orbit/nav_data.hpp"

namespace gnssemu::atmosphere {

enum class IonoCorrection {
  kNone,
  kKlobuchar,  ///< broadcast Klobuchar at L1 (IS-GPS-200 §20.3.3.5.2.5)
};

enum class TropoCorrection {
  kNone,
  /// Saastamoinen ZHD + ZWD from the standard atmosphere (RH 0.7, as RTKLIB's
  /// tropmodel) mapped with Niell hydrostatic / wet.
  kSaastamoinenNiell,
  /// Zenith hydrostatic delay a exp(-b h) (a = 2.31 m, b = 1.2e-4 1/m) times
  /// the Niell hydrostatic mapping; no wet part.
  kZhdNiell,
  /// Saastamoinen ZHD + ZWD as kSaastamoinenNiell, both mapped with 1/sin(el)
  /// (= 1/cos z), as RTKLIB's tropmodel does: for comparing with rnx2rtkp.
  kSaastamoinenCosZ,
};

/// Broadcast ionospheric code delay at L1, m (>= 0). params invalid (the
/// nav file had none) -> RTKLIB's default coefficients (rtklib_default_klobuchar).
/// lat_rad, lon_rad: receiver; az_rad, el_rad: look angles; tow_s: GPS time of week, s.
double receiver_iono_delay_m(const orbit::KlobucharParams& params, double lat_rad, double lon_rad, double az_rad,
                             double el_rad, double tow_s) noexcept;

/// The same delay on a carrier of wavelength_m (> 0), m: L1's times
/// (f_L1 / f)^2 = (lambda / lambda_L1)^2 (IS-GPS-200 20.3.3.3.3.2; GLONASS
/// L1OF and BeiDou B1I differ from L1 by 1.7 % and 0.9 %).
double receiver_iono_delay_m(const orbit::KlobucharParams& params, double lat_rad, double lon_rad, double az_rad,
                             double el_rad, double tow_s, double wavelength_m) noexcept;

/// Receiver's tropospheric correction, m (>= 0). lat_rad; height_m:
/// ellipsoidal (clamped to [-1 km, 100 km]); el_rad (held at >= 1 deg);
/// doy: day of year, fractional allowed.
double receiver_tropo_delay_m(double lat_rad, double height_m, double el_rad, double doy,
                              TropoCorrection model = TropoCorrection::kSaastamoinenNiell) noexcept;

/// receiver_tropo_delay_m() at one place and day for many elevations: what
/// does not depend on the elevation computed once (the same bits).
class ReceiverTropo {
public:
  ReceiverTropo(double lat_rad, double height_m, double doy, TropoCorrection model) noexcept;
  double delay_m(double el_rad) const noexcept;

private:
  TropoCorrection model_;
  double lat_rad_, height_m_;
  StandardTroposphereAt standard_;
  double zhd_m_ = 0.0;  ///< kZhdNiell: exponential_zhd_m(height_m)
};

/// Zenith hydrostatic delay of the receiver's standard atmosphere
/// (Saastamoinen with the standard pressure at height_m), m.
double receiver_zhd_m(double lat_rad, double height_m) noexcept;

}  // namespace gnssemu::atmosphere

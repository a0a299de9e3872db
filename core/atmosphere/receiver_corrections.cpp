// SPDX-License-Identifier: Apache-2.0
#include "core/atmosphere/receiver_corrections.hpp"

#include "core/atmosphere/klobuchar.hpp"
#include "core/common/constants.hpp"
#include "core/atmosphere/troposphere.hpp"

namespace gnssemu::atmosphere {

double receiver_iono_delay_m(const orbit::KlobucharParams& params, double lat_rad, double lon_rad, double az_rad,
                             double el_rad, double tow_s) noexcept {
  if (params.valid) return klobuchar_delay_l1_m(params, lat_rad, lon_rad, az_rad, el_rad, tow_s);
  return klobuchar_delay_l1_m(rtklib_default_klobuchar(), lat_rad, lon_rad, az_rad, el_rad, tow_s);
}

double receiver_iono_delay_m(const orbit::KlobucharParams& params, double lat_rad, double lon_rad, double az_rad,
                             double el_rad, double tow_s, double wavelength_m) noexcept {
  const double r = wavelength_m / kL1Wavelength_m;
  return receiver_iono_delay_m(params, lat_rad, lon_rad, az_rad, el_rad, tow_s) * r * r;
}

ReceiverTropo::ReceiverTropo(double lat_rad, double height_m, double doy, TropoCorrection model) noexcept
    : model_(model), lat_rad_(lat_rad), height_m_(height_m), standard_(lat_rad, height_m, doy) {
  if (model == TropoCorrection::kZhdNiell) zhd_m_ = exponential_zhd_m(height_m);
}

double ReceiverTropo::delay_m(double el_rad) const noexcept {
  switch (model_) {
    case TropoCorrection::kNone:
      return 0.0;
    case TropoCorrection::kSaastamoinenNiell:
      return standard_.correction_m(el_rad);
    case TropoCorrection::kZhdNiell:
      return zhd_m_ * standard_.niell()(el_rad).hydro;
    case TropoCorrection::kSaastamoinenCosZ:
      return standard_troposphere_cosz_m(lat_rad_, height_m_, el_rad);
  }
  return 0.0;
}

double receiver_tropo_delay_m(double lat_rad, double height_m, double el_rad, double doy,
                              TropoCorrection model) noexcept {
  return ReceiverTropo(lat_rad, height_m, doy, model).delay_m(el_rad);
}

double receiver_zhd_m(double lat_rad, double height_m) noexcept {
  return saastamoinen_zhd_m(standard_atmosphere(height_m).pressure_hpa, lat_rad, height_m);
}

}  // namespace gnssemu::atmosphere

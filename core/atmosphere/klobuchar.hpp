// SPDX-License-Identifier: Apache-2.0
#pragma once
// Klobuchar broadcast ionosphere model (IS-GPS-200 §20.3.3.5.2.5, Fig. 20-4).
// Angles inside the algorithm are semicircles; the interface is radians.
#include "core/orbit/nav_data.hpp"

namespace gnssemu::atmosphere {

/// RTKLIB's fallback coefficients ("2004/1/1", rtkcmn.c ion_default), used
/// when a nav file carries none. Reference: shared/reference/atmosphere.md §1.1.
orbit::KlobucharParams rtklib_default_klobuchar() noexcept;

/// Klobuchar slant factor F = 1 + 16 (0.53 - E)^3, E = elevation in
/// semicircles. el_rad is clamped to [0, pi/2]. Dimensionless, 1 at zenith.
double klobuchar_slant_factor(double el_rad) noexcept;

/// Vertical (zenith-equivalent) ionospheric delay at L1, m: the Klobuchar
/// delay divided by its slant factor, at the pierce point seen along (az, el).
/// lat_rad, lon_rad: receiver geodetic position (any finite value; latitude
/// is clamped to [-pi/2, pi/2]); az_rad, el_rad: look angles (el clamped to
/// [0, pi/2]); tow_s: GPS time of week, s (any finite value).
double klobuchar_vertical_delay_l1_m(const orbit::KlobucharParams& p, double lat_rad, double lon_rad,
                                     double az_rad, double el_rad, double tow_s) noexcept;

/// Slant ionospheric code delay at L1, m (IS-GPS-200 T_iono times c). Same
/// arguments as klobuchar_vertical_delay_l1_m. Never NaN for finite inputs.
double klobuchar_delay_l1_m(const orbit::KlobucharParams& p, double lat_rad, double lon_rad,
                            double az_rad, double el_rad, double tow_s) noexcept;

/// Scale a delay at L1 to another carrier (first-order ionosphere, 1/f^2), m.
double iono_delay_at_freq_m(double delay_l1_m, double freq_hz) noexcept;

}  // namespace gnssemu::atmosphere

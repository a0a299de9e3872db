// SPDX-License-Identifier: Apache-2.0
#pragma once
// World-side geometry of one satellite seen from the true antenna position:
// light-time iteration, Sagnac rotation, look angles and range rate
// (shared/reference/gps-orbits.md §4).
#include <cmath>

#include "core/common/vec3.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/sky/shared_sky.hpp"

namespace gnssemu::world {

/// Rotation of an ECEF vector about Z by angle_rad (Earth rotation during
/// the signal flight: from the transmit-time frame into the receive-time frame).
inline Ecef rotate_earth(const Vec3& v, double angle_rad) noexcept {
  double c, s;
  if (std::fabs(angle_rad) < 1e-4) {
    // Light-time angles (< 2e-5 rad): the series to a^3 leaves a^4 / 24 <
    // 5e-18 in the cosine and a^5 / 120 < 1e-22 in the sine, below the
    // rounding of either; libm's sin/cos cost far more.
    const double a2 = angle_rad * angle_rad;
    c = 1.0 - 0.5 * a2;
    s = angle_rad * (1.0 - a2 / 6.0);
  } else {
    c = std::cos(angle_rad);
    s = std::sin(angle_rad);
  }
  return Ecef(c * v.x + s * v.y, -s * v.x + c * v.y, v.z);
}

struct SkySat {
  time::GpsTime t_tx;       ///< true transmit time (GPS)
  Ecef pos_m;               ///< satellite at t_tx, in the ECEF frame of the receive time
  Ecef vel_m_s;             ///< its velocity, same frame
  double clk_bias_s = 0.0;  ///< broadcast clock at t_tx, relativity included, TGD excluded
  double clk_drift_s_s = 0.0;
  double range_m = 0.0;     ///< geometric range, m
  double range_rate_m_s = 0.0;  ///< d(range)/dt, m/s (LOS projection)
  double az_rad = 0.0, el_rad = 0.0;
};

/// Satellite as seen at receive time t_rx from a receiver at rx_pos_m (with
/// its geodetic rx_lla) moving at rx_vel_m_s (ECEF m/s). Light time starts at
/// 0.075 s and iterates until it changes by less than 1e-9 s (5 passes at most).
SkySat sky_sat(const orbit::Ephemeris& eph, const time::GpsTime& t_rx, const Ecef& rx_pos_m,
               const Lla& rx_lla, const Ecef& rx_vel_m_s) noexcept;

/// A receiver's place for one epoch: its position and the sines and cosines
/// of its geodetic latitude and longitude (the local axes), computed once.
struct RxPlace {
  Ecef pos_m;
  double sin_lat = 0.0, cos_lat = 1.0, sin_lon = 0.0, cos_lon = 1.0;
  static RxPlace of(const Ecef& pos_m, const Lla& lla) noexcept;
  /// Component of v along the geodetic up.
  double up(const Vec3& v) const noexcept { return cos_lat * cos_lon * v.x + cos_lat * sin_lon * v.y + sin_lat * v.z; }
};

/// sky_sat() from the shared sky's evaluation of eph's satellite (Taylor
/// steps across the light time; eph evaluated in full if the sky lacks it).
/// Returns false, leaving out incomplete, when the satellite is below the
/// horizon (no look angles computed) or, before any light-time work, more
/// than ~1° below it. tau_guess_s: where the light-time iteration starts
/// (lightTimeGuess() from the satellite's previous epoch converges in one
/// pass; 0.075 s takes three).
bool sky_sat(const SharedSky& sky, const orbit::Ephemeris& eph, const time::GpsTime& t_rx, const RxPlace& rx,
             const Ecef& rx_vel_m_s, SkySat& out, double tau_guess_s = 0.075) noexcept;

/// A light-time start for receive time t_rx from the same satellite's
/// SkySat of an earlier epoch (range and range rate carried forward: off by
/// ~1e-11 s after 0.1 s); 0.075 s when prev is older than 2 s or unset.
double light_time_guess(const SkySat& prev, const time::GpsTime& t_rx) noexcept;

}  // namespace gnssemu::world

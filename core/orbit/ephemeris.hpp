// SPDX-License-Identifier: Apache-2.0
#pragma once
// GPS LNAV broadcast ephemeris and its evaluation to ECEF position, velocity
// and clock (IS-GPS-200 §20.3.3.3.3 and Table 20-IV).
#include <cstdint>

#include "core/common/vec3.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::orbit {

/// One broadcast ephemeris set, SI units and radians (as RINEX stores them).
struct Ephemeris {
  int prn = 0;                 ///< 1..32
  time::GpsTime toc;           ///< clock reference time
  time::GpsTime toe;           ///< ephemeris reference time (week from BO-5, continuous)
  double af0_s = 0.0;          ///< clock bias, s
  double af1_s_s = 0.0;        ///< clock drift, s/s
  double af2_s_s2 = 0.0;       ///< clock drift rate, s/s^2
  int iode = 0;                ///< issue of data, ephemeris
  int iodc = 0;                ///< issue of data, clock
  double crs_m = 0.0, crc_m = 0.0;       ///< radius harmonic corrections, m
  double cus_rad = 0.0, cuc_rad = 0.0;   ///< argument-of-latitude corrections, rad
  double cis_rad = 0.0, cic_rad = 0.0;   ///< inclination corrections, rad
  double delta_n_rad_s = 0.0;  ///< mean motion difference, rad/s
  double m0_rad = 0.0;         ///< mean anomaly at toe, rad
  double e = 0.0;              ///< eccentricity, dimensionless
  double sqrt_a_sqrtm = 0.0;   ///< square root of the semi-major axis, m^0.5
  double omega0_rad = 0.0;     ///< longitude of ascending node at weekly epoch, rad
  double i0_rad = 0.0;         ///< inclination at toe, rad
  double omega_rad = 0.0;      ///< argument of perigee, rad
  double omega_dot_rad_s = 0.0;///< rate of right ascension, rad/s
  double idot_rad_s = 0.0;     ///< rate of inclination, rad/s
  double tgd_s = 0.0;          ///< L1/L2 group delay, s (subtract for L1 C/A users)
  double sv_accuracy_m = 0.0;  ///< URA, m
  int health = 0;              ///< SV health word, 0 = healthy
  double fit_interval_h = 0.0; ///< curve-fit interval, h; 0 = unknown (4 h assumed)
  double transmit_tow_s = 0.0; ///< transmission time of message, s from the start of toe's week
                               ///< (negative = previous week); 0 when !transmit_known
  bool transmit_known = false; ///< false when the file gave 0.9999e9 (unknown) or for almanacs
};

/// Satellite state at a GPS time.
struct SatState {
  Ecef pos_m;                  ///< ECEF position at t, in the ECEF frame of time t
  Ecef vel_m_s;                ///< ECEF velocity (includes Earth-rotation terms)
  double clk_bias_s = 0.0;     ///< af0 + af1 dt + af2 dt^2 + relativistic term; excludes TGD
  double clk_drift_s_s = 0.0;  ///< af1 + 2 af2 dt (+ relativistic rate)
  double relativity_s = 0.0;   ///< F e sqrt(A) sin(E), included in clk_bias_s
};

/// Evaluate an ephemeris at GPS system time t (the transmission time).
/// Never throws; crossover of weeks is handled through continuous GpsTime.
SatState sat_state(const Ephemeris& eph, const time::GpsTime& t) noexcept;

/// Satellite clock correction (s, relativistic term included, TGD excluded) at
/// satellite time t_sv, solved for t = t_sv - dt (IS-GPS-200 §20.3.3.3.3.1).
double sat_clock_at_sv_time(const Ephemeris& eph, const time::GpsTime& t_sv) noexcept;

/// Validity half-window of an ephemeris around toe, s: half its fit interval,
/// 2 h when unknown (RTKLIB MAXDTOE).
double validity_half_window_s(const Ephemeris& eph) noexcept;

}  // namespace gnssemu::orbit

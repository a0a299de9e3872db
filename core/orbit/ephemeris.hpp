// SPDX-License-Identifier: Apache-2.0
#pragma once
// Broadcast ephemeris of every system and its evaluation to ECEF position,
// velocity and clock. One struct for all systems, so every caller holds a
// const Ephemeris*: Keplerian elements for GPS, Galileo, BeiDou and QZSS
// (IS-GPS-200 §20.3.3.3.3, Table 20-IV; per-system constants from
// system_info()), a state vector for GLONASS (ICD GLONASS Ed. 5.1 App.
// A.3.1.2) and SBAS (RTCA DO-229). Sources: shared/reference/gps-orbits.md,
// multi-gnss.md §1-5.
#include <cstdint>

#include "core/common/gnss_systems.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::orbit {

/// Galileo RINEX "data sources" bits (RINEX 3.04 Table A8).
inline constexpr int kGalInavE1b = 1 << 0;   ///< I/NAV on E1-B
inline constexpr int kGalFnavE5a = 1 << 1;   ///< F/NAV on E5a-I
inline constexpr int kGalInavE5b = 1 << 2;   ///< I/NAV on E5b-I
inline constexpr int kGalClockE5a = 1 << 8;  ///< clock and BGD for (E1,E5a)
inline constexpr int kGalClockE5b = 1 << 9;  ///< clock and BGD for (E1,E5b)

/// One broadcast ephemeris set, SI units and radians (as RINEX stores them,
/// km converted to m). Every time is GPST, converted on reading (BDT + 14 s;
/// GLONASS from UTC(SU) with the leap seconds of its date).
struct Ephemeris {
  SatId sat;                   ///< system and RINEX number
  time::GpsTime toc;           ///< clock reference time (GLONASS: tb; SBAS: t0)
  time::GpsTime toe;           ///< ephemeris reference time (GLONASS: tb; SBAS: t0)
  double af0_s = 0.0;          ///< clock bias, s (SBAS: aGf0)
  double af1_s_s = 0.0;        ///< clock drift, s/s (SBAS: aGf1)
  double af2_s_s2 = 0.0;       ///< clock drift rate, s/s^2
  int iode = 0;                ///< issue of data, ephemeris (Galileo IODnav, BeiDou AODE, GLONASS tb index)
  int iodc = 0;                ///< issue of data, clock (BeiDou AODC)
  double crs_m = 0.0, crc_m = 0.0;       ///< radius harmonic corrections, m
  double cus_rad = 0.0, cuc_rad = 0.0;   ///< argument-of-latitude corrections, rad
  double cis_rad = 0.0, cic_rad = 0.0;   ///< inclination corrections, rad
  double delta_n_rad_s = 0.0;  ///< mean motion difference, rad/s
  double m0_rad = 0.0;         ///< mean anomaly at toe, rad
  double e = 0.0;              ///< eccentricity, dimensionless
  double sqrt_a_sqrtm = 0.0;   ///< square root of the semi-major axis, m^0.5
  double omega0_rad = 0.0;     ///< longitude of ascending node at the start of the system's week, rad
  double i0_rad = 0.0;         ///< inclination at toe, rad
  double omega_rad = 0.0;      ///< argument of perigee, rad
  double omega_dot_rad_s = 0.0;///< rate of right ascension, rad/s
  double idot_rad_s = 0.0;     ///< rate of inclination, rad/s
  /// Group delay the single-frequency L1-band user subtracts, s: GPS/QZSS
  /// TGD, Galileo BGD(E1,E5b) (I/NAV), BeiDou TGD1 (B1I), GLONASS and SBAS 0.
  double tgd_s = 0.0;
  /// Second group delay, s: Galileo BGD(E1,E5a), BeiDou TGD2 (B2I); else 0.
  double tgd2_s = 0.0;
  double sv_accuracy_m = 0.0;  ///< URA / SISA / URA index as metres, m
  /// Health as broadcast: GPS/QZSS SV health, Galileo SV health bits
  /// (bit 0 E1-B DVS, 1-2 E1-B HS, ...), BeiDou SatH1, GLONASS Bn, SBAS
  /// health; 0 = healthy.
  int health = 0;
  double fit_interval_h = 0.0; ///< GPS curve-fit interval, h; 0 = unknown (4 h assumed)
  double transmit_tow_s = 0.0; ///< transmission time of message, s from the start of toe's GPS week
                               ///< (negative = previous week); 0 when !transmit_known
  bool transmit_known = false; ///< false when the file gave 0.9999e9 (unknown) or for almanacs
  int gal_data_sources = 0;    ///< Galileo data-source bits (kGal*); 0 for other systems

  // State-vector systems (GLONASS, SBAS): the state at toe, ECEF (PZ-90.11
  // for GLONASS, taken as WGS 84).
  Ecef pos_m;                  ///< position at toe, m
  Ecef vel_m_s;                ///< velocity at toe, m/s
  Ecef acc_m_s2;               ///< GLONASS: luni-solar acceleration; SBAS: acceleration, m/s^2
  double tau_n_s = 0.0;        ///< GLONASS clock offset tau_n (clock = -tau_n + gamma_n (t - tb)), s
  double gamma_n = 0.0;        ///< GLONASS relative frequency offset gamma_n, dimensionless
  int glo_channel = 0;         ///< GLONASS FDMA channel k, -7..+6
  int glo_age_days = 0;        ///< GLONASS age of the data E, days
};

/// The L1-band carrier the satellite transmits, Hz: its system's (the
/// system table), GLONASS by the set's FDMA channel.
constexpr double carrier_hz(const Ephemeris& eph) noexcept { return l1_carrier_hz(eph.sat.system, eph.glo_channel); }

/// Group delay a user of the satellite's second signal subtracts from the
/// broadcast clock, s; gamma = (f1 / f2)^2 of its two carriers. GPS and
/// QZSS: gamma TGD (IS-GPS-200 §20.3.3.3.3.2, gamma = (77/60)^2); Galileo:
/// gamma BGD(E1,E5b) for E5b (OS SIS ICD §5.1.5); BeiDou: TGD2 for B2I (BDS
/// ICD B1I §5.2.4.10); GLONASS (its L1/L2 delay is not in the nav data read)
/// and SBAS: 0.
constexpr double band1_group_delay_s(const Ephemeris& eph, double gamma) noexcept {
  switch (eph.sat.system) {
    case GnssSystem::kGps:
    case GnssSystem::kQzss:
    case GnssSystem::kGalileo: return gamma * eph.tgd_s;
    case GnssSystem::kBeiDou: return eph.tgd2_s;
    default: return 0.0;
  }
}

/// Satellite state at a GPS time.
struct SatState {
  Ecef pos_m;                  ///< ECEF position at t, in the ECEF frame of time t
  Ecef vel_m_s;                ///< ECEF velocity (includes Earth-rotation terms)
  double clk_bias_s = 0.0;     ///< clock offset incl. the relativistic term (Kepler systems); excludes TGD
  double clk_drift_s_s = 0.0;  ///< its rate, s/s
  double relativity_s = 0.0;   ///< F e sqrt(A) sin(E), included in clk_bias_s; 0 for GLONASS/SBAS
};

/// Evaluate an ephemeris at GPS system time t (the transmission time), by
/// the orbit kind of its system. Never throws; crossover of weeks is handled
/// through continuous GpsTime. GLONASS: RK4 with 60 s steps from tb.
SatState sat_state(const Ephemeris& eph, const time::GpsTime& t) noexcept;

/// Satellite clock correction (s, relativistic term included for Kepler
/// systems, TGD excluded) at satellite time t_sv, solved for t = t_sv - dt
/// (IS-GPS-200 §20.3.3.3.3.1). Cheap for every system: no orbit integration.
double sat_clock_at_sv_time(const Ephemeris& eph, const time::GpsTime& t_sv) noexcept;

/// Validity half-window of an ephemeris around toe, s: GPS half its fit
/// interval, 2 h when unknown (RTKLIB MAXDTOE); the others the system's
/// maximum age (system_info().max_ephemeris_age_s).
double validity_half_window_s(const Ephemeris& eph) noexcept;

/// Seconds of toe in the system's own week (BDT for BeiDou; GST and QZSS
/// weeks start with GPS weeks): Omega0 of a Keplerian set is referred to
/// that week's start (the -omega_e toe term of IS-GPS-200 Table 20-IV).
double toe_of_week_s(const Ephemeris& eph) noexcept;

/// Step of the GLONASS orbit integration, s (ICD GLONASS Ed. 5.1 App. A.3.1.2; RTKLIB TSTEP).
inline constexpr double kGlonassStep_s = 60.0;

/// Longest GLONASS integration, s: further from tb the state at this span is returned.
inline constexpr double kGlonassMaxSpan_s = 8.0 * 86400.0;

/// GLONASS state vector integrated from the ephemeris' tb to t with RK4 and
/// steps of at most step_s (the last one shortened). For tests of the step
/// size; sat_state() uses kGlonassStep_s.
SatState glonass_state(const Ephemeris& eph, const time::GpsTime& t, double step_s) noexcept;

/// Where a GLONASS integration stands after whole RK4 steps from tb: lets
/// the next evaluation of the same set resume there instead of integrating
/// from tb again (the state at t is then the same to the last bit).
struct GlonassNode {
  const Ephemeris* eph = nullptr;  ///< the set integrated; null: none yet
  time::GpsTime toe;               ///< its tb (a set at a reused address is told apart by it)
  int steps = 0;                   ///< whole steps taken from tb, in the direction of sign
  double sign = 0.0;               ///< +1 forward, -1 backward, 0 at tb
  double x[6] = {};                ///< position m, velocity m/s (PZ-90 = ECEF)
};

/// sat_state() of a GLONASS set, resuming from node when node holds a whole
/// step of this set on the way to t (else from tb), and leaving node at the
/// last whole step before t. Bit-identical to sat_state(eph, t). Other
/// systems: sat_state(eph, t), node untouched.
SatState sat_state(const Ephemeris& eph, const time::GpsTime& t, GlonassNode& node) noexcept;

/// Acceleration of the satellite at pos_m / vel_m_s in the rotating ECEF
/// frame, m/s^2, for short Taylor steps of an evaluated state: GLONASS the
/// ICD force model with the set's luni-solar term (the derivative its RK4
/// integrates), SBAS its broadcast acceleration, the Keplerian systems
/// central gravity with J2 plus the centrifugal and Coriolis terms (the
/// luni-solar ~5e-6 m/s^2 left out moves a state by < 2e-8 m over 80 ms).
Ecef ecef_acceleration_m_s2(const Ephemeris& eph, const Ecef& pos_m, const Ecef& vel_m_s) noexcept;

}  // namespace gnssemu::orbit

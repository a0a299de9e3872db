// SPDX-License-Identifier: Apache-2.0
#pragma once
// Fix: everything one receiver epoch produces. Every protocol encoder reads
// only this, so satellites used, DOP, accuracy and C/N0 agree across outputs.
#include <array>
#include <cstdint>
#include <string_view>

#include "core/common/constants.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::receiver {

enum class FixType : uint8_t {
  kNone = 0,  ///< no position (too few satellites, bad geometry, no antenna)
  /// The navigation filter's prediction alone (too few satellites for a few
  /// seconds): the position is extrapolated, the accuracies grow, nothing is
  /// used; reported as u-blox "dead reckoning only" (NAV-PVT fixType 1,
  /// GGA quality 6) or as no fix (NavFilterConfig::coast_report).
  kDeadReckoning = 1,
  k2D = 2,    ///< horizontal only; height held
  k3D = 3,
};

/// Short name for logs and the status page: "none", "DR", "2D", "3D".
constexpr std::string_view fix_type_name(FixType t) noexcept {
  switch (t) {
    case FixType::k3D: return "3D";
    case FixType::k2D: return "2D";
    case FixType::kDeadReckoning: return "DR";
    case FixType::kNone: break;
  }
  return "none";
}

/// A position from the satellites (2D or 3D), not extrapolated: what error
/// statistics count as a fix.
constexpr bool is_gnss_fix(FixType t) noexcept { return t == FixType::k2D || t == FixType::k3D; }

/// Carrier-phase solution state (NAV-PVT flags carrSoln; GGA quality 5 float, 4 fixed).
enum class CarrierSolution : uint8_t { kNone = 0, kFloat = 1, kFixed = 2 };

/// Position relative to a reference station or a moving base (NAV-RELPOSNED,
/// NMEA HDT/THS): the baseline from the reference antenna to this one.
struct RelativePosition {
  bool valid = false;          ///< relPosValid: a baseline is computed this epoch
  bool moving_base = false;    ///< isMoving: the reference moves (moving-baseline heading)
  bool ref_pos_miss = false;   ///< refPosMiss: the reference position was not available this epoch (extrapolated)
  bool ref_obs_miss = false;   ///< refObsMiss: the reference observations were not available this epoch (extrapolated)
  CarrierSolution carr_soln = CarrierSolution::kNone;
  int ref_station_id = 0;      ///< DF003, 0..4095
  double n_m = 0.0, e_m = 0.0, d_m = 0.0;  ///< baseline in the reference's local NED frame, m
  double length_m = 0.0;       ///< |baseline|, m
  double heading_rad = 0.0;    ///< of the baseline's horizontal part, [0, 2pi) from true north
  bool heading_valid = false;  ///< relPosHeadingValid
  double acc_n_m = 0.0, acc_e_m = 0.0, acc_d_m = 0.0;  ///< 1-sigma, m
  double acc_length_m = 0.0;   ///< 1-sigma, m
  double acc_heading_rad = 0.0;///< 1-sigma, rad
  /// The epoch the baseline is for. A moving-base rover time-matches the
  /// base's observations, so its baseline comes out once the base's epoch
  /// has arrived: late set, t earlier than the Fix's own epoch.
  time::GpsTime t;
  bool late = false;
  /// No NAV-RELPOSNED with this epoch's output: the moving base's epoch of
  /// this time is expected within the epoch period, and the RELPOSNED goes
  /// out when it arrives (the daemon's on-arrival path).
  bool held = false;
};

/// The antenna supervisor's state (MON-HW aStatus).
enum class AntennaStatus : uint8_t { kOk, kShort, kOpen };

/// Dilutions of precision; kNoDop when undefined (NMEA prints 99.99).
struct Dop {
  static constexpr double kNoDop = 99.99;
  double gdop = kNoDop, pdop = kNoDop, hdop = kNoDop, vdop = kNoDop, tdop = kNoDop;
};

/// Per-satellite state of one epoch (for GSV/GSA, NAV-SAT, NAV-SVINFO).
struct SatInfo {
  SatId sat;                  ///< system and RINEX number
  double az_rad = 0.0;        ///< [0, 2pi), from true north
  double el_rad = 0.0;        ///< [-pi/2, pi/2]
  double cn0_dbhz = 0.0;      ///< 0 when not tracked
  bool healthy = false;       ///< ephemeris healthy and valid
  bool above_mask = false;    ///< elevation >= mask
  bool tracked = false;       ///< signal tracked (pseudorange available)
  bool used = false;          ///< used in the navigation solution
  bool excluded = false;      ///< tracked, but removed from the solution by fault detection (residual test)
  bool ephemeris = true;      ///< the receiver has its broadcast ephemeris (decoded, or kept over a restart)
  bool smoothed = false;      ///< its pseudorange is carrier-smoothed
  /// SBAS corrections (fast and long-term) applied to its pseudorange this
  /// epoch; sbas_iono: its ionospheric delay from the SBAS grid, not Klobuchar.
  bool sbas_corr = false;
  bool sbas_iono = false;
  double pseudorange_m = 0.0; ///< measured (with all errors), m
  double doppler_hz = 0.0;    ///< measured Doppler of the satellite's carrier, Hz
  double residual_m = 0.0;    ///< post-fit pseudorange residual, m (used only)
  // Scene propagation (world truth, for analysis; zero without a scene).
  bool nlos = false;          ///< received via reflections only
  bool blocked = false;       ///< above the mask but no signal path (not received)
  int bounces = 0;            ///< reflections on the tracked path
  double nlos_delay_m = 0.0;  ///< extra path length added to the pseudorange, m
  int glonass_channel = 0;    ///< GLONASS FDMA channel k (-7..6); 0 for other systems
};

struct Fix {
  time::GpsTime t;             ///< epoch, GPS time (receive time)
  int leap_seconds = 18;       ///< GPS - UTC used for UTC output, s
  bool in_leap_second = false; ///< t is in an inserted leap second: UTC 23:59:60.x (leap_seconds still the old count)
  bool time_valid = false;     ///< receiver time known (false before the receiver has GPS time)
  FixType type = FixType::kNone;

  Ecef pos_m;                  ///< valid when type != kNone
  Lla lla;                     ///< same position, geodetic; height above ellipsoid
  double geoid_sep_m = 0.0;    ///< geoid height N, m (MSL height = lla.height_m - N)
  Ecef vel_m_s;                ///< ECEF velocity
  Enu vel_enu_m_s;             ///< same velocity in ENU at the fix position
  double speed_m_s = 0.0;      ///< horizontal speed over ground
  double course_rad = 0.0;     ///< course over ground [0, 2pi), from true north
  double climb_m_s = 0.0;

  double clock_bias_s = 0.0;   ///< estimated receiver clock bias
  double clock_drift_s_s = 0.0;///< estimated receiver clock drift

  /// Differential corrections applied to the solution (NAV-PVT flags diffSoln;
  /// GGA quality 2 without a carrier solution).
  bool diff_soln = false;
  /// The differential corrections are an SBAS's (GGA station 0000, no age, as
  /// the real NEO-M9N prints); false with diff_soln: RTCM.
  bool sbas_soln = false;
  CarrierSolution carr_soln = CarrierSolution::kNone;
  /// Age of the corrections the solution used, s (rover epoch - base epoch;
  /// < 0: none). GGA field 13, NAV-PVT flags3 lastCorrectionAge.
  double corr_age_s = -1.0;
  int ref_station_id = -1;     ///< reference station of the corrections (GGA field 14); -1 none
  RelativePosition rel_pos;    ///< NAV-RELPOSNED

  Dop dop;
  int num_used = 0;            ///< satellites in the solution
  int num_tracked = 0;         ///< satellites tracked (C/N0 > 0)
  int num_visible = 0;         ///< satellites above the mask with a valid ephemeris

  // 1-sigma accuracy estimates (sigma_uere * DOP); large values when no fix.
  double sigma_uere_m = 0.0;   ///< user equivalent range error assumed by the solver
  double range_rms_m = 0.0;    ///< RMS of post-fit residuals (GST field 2)
  double sigma_e_m = 0.0, sigma_n_m = 0.0, sigma_u_m = 0.0;
  double cov_en_m2 = 0.0;      ///< east-north covariance, m^2 (the error ellipse's tilt)
  double h_acc_m = 0.0;        ///< horizontal accuracy (as u-blox hAcc)
  double v_acc_m = 0.0;        ///< vertical accuracy (vAcc)
  double speed_acc_m_s = 0.0;  ///< sAcc
  double time_acc_s = 0.0;     ///< tAcc

  /// Environment noise-floor rise above thermal at the antenna, dB (>= 0);
  /// the signal module's environment_noise_rise_db. Drives MON-HW noisePerMS,
  /// AGC and jamInd. 1 dB = quiet countryside.
  double noise_rise_db = 1.0;
  /// CW / narrowband interference over the front end's noise floor (linear,
  /// >= 0; 0 none): the CW detector's input (MON-HW jamInd).
  double cw_jam_to_noise = 0.0;
  AntennaStatus antenna_status = AntennaStatus::kOk;
  /// NAV-STATUS flags2 spoofDetState: 0 deactivated, 1 no spoofing
  /// indicated, 2 spoofing indicated, 3 multiple indications.
  uint8_t spoof_det_state = 1;

  std::array<SatInfo, kMaxSatsInView> sats{};  ///< first num_sats entries valid, sorted by SatId order
  int num_sats = 0;
};

}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu spp`: single-point positioning from real RINEX observations of
// every chosen system (GPS C1C, GLONASS C1C, Galileo E1 C1C/C1X, BeiDou B1I
// C2I, QZSS C1C) through the emulated receiver's own solver and corrections
// (receiver::Solver: satellite at transmit time from the pseudorange, Sagnac,
// broadcast clock + relativity - the system's group delay, one clock per
// system, and the receiver's ionosphere, scaled to each carrier, and
// troposphere corrections).
#include <array>
#include <optional>
#include <ostream>
#include <vector>

#include "core/common/constants.hpp"
#include "core/common/vec3.hpp"
#include "core/observation/obs_data.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/receiver/receiver_config.hpp"
#include "core/receiver/solution/solver.hpp"

namespace gnssemu::cli {

/// The receiver's own ionosphere (broadcast Klobuchar; RTKLIB defaults when
/// k is invalid) plus troposphere correction for a satellite at (az_rad,
/// el_rad) seen from rx at GPS time t, m, with the models chosen in solver
/// ([receiver.corrections]; the defaults are the receiver's). variance_m2
/// (optional): set to what the correction may miss as the solver weights it
/// (receiver::correction_variance_m2), m^2. carrier_hz: the signal's carrier
/// (gnss_systems.hpp l1_carrier_hz), Hz: the Klobuchar delay, an L1 figure,
/// is scaled by (f_L1 / f)^2 and its variance by that factor once, as RTKLIB's
/// pntpos does.
double receiver_correction_m(const orbit::KlobucharParams& k, const Lla& rx, double az_rad, double el_rad,
                             const time::GpsTime& t, const receiver::SolverConfig& solver = {},
                             double* variance_m2 = nullptr, double carrier_hz = kL1Freq_hz);

/// The pseudorange type spp takes for system s from a header's types, in
/// RTKLIB 2.4.3's code priority for the L1-band slot (rinex.c codepris): GPS
/// C1C; GLONASS C1C, C1P; Galileo C1C, C1A, C1B, C1X, C1Z; BeiDou B1I C2I,
/// C2Q, C2X; QZSS C1C, C1L, C1S, C1X, C1Z; SBAS none. -1 when the file has none.
int pseudorange_type(const observation::ObsHeader& header, GnssSystem s);

/// One epoch's solution.
struct SppEpoch {
  time::GpsTime t;
  bool fix = false;            ///< 3D fix (4+ satellites above the mask, test passed)
  Ecef pos_m;
  double clock_m = 0.0;        ///< c * receiver clock bias, m
  double pdop = 0.0;
  int nsat = 0;                ///< satellites used
  std::array<SatId, kMaxSatsInView> sat{};          ///< used satellites, first nsat entries
  std::array<double, kMaxSatsInView> el_rad{};      ///< their elevation at the fix
  std::array<double, kMaxSatsInView> residual_m{};  ///< their post-fit residuals
};

/// Single-point solutions epoch by epoch (warm start from the previous fix).
class SppEngine {
public:
  /// nav and store must outlive the engine; header gives the pseudorange and
  /// C/N0 columns (pseudorange_type). The receiver's own settings, as the
  /// live receiver takes them: its mask, max_pdop and solver (weights,
  /// corrections, residual test). systems: those solved with (SBAS is not
  /// ranged). Throws gnssemu::Error when the file has no pseudorange type of
  /// those systems or on an invalid setting.
  SppEngine(const orbit::NavData& nav, const orbit::EphemerisStore& store, const observation::ObsHeader& header,
            const receiver::ReceiverConfig& receiver, SystemSet systems = SystemSet::only(GnssSystem::kGps));

  /// Solve one epoch. The mask is applied at the previous fix (or, without
  /// one, after a first unmasked solution) and re-checked at the result.
  const SppEpoch& solve(const observation::ObsEpoch& epoch);

private:
  bool run(const observation::ObsEpoch& epoch, const Ecef* site);

  const orbit::EphemerisStore& store_;
  orbit::KlobucharParams klobuchar_;
  receiver::ReceiverConfig rx_;
  /// Per system: pseudorange and C/N0 type index (-1: not solved with).
  std::array<int, kNumSystems> code_{}, cn0_{};
  receiver::Solver solver_;
  receiver::Solver cold_solver_;  ///< first solution of a cold start: no residual test
  receiver::SolverInput in_;
  receiver::SolverOutput out_;
  std::array<SatId, kMaxSatsInView> meas_sat_{};
  SppEpoch result_;
  std::optional<Ecef> last_pos_m_;
  double last_clock_m_ = 0.0;
};

/// Single-point errors of obs at a known station: fix minus station in local
/// ENU at the station, m, one entry per step_s from the first epoch (NaN
/// where an epoch has no fix). fixes (optional): epochs with a fix.
std::vector<Enu> spp_error_series(const observation::ObsData& obs, const orbit::NavData& nav,
                                  const orbit::EphemerisStore& store, const receiver::ReceiverConfig& receiver,
                                  const Ecef& station, double step_s, int* fixes = nullptr,
                                  SystemSet systems = SystemSet::only(GnssSystem::kGps));

struct SppSummary {
  int epochs = 0;
  int fixes = 0;
};

/// The Keplerian sets RTKLIB 2.4.3 keeps after reading navigation files
/// (rtkcmn.c uniqeph): every GPS, Galileo (I/NAV and F/NAV), QZSS and BeiDou
/// set sorted stably by transmission time, then toe (whole seconds), then
/// RTKLIB's satellite number (G, R, E, J, C order), and a set dropped when
/// the one before it in that order has the same satellite and IODE/IODnav/
/// AODE. An I/NAV set that follows the F/NAV set of its IODnav is so lost
/// and RTKLIB falls back to an older one. Every kept set of a satellite gets
/// the group delay of its first kept set, as pntpos.c gettgd() takes it
/// (Galileo: the BGD(E1,E5b) field of that set, F/NAV or I/NAV). spp --preset
/// rtklib selects from what this keeps. GLONASS and SBAS sets are returned
/// unchanged.
std::vector<orbit::Ephemeris> rtklib_unique_ephemerides(const std::vector<orbit::Ephemeris>& ephemerides);

/// Writes `gps_week,tow_s,x_m,y_m,z_m,nsat,pdop` per epoch with a fix, plus
/// `e_m,n_m,u_m` (fix minus station in local ENU) when station is given.
/// rtklib_sets: select ephemerides from rtklib_unique_ephemerides (--preset rtklib).
SppSummary write_spp(const observation::ObsData& obs, const orbit::NavData& nav,
                     const receiver::ReceiverConfig& receiver, const std::optional<Ecef>& station, std::ostream& out,
                     SystemSet systems = SystemSet::only(GnssSystem::kGps), bool rtklib_sets = false);

}  // namespace gnssemu::cli

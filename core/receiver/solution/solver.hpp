// SPDX-License-Identifier: Apache-2.0
#pragma once
// Receiver-side navigation solver: broadcast satellite clock (relativity
// included) minus the group delay, Sagnac, weighted least squares
// (Gauss–Newton) for position, the receiver clock and an inter-system bias
// per further system present in the epoch (RTKLIB pntpos' states; a system
// with no measurement has no state), Doppler least squares for velocity and
// clock drift, DOP, covariance-based accuracy, chi-square residual test, 2D
// height hold. Never throws, never allocates.
#include <array>

#include "core/common/constants.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/receiver/fix.hpp"
#include "core/receiver/receiver_config.hpp"
#include "core/receiver/solution/small_matrix.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/sky/shared_sky.hpp"

namespace gnssemu::receiver {

/// One tracked satellite's measurements.
struct Measurement {
  /// Its system chooses the receiver clock state (eph->sat.system).
  const orbit::Ephemeris* eph = nullptr;
  double pseudorange_m = 0.0;
  double doppler_hz = 0.0;  ///< carrier Doppler at wavelength_m, Hz (positive when approaching)
  double wavelength_m = kL1Wavelength_m;  ///< wavelength of the tracked carrier, m (> 0): range rate = -lambda D
  double cn0_dbhz = 0.0;    ///< receiver's C/N0 estimate, dB-Hz; <= 0: unknown (no C/N0 weight term)
  /// Variance of corrections already applied to pseudorange_m by the caller
  /// (`gnssemu spp` corrects before the solver; correction_variance_m2), m^2.
  double correction_var_m2 = 0.0;
  /// The slant ionospheric delay at wavelength_m is known (an SBAS grid's,
  /// iono_m, m): used instead of the broadcast model, without its variance.
  bool iono_given = false;
  double iono_m = 0.0;
};

struct SolverInput {
  time::GpsTime t_rx_local;  ///< measurement time tag on the receiver's own clock
  /// The epoch's broadcast orbits (world::Observables::sky); null: each
  /// measurement's ephemeris is evaluated in full.
  const world::SharedSky* sky = nullptr;
  double doy = 1.0;          ///< day of year of t_rx_local (fractional), for the Niell mapping
  std::array<Measurement, kMaxSatsInView> meas{};
  int num_meas = 0;
  bool have_prior = false;   ///< warm start from prior_pos_m / prior_clock_m
  Ecef prior_pos_m;
  double prior_clock_m = 0.0;  ///< c * clock bias, m
  bool have_held_height = false;  ///< a 3D fix exists: 2D with 3 satellites allowed
  Ecef held_pos_m;           ///< last 3D position (start point of 2D solutions)
  double held_height_m = 0.0;///< its ellipsoidal height, m
};

struct SolverOutput {
  FixType type = FixType::kNone;
  Ecef pos_m;
  Lla lla;
  double clock_m = 0.0;          ///< c * clock bias of the first system present (table order: GPS if any), m
  /// Inter-system bias per system: c x (its clock - clock_m), m; 0 for the
  /// first system and systems without a clock state (clock_systems).
  std::array<double, kNumSystems> isb_m{};
  SystemSet clock_systems;       ///< systems with their own clock state in the solution
  Enu vel_enu_m_s;
  Ecef vel_m_s;
  double drift_m_s = 0.0;        ///< c * clock drift, m/s
  Dop dop;
  /// Covariances in local ENU + clock (m^2, clock in m^2): position solve
  /// (its position and clock_m block; the inter-system biases marginalised)
  /// and velocity solve (m^2/s^2).
  std::array<std::array<double, 4>, 4> cov_pos{};
  std::array<std::array<double, 4>, 4> cov_vel{};
  std::array<double, kMaxSatsInView> residual_m{};  ///< post-fit, per measurement index
  int num_used = 0;
  double range_rms_m = 0.0;
  double sigma_uere_m = 0.0;     ///< RMS of the assumed 1-sigma over used satellites
  double chi2 = 0.0;             ///< weighted sum of squared residuals
  int dof = 0;
  /// Fault exclusion: per measurement index, true when the residual test
  /// excluded that satellite from the solution (residual_m is then 0).
  std::array<bool, kMaxSatsInView> excluded{};
  int num_excluded = 0;
};

/// One measurement linearised at a given state (MeasurementModel).
struct MeasurementRow {
  Vec3 los;                  ///< unit vector receiver -> satellite, ECEF
  double range_resid_m = 0.0;  ///< pseudorange minus its prediction at the state, m
  double sigma2_m2 = 0.0;    ///< the weight model's variance of the pseudorange, m^2
  /// Measured range rate minus the satellite's part (LOS satellite velocity,
  /// its clock drift): what -los . v_rx + c drift_rx should equal, m/s.
  double rate_obs_m_s = 0.0;
};

class Solver {
public:
  /// cfg and max_pdop as in ReceiverConfig. Does not validate (Receiver does).
  Solver(const SolverConfig& cfg, double max_pdop) noexcept;

  /// Solves, then runs fault detection and exclusion (RAIM-style): while the
  /// chi-square residual test fails, at least kMinSatsAfterExclusion
  /// satellites would remain and fewer than cfg.max_exclusions have been
  /// excluded, the satellite with the largest normalised
  /// residual |v_i| / sqrt(sigma_i^2 (1 - h_ii)) is excluded and the epoch
  /// re-solved; if the test still fails, no fix.
  void solve(const SolverInput& in, SolverOutput& out) noexcept;

  /// Satellites that must remain after an exclusion with one system: 4
  /// unknowns + 1 to keep the residual test meaningful (one more per further
  /// system's clock).
  static constexpr int kMinSatsAfterExclusion = 5;

  /// Broadcast Klobuchar coefficients for the ionospheric correction (the
  /// nav header's); invalid -> RTKLIB defaults (the state after construction).
  void set_klobuchar(const orbit::KlobucharParams& p) noexcept { klobuchar_ = p; }
  const orbit::KlobucharParams& klobuchar() const noexcept { return klobuchar_; }

  /// Chi-square threshold for dof degrees of freedom at the configured
  /// false-alarm probability (Wilson–Hilferty; dof >= 1).
  double chi2_threshold(int dof) const noexcept;

  /// The measurements of in linearised at pos_m (ECEF, m, near the Earth's
  /// surface) and clock_m (c x clock bias, m) with the receiver's corrections
  /// and weights, as the solver does at its solution (for a navigation
  /// filter's update); each system's inter-system bias of the last solution
  /// is removed, so one clock describes every row. Returns the rows filled
  /// (in.num_meas; 0 for malformed input).
  int measurement_model(const SolverInput& in, const Ecef& pos_m, double clock_m,
                        std::array<MeasurementRow, kMaxSatsInView>& rows) noexcept;

private:
  struct Sat {
    Ecef pos_m;            // at transmit time, transmit-time ECEF frame
    Ecef vel_m_s;
    double clk_m = 0.0;    // c * (broadcast clock - TGD), m
    double drift_m_s = 0.0;
    double since_tx_s = 0.0;  // t_rx_local - t_tx, s
    double sat_var_m2 = 0.0;  // satellite_variance_m2 + the caller's correction variance, m^2
    double corr_m = 0.0;      // receiver's iono + tropo correction, m
    double model_var_m2 = 0.0;  // variance of what those corrections miss, m^2
    double efact2 = 1.0;   // squared system factor on the elevation variance
    GnssSystem system = GnssSystem::kGps;
    int col = 3;           // state column of its clock: 3 the first system's clock, > 3 an inter-system bias
    // Per-iteration linearisation.
    Vec3 los;              // unit vector receiver -> satellite, ECEF
    Ecef vel_rx_frame_m_s; // velocity rotated into the receive-time frame
    double resid_m = 0.0;
    double weight = 0.0;   // 1 / sigma^2, 1/m^2
    double sigma2 = 0.0;
  };

  /// Satellite states at transmit time and the C/N0 weight terms of in; false
  /// for malformed input (n_ = 0).
  bool prepare(const SolverInput& in) noexcept;
  /// Clock states of the prepared satellites: columns, num_states_.
  void assign_clock_states() noexcept;
  /// Receiver clock of satellite s: clock_m plus its system's bias, m.
  double rx_clock_m(const Sat& s, double clock_m) const noexcept {
    return s.col > 3 ? clock_m + bias_m_[static_cast<std::size_t>(s.col - 4)] : clock_m;
  }
  bool iterate(const SolverInput& in, Ecef& pos, double& clock_m, bool two_d) noexcept;
  void linearise(const SolverInput& in, const Ecef& pos, double clock_m, const Lla* lla) noexcept;
  void update_corrections(const SolverInput& in, const Ecef& pos, const Lla& lla) noexcept;
  bool finish(const SolverInput& in, const Ecef& pos, double clock_m, bool two_d, SolverOutput& out) noexcept;
  enum class Outcome { kFix, kNoFix, kResidualTestFailed };
  /// One solution over every measurement of in (no exclusion). On
  /// kResidualTestFailed out holds the rejected solution and its residuals.
  Outcome solve_all(const SolverInput& in, SolverOutput& out) noexcept;
  /// Index of the largest normalised residual of the solution in out.
  int worst_residual(const SolverOutput& out) const noexcept;
  /// The system whose clock a satellite of sys uses (QZSS and SBAS may share GPS's).
  GnssSystem clock_group(GnssSystem sys) const noexcept;

  SolverConfig cfg_;
  double max_pdop_;
  double z_pfa_;  // standard-normal upper quantile of residual_test_pfa
  std::array<Sat, kMaxSatsInView> sats_{};
  SolverInput subset_;  ///< in without the excluded measurements (fault exclusion)
  /// The input solve() last prepared whole, its satellites and corrections
  /// (measurement_model at the same epoch starts from them).
  struct Solved {
    const SolverInput* in = nullptr;
    time::GpsTime t_rx_local;
    int n = 0;
  } solved_;
  std::array<Sat, kMaxSatsInView> solved_sats_{};
  bool solved_corr_valid_ = false;
  Ecef solved_corr_pos_;
  int n_ = 0;
  int num_states_ = 4;  ///< 3 + clock states of the prepared satellites
  std::array<GnssSystem, kNumSystems> col_system_{};  ///< clock group of column 3 + i
  std::array<double, kNumSystems> bias_m_{};  ///< inter-system bias of column 4 + i during the solve, m
  /// Last solution's biases per system (measurement_model).
  std::array<double, kNumSystems> solved_isb_m_{};
  /// Within solve(): an exclusion's re-solve takes its satellites from the
  /// whole set's (solved_sats_) and the corrections computed for them at
  /// the same position from this cache (the same arithmetic on the same
  /// inputs, so the same bits), by each measurement's index in solve()'s
  /// input (orig_).
  void solve_epoch(const SolverInput& in, SolverOutput& out) noexcept;
  bool in_solve_ = false;
  bool subset_prepared_ = false;  ///< prepare() copies solved_sats_[orig_[i]]
  std::array<int, kMaxSatsInView> orig_{};
  bool corr_cache_valid_ = false;
  Ecef corr_cache_pos_;
  std::array<bool, kMaxSatsInView> corr_cached_{};
  std::array<double, kMaxSatsInView> corr_cache_m_{}, corr_cache_var_m2_{};
  MatN q_{};  ///< weighted covariance of the last finish() (ENU + clock states)
  orbit::KlobucharParams klobuchar_;  // invalid: RTKLIB defaults
  bool corr_valid_ = false;           // corr_m computed at corr_pos_
  Ecef corr_pos_;
};

}  // namespace gnssemu::receiver

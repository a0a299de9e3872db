// SPDX-License-Identifier: Apache-2.0
#pragma once
// The receiver's differential stage: from its own raw measurements and the
// reference station's epoch (Corrections) it computes a DGNSS, RTK float or
// RTK fixed position, or a moving base's baseline and heading, and writes it
// into the Fix (position, accuracies, diff_soln, carr_soln, corr_age_s,
// ref_station_id, rel_pos).
//
// Estimator (docs/rtk.md "RTK state model"): single differences rover - base
// of code and carrier per satellite and band, each receiver's measurement at
// its own epoch with the satellite at its own transmit time (a base epoch
// older by the link latency needs no extrapolation; RTKLIB manual 2.4.2
// §E.7 "time-mismatch"). A moving base is time-matched instead: the rover
// holds its last epochs and solves the one whose time the base's newest
// epoch has: at once when that epoch arrives before the rover's next one
// (on_base_epoch), else with the rover's next epoch. A Kalman filter over the rover position, one
// single-difference clock per system (white, re-initialised every epoch) and
// one single-difference ambiguity per satellite and band (cycles; reset on a
// lock-time restart, a half-cycle state change or a rejected innovation).
// Diagonal noise, so every measurement is one scalar update. Integer
// ambiguities: double differences per system and band against the highest
// satellite, LAMBDA with the ratio test (lambda.hpp), partial resolution by
// dropping the lowest satellites. Integers are held (not fed back into the
// float filter) and the fixed position is re-solved and validated from the
// carrier alone every epoch: a wrong fix shows as growing carrier residuals
// and is dropped, the float filter is untouched by it.
#include <array>
#include <cstdint>

#include "core/common/sat_id.hpp"
#include "core/common/gnss_signals.hpp"
#include "core/common/vec3.hpp"
#include "core/receiver/corrections.hpp"
#include "core/receiver/fix.hpp"
#include "core/receiver/raw_measurements.hpp"
#include "core/receiver/rtk/lambda.hpp"
#include "core/receiver/rtk/rtk_config.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/observables.hpp"

namespace gnssemu::receiver::rtk {

/// Ambiguity states the filter carries at most (satellite-bands).
inline constexpr int kMaxSlots = 64;
inline constexpr int kClockState0 = 3;
inline constexpr int kAmbState0 = 3 + kNumSystems;
inline constexpr int kMaxRtkStates = kAmbState0 + kMaxSlots;
/// Rover epochs a moving-base rover holds for the base's epoch of the same
/// time (1.2 s at the emulator's fastest 10 Hz; RtkConfig::moving_base_max_age_s
/// gives up on them sooner).
inline constexpr int kMovingBaseHeldEpochs = 12;

/// Counters and the last epoch's figures (status page, tests, bench).
struct RtkStatus {
  int num_code_sd = 0;        ///< code single differences used this epoch
  int num_phase_sd = 0;       ///< carrier single differences used this epoch
  int num_fixed_dd = 0;       ///< double differences with held integers this epoch
  double ratio = 0.0;         ///< last LAMBDA ratio test value
  double baseline_m = 0.0;    ///< current baseline length, m
  std::uint32_t ar_attempts = 0;      ///< integer searches run
  std::uint32_t fixes = 0;            ///< searches that passed ratio and validation
  std::uint32_t fix_rejections = 0;   ///< held fixes dropped by the carrier residual test
  std::uint32_t slips = 0;            ///< ambiguities reset (lock restart, half cycle, innovation)
  std::uint32_t baseline_big = 0;     ///< epochs beyond warn_baseline_m (INF-WARNING "DGNSS baseline big")
  std::uint32_t long_baseline = 0;    ///< epochs beyond max_fix_baseline_m (float only)
  std::uint32_t unmatched = 0;        ///< base signals the rover does not track (ignored)
  std::uint32_t stale = 0;            ///< epochs with corrections older than the DGNSS timeout
  std::uint32_t moving_base_matched = 0;  ///< rover epochs solved with the moving base's epoch of the same time
  std::uint32_t moving_base_missed = 0;   ///< rover epochs whose base epoch never came (refObsMiss)
  double moving_base_delay_s = 0.0;       ///< last matched epoch: rover epochs it waited for its base epoch, s
  std::uint32_t moving_base_early = 0;    ///< of the matched: solved when the base's epoch arrived (on_base_epoch)
};

class RtkEngine {
public:
  explicit RtkEngine(const RtkConfig& config = {}) noexcept : cfg_(config) {}

  void set_config(const RtkConfig& c) noexcept { cfg_ = c; }
  const RtkConfig& config() const noexcept { return cfg_; }
  /// CFG-NAVSPG-CONSTR_DGNSSTO, s (> 0; others ignored).
  void set_fix_ambiguities(bool on) noexcept { cfg_.fix_ambiguities = on; }
  void set_dgnss_timeout_s(double s) noexcept {
    if (s > 0.0) cfg_.dgnss_timeout_s = s;
  }
  /// Forget the filter and the held integers.
  void reset() noexcept;

  /// One rover epoch: rover its raw measurements, obs the observables they
  /// came from (ephemerides of the satellites in view), corr the link
  /// (nullptr: none), fix the standalone solution, updated in place.
  void step(const RawEpoch& rover, const world::Observables& obs, const Corrections* corr, Fix& fix) noexcept;
  /// The link changed between rover epochs (corr: as for step, obs: the
  /// observables of the last step, fix: its solution). A moving base's epoch
  /// of the time of the rover's last epoch is solved now, as the F9P does
  /// once the time-matched observations are in; true: fix.rel_pos is that
  /// epoch's (send NAV-RELPOSNED now). An epoch whose RELPOSNED already went
  /// out (refObsMiss) is solved but not reported again (false).
  bool on_base_epoch(const world::Observables& obs, const Corrections* corr, Fix& fix) noexcept;

  const RtkStatus& status() const noexcept { return status_; }

private:
  static constexpr int kNumKeys = kNumSats * kNumBands;

  struct BaseSignal {
    std::uint32_t stamp = 0;   ///< base_stamp_ when filled
    double code_omc_m = 0.0;   ///< pseudorange - range + c dt_sv at the base epoch, m
    double phase_omc_m = 0.0;  ///< carrier (m) - range + c dt_sv, m
    bool phase = false;
    bool half_cycle = false;
    double lock_s = 0.0;
    double code_sigma_m = 0.0;
  };
  struct Slot {
    int key = -1;              ///< sat.index() * kNumBands + band
    GnssSystem system = GnssSystem::kGps;
    int band = 0;
    double wavelength_m = 0.0;
    double lock_r_s = 0.0, lock_b_s = 0.0;
    bool half_r = false, half_b = false;
    std::uint32_t arc = 0;     ///< incremented when the ambiguity restarts
    // This epoch.
    bool in_use = false;
    double y_m = 0.0;          ///< carrier single difference minus the range at the linearisation point, m
    Vec3 e;                    ///< unit line of sight rover -> satellite
    double var_m2 = 0.0;
    double el_rad = 0.0;
    // Held integer: N = N_ref(float) + held_dd, the reference slot's key and arc.
    bool held = false;
    double held_dd = 0.0;
    int held_ref_key = -1;
    std::uint32_t held_ref_arc = 0;
  };

  /// What the filter takes from the navigation solution of an epoch.
  struct NavSnapshot {
    time::GpsTime t;
    Ecef pos_m;
    Vec3 vel_m_s;
    double speed_acc_m_s = 0.0;
  };
  /// A rover epoch waiting for the moving base's epoch of the same time.
  struct HeldEpoch {
    bool pending = false;
    bool reported = false;  ///< its RELPOSNED went out already (refObsMiss)
    RawEpoch raw;
    NavSnapshot nav;
  };

  /// The moving-base path: hold this epoch, solve the held one the base's
  /// newest epoch matches, give up on those it can no longer match.
  /// prev_early: the previous epoch was solved by on_base_epoch (this one's
  /// RELPOSNED then waits for its base epoch too).
  void step_moving(const RawEpoch& rover, const world::Observables& obs, const Corrections& c, bool prev_early,
                   Fix& fix) noexcept;
  /// One filter epoch: rover's measurements with nav its solution, against the processed base epoch.
  void solve(const RawEpoch& rover, const NavSnapshot& nav, const Corrections& c, const world::Observables& obs,
             Fix& fix) noexcept;
  void reset_filter(const Ecef& pos_m) noexcept;
  void clear_link_fields(Fix& fix) const noexcept;
  /// sky: the rover epoch's broadcast orbits (Taylor steps back to the base epoch), or null.
  void process_base(const Corrections& c, const world::SharedSky* sky) noexcept;
  /// Moves the rover state by shift_m (1-sigma shift_sigma_m) and adds the process noise of dt_s.
  void predict(double dt_s, const Vec3& shift_m, double shift_sigma_m) noexcept;
  int slot_for(int key, GnssSystem sys, int band, double wavelength_m) noexcept;
  void reset_ambiguity(int s, double value_cyc, double var_cyc2) noexcept;
  void free_slot(int s) noexcept;
  void zero_cross(int i) noexcept;
  /// Scalar update with sparse h (idx/h, nh entries), innovation v, noise r;
  /// returns false (nothing changed) when v^2 / S exceeds gate2. n_active > 0:
  /// on the first n_active states only (their marginal; see carry_code_block).
  bool update(const int* idx, const double* h, int nh, double v, double r, double gate2,
              int n_active = 0) noexcept;
  /// After updates of the position-and-clock block alone (states below
  /// kAmbState0; the clocks fresh, uncorrelated with the rest): the
  /// ambiguities' mean and covariance conditioned on the new block, from the
  /// position's prior mean xp0 and covariance (inverse ppp0_inv).
  void carry_code_block(const std::array<double, 3>& xp0, const std::array<std::array<double, 3>, 3>& ppp0,
                        const std::array<std::array<double, 3>, 3>& ppp0_inv) noexcept;
  /// Applies the pending rank-one terms of update() to P in one pass.
  void flush() noexcept;
  int n_states() const noexcept { return kAmbState0 + n_slots_; }
  bool try_fix(double t_s) noexcept;
  /// Position from the held integers (carrier only); false: too few or the residual test failed.
  bool fixed_solution(Ecef& pos, std::array<std::array<double, 3>, 3>& cov) noexcept;
  void write_output(const Corrections& c, double age_s, bool carrier, bool fixed, const Ecef& pos,
                    const std::array<std::array<double, 3>, 3>& cov_ecef, Fix& fix) const noexcept;

  RtkConfig cfg_;
  RtkStatus status_;

  // Base epoch (per key), processed once per corrections revision.
  std::array<BaseSignal, kNumKeys> base_{};
  std::uint32_t base_stamp_ = 0;
  std::uint32_t base_revision_ = 0;
  bool base_seen_ = false;
  /// A rover measurement's satellite this epoch.
  struct Geometry {
    bool valid = false;
    double range_m = 0.0;      ///< at the linearisation point, Earth rotation included
    Vec3 e;                    ///< unit line of sight rover -> satellite
    double sat_clock_m = 0.0;  ///< c x broadcast satellite clock at transmit time
  };
  std::array<Geometry, kMaxRawMeasurements> geom_{};
  // Per satellite this epoch.
  std::array<const orbit::Ephemeris*, kNumSats> eph_{};
  std::array<std::uint32_t, kNumSats> eph_stamp_{};
  std::array<double, kNumSats> el_rad_{};
  std::uint32_t epoch_ = 0;

  // Float filter.
  bool init_ = false;
  time::GpsTime t_last_;
  Ecef x_lin_;  ///< linearisation point (the predicted position) of this epoch
  Ecef last_arp_m_;  ///< the reference position of the filter's last epoch (a moving base's moves)
  bool init_arp_ = false;
  std::array<double, kMaxRtkStates> x_{};
  /// The covariance: its lower triangle p_[i][j], j <= i (the upper one is
  /// not kept: the updates and flush() touch half the matrix); pv() reads it.
  std::array<std::array<double, kMaxRtkStates>, kMaxRtkStates> p_{};
  double pv(int i, int j) const noexcept {
    return i >= j ? p_[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]
                  : p_[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)];
  }
  std::array<double, kMaxRtkStates> ph_{};
  /// p_'s position-and-clock columns (cols_[a][i] = P(i,a)), copied when a
  /// whole-state update starts without pending terms: read along a row
  /// instead of down p_'s columns.
  std::array<std::array<double, kMaxRtkStates>, kAmbState0> cols_{};
  /// Whole-state updates not yet applied to p_ (P = p_ - sum ph ph' inv):
  /// the covariance's update is memory-bound, so kPendingUpdates of them go
  /// in one pass over it. Only update() and flush() see them; whatever else
  /// writes or resizes p_ flushes first, and solve() before anything reads it.
  static constexpr int kPendingUpdates = 8;
  std::array<std::array<double, kMaxRtkStates>, kPendingUpdates> pend_ph_{};
  std::array<double, kPendingUpdates> pend_inv_{};
  int n_pend_ = 0;
  std::array<Slot, kMaxSlots> slots_{};
  std::array<std::int8_t, kNumKeys> slot_of_{};  ///< -1 none (set in reset)
  int n_slots_ = 0;
  bool slot_map_ready_ = false;

  // Moving base: the last rover epochs (a ring, oldest overwritten).
  std::array<HeldEpoch, kMovingBaseHeldEpochs> held_{};
  int held_next_ = 0;
  int held_last_ = -1;        ///< the last step's epoch in held_ (on_base_epoch may solve it); -1 none
  bool last_early_ = false;   ///< the last step's epoch was solved by on_base_epoch

  // Integer resolution.
  bool fixed_ = false;
  bool glonass_ar_ = false;  ///< 1230 received: GLONASS ambiguities may be fixed
  double last_ar_s_ = -1.0e300;
  Lambda lambda_;
  AmbMat q_dd_{};
  AmbVec a_dd_{};
  std::array<int, kMaxAmbiguities> dd_slot_{}, dd_ref_{};
};

}  // namespace gnssemu::receiver::rtk

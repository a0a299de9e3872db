#pragma once
// Receiver: one GNSS receiver. step() turns vehicle truth at an epoch into
// the Fix a real receiver would report. Pure and deterministic for a seed;
// no exceptions and no allocation on step() after construction.
// World stages per epoch (DESIGN.md §1): sky -> propagation (atmosphere;
// scene slots in here) -> signal (C/N0, tracking) -> observables; then the
// receiver's own solver with its broadcast corrections.
#include <array>
#include <cstdint>
#include <memory>

#include "core/atmosphere/term_cache.hpp"
#include "core/common/vec3.hpp"
#include "core/geo/local_frame.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/receiver/error_processes.hpp"
#include "core/receiver/fix.hpp"
#include "core/receiver/propagation.hpp"
#include "core/receiver/random.hpp"
#include "core/receiver/receiver_config.hpp"
#include "core/receiver/sky.hpp"
#include "core/receiver/solver.hpp"
#include "core/scene/propagator.hpp"
#include "core/signal/link_budget.hpp"
#include "core/signal/tracking.hpp"

namespace gnssemu::receiver {

/// Vehicle truth at the antenna, at time t.
struct Truth {
  time::GpsTime t;
  Ecef pos_m;       ///< antenna position, ECEF m
  Ecef vel_m_s;     ///< antenna velocity, ECEF m/s
  bool valid = false;  ///< false: no truth (antenna lost) -> no fix
};

class Receiver {
public:
  /// store must outlive the receiver. Throws gnssemu::Error on an invalid config.
  Receiver(const orbit::EphemerisStore& store, const ReceiverConfig& config);

  /// Run one epoch at receive time t (GPS). truth.valid == false gives a
  /// no-fix epoch (time still advances, satellites drop out).
  const Fix& step(const time::GpsTime& t, const Truth& truth) noexcept;

  const Fix& last_fix() const noexcept { return fix_; }
  const ReceiverConfig& config() const noexcept { return config_; }

  /// GPS - UTC to report (e.g. the nav header's LEAP SECONDS); without it
  /// the built-in table (time::leap_seconds_at) is used.
  void set_leap_seconds(int leap_s) noexcept {
    leap_override_ = true;
    leap_s_ = leap_s;
  }

  /// Broadcast Klobuchar coefficients of the nav header (RINEX 2 ION
  /// ALPHA/BETA, RINEX 3 GPSA/GPSB). The receiver corrects with them; the
  /// world's Klobuchar-shaped ionosphere takes its shape from them unless
  /// the config gave one. Without this call (or with p.valid false) both use
  /// RTKLIB's default coefficients. Throws gnssemu::Error for non-finite values.
  void set_klobuchar(const orbit::KlobucharParams& p);

  /// Buildings: the scene (built in the ENU frame of origin) decides per
  /// satellite direct / reflected only (extra delay and reflection loss join
  /// the PathEffects) / not received. scene must outlive the receiver. Setup
  /// only (allocates); throws gnssemu::Error on a bad search config.
  void attach_scene(const scene::Scene& scene, const Lla& origin, const scene::SearchConfig& search);
  /// The scene stage (null without a scene); its stats() describe the last epoch.
  const scene::Propagator* propagator() const noexcept { return propagator_.get(); }

  /// The world's propagation effects on prn (1..32) at the last epoch with
  /// truth (zero when the satellite was not above the mask).
  const PathEffects& path_effects(int prn) const noexcept { return path_[static_cast<std::size_t>(prn - 1)]; }
  /// Evaluations of the slow atmospheric terms so far (one per satellite and
  /// refresh; every satellite every epoch without a cache). For benchmarks.
  long atmosphere_refreshes() const noexcept { return atmosphere_evaluations_; }

  /// World truth of the receiver oscillator at the last epoch (for error
  /// analysis; the solver never reads it).
  double true_clock_bias_s() const noexcept { return clock_.bias_s(); }
  double true_clock_drift_s_s() const noexcept { return clock_.drift_s_s(); }

private:
  void advance_world(const time::GpsTime& t) noexcept;
  int sky_stage(const time::GpsTime& t, const Truth& truth, const Lla& rx_lla) noexcept;
  void propagation_stage(const time::GpsTime& t, const Lla& rx_lla, const Ecef& rx_pos_m) noexcept;
  void scene_stage(const Ecef& rx_pos_m) noexcept;
  void signal_stage() noexcept;
  void observables_stage(const time::GpsTime& t, uint64_t epoch) noexcept;
  /// G_N, G_E of the azimuthal gradient at t for a receiver at lon_rad.
  void gradient_now(const time::GpsTime& t, double lon_rad) noexcept;
  void no_fix_epoch() noexcept;
  void fill_solution() noexcept;

  const orbit::EphemerisStore& store_;
  ReceiverConfig config_;
  Fix fix_;

  // World side.
  CounterRng rng_;
  ReceiverClock clock_;
  std::array<double, kMaxGpsPrn> orbit_clock_m_{};  ///< Gauss–Markov state per PRN, m
  std::array<double, kMaxGpsPrn> multipath_unit_{};  ///< unit multipath Gauss–Markov state per PRN
  std::array<double, 2> gradient_m_{};  ///< azimuthal gradient processes g_N, g_E, m
  std::array<double, 2> gradient_now_m_{};  ///< G_N, G_E this epoch (mean + daily cycle + process), m
  std::array<double, kMaxGpsPrn> iono_tecu_{};      ///< vertical TEC perturbation per line of sight, TECU
  double zwd_pert_m_ = 0.0;                         ///< zenith wet delay perturbation, m
  double dt_s_ = 0.0;                               ///< time since the previous epoch, s (>= 0)
  std::array<SkySat, kMaxGpsPrn> sky_{};
  std::array<bool, kMaxGpsPrn> in_sky_{};
  std::array<int, kMaxGpsPrn> above_{};             ///< PRNs above the mask this epoch
  int n_above_ = 0;
  // Propagation stage.
  AtmospherePropagation atmosphere_;
  atmosphere::SlowTermCache<kSlowTermCount> cache_;
  Ecef cache_pos_m_;                                ///< receiver position the cache belongs to
  double cache_height_m_ = 0.0;
  bool cache_pos_valid_ = false;
  long atmosphere_evaluations_ = 0;
  std::array<PathEffects, kMaxGpsPrn> path_{};
  // Scene (optional part of the propagation stage).
  std::unique_ptr<scene::Propagator> propagator_;
  std::unique_ptr<geo::LocalFrame> scene_frame_;
  std::array<scene::SatQuery, kMaxGpsPrn> scene_query_{};
  std::array<scene::SatPath, kMaxGpsPrn> scene_out_{};
  std::array<scene::SatPath, kMaxGpsPrn> scene_path_{};  ///< per PRN, this epoch
  // Signal stage.
  signal::LinkBudgetModel link_;
  std::array<signal::TrackingState, kMaxGpsPrn> tracking_{};
  std::array<double, kMaxGpsPrn> cn0_dbhz_{};
  std::array<bool, kMaxGpsPrn> tracked_{};
  uint64_t epoch_ = 0;          ///< step() calls so far (random-stream counter)
  bool started_ = false;
  time::GpsTime t_prev_;

  // Receiver side.
  Solver solver_;
  SolverInput in_;
  SolverOutput out_;
  std::array<int, kMaxGpsPrn> meas_prn_{};  ///< PRN of each solver measurement
  bool time_valid_ = false;
  bool have_fix_ = false;
  time::GpsTime last_fix_t_;
  Ecef last_pos_m_, last_vel_m_s_;
  double last_clock_m_ = 0.0, last_drift_m_s_ = 0.0;
  bool have_3d_ = false;
  Ecef held_pos_m_;
  double held_height_m_ = 0.0;
  bool leap_override_ = false;
  int leap_s_ = 18;
};

}  // namespace gnssemu::receiver

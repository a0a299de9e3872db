// SPDX-License-Identifier: Apache-2.0
#pragma once
// Receiver: the emulated receiver's own processing of the world's
// observables at one epoch (DESIGN.md §1, steps 7-9): acquisition and
// tracking (search times, lose hysteresis, ephemeris download, the channel
// limit), carrier smoothing of code, its own broadcast corrections, weighted
// least squares with fault exclusion, the navigation Kalman filter with its
// dynamic model, DOP, accuracy, fix state and operational limits. It never
// sees the world's models or the truth. Pure and deterministic for a seed; no
// exceptions and no allocation on step() after construction.
#include <array>
#include <cstdint>

#include "core/orbit/nav_data.hpp"
#include "core/receiver/tracking/acquisition.hpp"
#include "core/receiver/corrections.hpp"
#include "core/receiver/fix.hpp"
#include "core/receiver/tracking/hatch_filter.hpp"
#include "core/receiver/solution/navigator.hpp"
#include "core/receiver/raw_measurements.hpp"
#include "core/receiver/receiver_config.hpp"
#include "core/receiver/rtk/rtk_engine.hpp"
#include "core/receiver/tracking/sbas_reception.hpp"
#include "core/receiver/solution/solver.hpp"
#include "core/world/observables.hpp"

namespace gnssemu::receiver {

class Receiver {
public:
  /// Throws gnssemu::Error on an invalid config. seed: the receiver's random
  /// draws (search times); the pipeline passes the world's seed.
  explicit Receiver(const ReceiverConfig& config, std::uint64_t seed = 1);

  /// Process the observables of the epoch at receive time t (GPS). Without
  /// an antenna (obs.antenna_connected false) the epoch has no fix (time
  /// still advances, satellites drop out).
  const Fix& step(const time::GpsTime& t, const world::Observables& obs) noexcept;

  const Fix& last_fix() const noexcept { return fix_; }
  /// The corrections changed between epochs (a host's RTCM arrived): a
  /// moving base's epoch of the last epoch's time is solved now
  /// (RtkEngine::on_base_epoch); obs: the observables of the last step.
  /// true: last_fix().rel_pos is that epoch's, to be sent now.
  bool on_corrections(const world::Observables& obs) noexcept { return rtk_.on_base_epoch(obs, corrections_, fix_); }
  /// The raw measurements of the last step (RXM-RAWX, RINEX, RTCM MSM):
  /// every tracked signal of an enabled system, on the receiver's clock.
  const RawEpoch& raw() const noexcept { return raw_; }
  const ReceiverConfig& config() const noexcept { return config_; }
  /// The correction link's state the RTK stage reads at every step (nullptr:
  /// no link). The caller keeps *c alive and updates it between steps.
  void set_corrections(const Corrections* c) noexcept { corrections_ = c; }
  /// CFG-NAVSPG-CONSTR_DGNSSTO: corrections older than this are not used, s (> 0).
  void set_dgnss_timeout_s(double s) noexcept { rtk_.set_dgnss_timeout_s(s); }
  /// CFG-NAVHPG-DGNSSMODE: fixed (true, factory) or float-only RTK.
  void set_rtk_fix_ambiguities(bool on) noexcept { rtk_.set_fix_ambiguities(on); }
  /// The differential stage's settings (noise terms, ratio threshold, ages).
  void set_rtk_config(const rtk::RtkConfig& c) noexcept { rtk_.set_config(c); }
  /// The differential stage (its counters and last ratio).
  const rtk::RtkEngine& rtk() const noexcept { return rtk_; }

  /// Restart navigation (CFG-RST): every satellite is lost and searched
  /// again, the filter starts over; keep says what the receiver remembers.
  void restart(const StartState& keep) noexcept;
  /// CFG-NAV5 dynModel: the filter's motion model and sanity limits from now on.
  void set_dynamic_model(DynamicModel m) noexcept;
  /// CFG-NAV5 static hold: speed threshold (m/s, 0 off) and distance (m, 0: none).
  void set_static_hold(double speed_m_s, double max_dist_m) noexcept;
  /// CFG-GNSS / CFG-SIGNAL-*: the systems the channels are assigned to. A
  /// satellite of another system is neither tracked nor reported, as on a
  /// u-blox with that system disabled (every system after construction).
  void set_systems(SystemSet systems) noexcept { systems_ = systems; }
  SystemSet systems() const noexcept { return systems_; }
  /// At most n satellites in the solution (the highest; kMaxSatsInView: no
  /// cap), as the NEO-M9N above 8 Hz (protocol::ubx::NavRateLimits).
  void set_max_solution_sats(int n) noexcept { max_solution_sats_ = n < 4 ? 4 : n; }
  int max_solution_sats() const noexcept { return max_solution_sats_; }
  /// CFG-GNSS channel budget: at most per_system[s] satellites of system s
  /// tracked (the highest; by GnssSystem), on top of config().max_channels
  /// in all. Every entry kMaxSatsInView: no per-system limit (after construction).
  void set_channel_limits(const std::array<int, kNumSystems>& per_system) noexcept { channels_ = per_system; }

  /// GPS - UTC to report (e.g. the nav header's LEAP SECONDS); without it
  /// the built-in table (time::leap_seconds_at) is used.
  void set_leap_seconds(int leap_s) noexcept {
    leap_override_ = true;
    leap_s_ = leap_s;
  }

  /// Broadcast Klobuchar coefficients of the nav header (RINEX 2 ION
  /// ALPHA/BETA, RINEX 3 GPSA/GPSB) for the receiver's ionospheric
  /// correction; invalid: RTKLIB's default coefficients (the state after
  /// construction). Throws gnssemu::Error for non-finite values.
  void set_klobuchar(const orbit::KlobucharParams& p);

  /// CFG-SBAS (mode enabled and usage diffCorr; on the M9 CFG-SBAS-USE_DIFFCORR):
  /// SBAS corrections applied from now on (config().sbas after construction).
  void set_sbas(bool on) noexcept { config_.sbas = on; }
  /// What the receiver decodes of the SBAS GEOs it tracks.
  const SbasReception& sbas() const noexcept { return sbas_; }

  const Acquisition& acquisition() const noexcept { return acq_; }
  const Navigator& navigator() const noexcept { return nav_; }

private:
  /// Acquisition, then the channel limit (highest elevations first): tracked_.
  void tracking_stage(const time::GpsTime& t, const world::Observables& obs, double dt_s) noexcept;
  /// fix_.sats from every satellite in view and the solver's measurements
  /// from the usable ones (carrier-smoothed with the filter).
  void measurement_stage(const world::Observables& obs, double dt_s) noexcept;
  void no_fix_epoch() noexcept;
  /// SBAS reception, then its corrections on the solver's measurements
  /// (obs: the epoch's observables, in SatId order as the measurements).
  void sbas_stage(const world::Observables& obs, double dt_s) noexcept;
  /// diff_soln from the satellites used with SBAS corrections (unless RTK set it).
  void sbas_fix_flags() noexcept;
  /// Keep the max_solution_sats_ highest of the solver's measurements (SatId order kept).
  void cap_measurements() noexcept;
  /// raw_ from the observables of the tracked satellites.
  void raw_stage(const world::Observables& obs, double dt_s) noexcept;
  /// One signal of a satellite as the world gives it.
  struct RawSignal {
    SignalId id;
    double pseudorange_m, doppler_hz, cn0_dbhz, wavelength_m;
    bool carrier_valid;
    double carrier_phase_cycles;
    std::uint32_t discontinuities;
    bool half_cycle;  ///< the phase is half a cycle off (world::SatObservable::carrier_half_cycle)
  };
  /// Append sig (band 0 or 1) of sat to raw_; new_lock: its loop (re)started
  /// this epoch; locked set when its carrier is tracked.
  void raw_measurement(SatId sat, int glonass_channel, int band, const RawSignal& sig, bool new_lock, double dt_s,
                       bool& locked) noexcept;
  /// The second signal of o (its first tracked) is tracked this epoch (also
  /// set in now); pulling: its C/N0 is enough (its pull-in time runs).
  bool band1_tracked(const world::SatObservable& o, double dt_s, bool& now, bool& pulling) noexcept;
  void clear_locks() noexcept;
  void fill_solution() noexcept;
  /// No fix beyond the operational limits or the dynamic model's sanity limits.
  bool within_limits() const noexcept;

  ReceiverConfig config_;
  Fix fix_;

  // Tracking.
  Acquisition acq_;
  // Per satellite (SatId::index()).
  SystemSet systems_ = SystemSet::all();
  int max_solution_sats_ = kMaxSatsInView;
  std::array<int, kNumSystems> channels_ = [] {
    std::array<int, kNumSystems> a{};
    a.fill(kMaxSatsInView);
    return a;
  }();
  std::array<bool, kNumSats> tracked_{};
  std::array<bool, kNumSats> usable_{};
  std::array<double, kNumSats> el_rad_{};  ///< elevation this epoch (channel priority)
  bool started_ = false;
  time::GpsTime t_prev_;

  SpoofMonitor spoof_;

  // Carrier smoothing.
  std::array<HatchFilter, kNumSats> hatch_{};
  std::array<std::uint32_t, kNumSats> discontinuities_{};  ///< the world's count at the last update
  std::array<bool, kNumSats> smoothed_last_{};  ///< smoothed at the previous epoch

  // Corrections (not owned) and the differential stage that reads them.
  const Corrections* corrections_ = nullptr;
  rtk::RtkEngine rtk_;

  // Raw measurements.
  RawEpoch raw_;
  // Per band (index band, then SatId::index()).
  template <class T> using PerBand = std::array<std::array<T, kNumSats>, kNumBands>;
  PerBand<double> lock_time_s_{};  ///< carrier tracked without a discontinuity, s
  PerBand<std::uint32_t> raw_discontinuities_{};  ///< the world's count at the last raw epoch
  /// Whole cycles the receiver's own re-acquisitions added to the world's
  /// phase (its carrier accumulator restarts at each), and their count.
  PerBand<double> relock_cycles_{};
  /// A re-acquired Costas loop locked on the other data sign than the world's: half a cycle more.
  PerBand<bool> relock_half_{};
  PerBand<std::uint32_t> locks_{};
  std::uint64_t seed_ = 1;
  /// The second signal: tracked at the last epoch; time its C/N0 has been
  /// enough while the first signal was tracked (its aided pull-in), s.
  std::array<bool, kNumSats> band1_tracked_{};
  std::array<double, kNumSats> band1_pull_in_s_{};
  double raw_clock_s_ = 0.0;       ///< the receiver clock's offset (local - GPS time) at the last raw epoch, s
  bool raw_clock_known_ = false;

  // Solution.
  Solver solver_;
  Navigator nav_;
  SolverInput in_;
  SolverOutput snap_;  ///< the snapshot solution of the epoch
  SolverOutput out_;   ///< the reported solution (snapshot or filter)
  std::array<SatId, kMaxSatsInView> meas_sat_{};  ///< satellite of each solver measurement
  /// Each solver measurement's SBAS corrections: orbit/clock, and ionosphere.
  std::array<bool, kMaxSatsInView> meas_sbas_{}, meas_sbas_iono_{};
  SbasReception sbas_;
  Lla last_lla_;  ///< of the last fix (the SBAS service area)
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

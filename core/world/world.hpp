// SPDX-License-Identifier: Apache-2.0
#pragma once
// World: the signals at the antenna of a vehicle, for one epoch at a time
// (DESIGN.md §1, steps 1-5): sky (ephemeris, light time, Sagnac) ->
// propagation (atmosphere; buildings when a scene is attached) -> signal
// (C/N0) -> observables (true range + error processes + noise). Pure and
// deterministic for a seed; step() never throws and never allocates.
// Satellites below the mask it is asked for get geometry only; stages the
// config turns off are skipped.
#include <array>
#include <cstdint>
#include <memory>

#include "core/atmosphere/term_cache.hpp"
#include "core/common/gnss_signals.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/geo/local_frame.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/scene/propagator.hpp"
#include "core/signal/link_budget.hpp"
#include "core/world/measurement/carrier.hpp"
#include "core/world/measurement/measurement_noise.hpp"
#include "core/world/measurement/error_processes.hpp"
#include "core/world/observables.hpp"
#include "core/world/measurement/propagation.hpp"
#include "core/world/random.hpp"
#include "core/world/sky/sbas_service.hpp"
#include "core/world/sky/shared_sky.hpp"
#include "core/world/sky/sky.hpp"
#include "core/world/truth.hpp"
#include "core/world/world_config.hpp"

namespace gnssemu::world {

/// Buildings for the propagation stage.
struct SceneSetup {
  const scene::Scene* scene = nullptr;  ///< built in the ENU frame of origin; null: no scene stage
  Lla origin;                           ///< origin of the scene's local frame
  scene::SearchConfig search;           ///< reflection search effort
};

class World {
public:
  /// store must outlive the world. Throws gnssemu::Error on an invalid config.
  World(const orbit::EphemerisStore& store, const WorldConfig& config);

  /// The signals at the antenna at receive time t (GPS) for truth, modelled
  /// for the satellites at or above mask_rad (rad, [0, pi/2)). truth.valid ==
  /// false: no signals (time and the error processes still advance). Updates
  /// the world's own sky for this antenna first.
  const Observables& step(const time::GpsTime& t, const Truth& truth, double mask_rad) noexcept;
  /// The same at the epoch of a sky shared with other receivers, which the
  /// caller updated for sky.t() (with this antenna among its antennas, or
  /// none) and which outlives the returned observables. Its systems must
  /// include this world's (the others' satellites are skipped).
  const Observables& step(const SharedSky& sky, const Truth& truth, double mask_rad) noexcept;
  /// The systems the receiver behind this antenna tracks (its CFG-GNSS):
  /// the others' satellites get no observables at all (a u-blox with a
  /// system disabled neither tracks nor reports it), which saves their light
  /// time, atmosphere, signal and noise. Every satellite draws from its own
  /// counter streams, so the satellites kept see the same draws. Default:
  /// every system.
  void set_tracked_systems(SystemSet systems) noexcept { tracked_ = systems; }
  SystemSet tracked_systems() const noexcept { return tracked_; }
  /// The world's own sky (the one step(t, ...) updates).
  const SharedSky& own_sky() const noexcept { return own_sky_; }

  const Observables& observables() const noexcept { return obs_; }
  const WorldConfig& config() const noexcept { return config_; }

  /// Broadcast Klobuchar coefficients of the day (the nav header's): the
  /// Klobuchar-shaped ionosphere takes its shape from them unless the config
  /// gave one; invalid: kept. Throws gnssemu::Error for non-finite values of
  /// a set it takes.
  void set_klobuchar_shape(const orbit::KlobucharParams& p);

  /// Buildings: the scene decides per satellite direct / reflected only
  /// (extra delay and reflection loss join the PathEffects) / not received.
  /// setup.scene must outlive the world; null detaches. Setup only (allocates).
  void attach_scene(const SceneSetup& setup);
  /// The scene stage (null without a scene); its stats() describe the last epoch.
  const scene::Propagator* propagator() const noexcept { return propagator_.get(); }

  /// The propagation effects on sat (valid()) at the last epoch with truth
  /// (zero when the satellite was not above the mask).
  const PathEffects& path_effects(SatId sat) const noexcept { return path_[static_cast<std::size_t>(sat.index())]; }
  /// Evaluations of the slow atmospheric terms so far (one per satellite and
  /// refresh; every satellite every epoch without a cache). For benchmarks.
  long atmosphere_refreshes() const noexcept { return atmosphere_evaluations_; }

  /// Truth of the receiver oscillator at the last epoch (for error analysis).
  double true_clock_bias_s() const noexcept { return clock_.bias_s(); }
  double true_clock_drift_s_s() const noexcept { return clock_.drift_s_s(); }

private:
  void advance(const SharedSky& sky, const time::GpsTime& t) noexcept;
  /// The code multipath of sat's signal on band (stream its random stream)
  /// at t, m, brought forward from its last step.
  double multipath_m(int band, SatId sat, uint64_t stream, const time::GpsTime& t, uint64_t epoch,
                     double el_rad) noexcept;
  void sky_stage(const SharedSky& sky, const time::GpsTime& t, const Truth& truth, const Lla& rx_lla,
                 double mask_rad) noexcept;
  void propagation_stage(const SharedSky& sky, const time::GpsTime& t, const Lla& rx_lla, const Ecef& rx_pos_m) noexcept;
  void scene_stage(const Ecef& rx_pos_m) noexcept;
  void signal_stage() noexcept;
  void observables_stage(const SharedSky& sky, const time::GpsTime& t, uint64_t epoch, double mask_rad) noexcept;
  /// Carrier phase, its continuity and the lock-break test of one received
  /// satellite (o: its pseudorange already set); rx_clock_s the receiver clock
  /// bias, s, gradient_m the azimuthal delay on its line of sight, m.
  void carrier_observable(SatObservable& o, const SkySat& s, uint64_t epoch, double rx_clock_s,
                          double orbit_clock_m, double gradient_m, double multipath_m) noexcept;
  /// The second signal of a received satellite (o: its first signal set),
  /// from the same geometry, clocks and troposphere.
  void second_signal(SatObservable& o, const SkySat& s, const time::GpsTime& t, uint64_t epoch, double rx_clock_s,
                     double rx_drift_s_s, double orbit_clock_m, double gradient_m) noexcept;
  /// One band's carrier track of a received satellite: a new lock, a slip or
  /// neither this epoch (restart: the path or the range broke the lock), and
  /// the whole and half cycles the track adds to the phase.
  double carrier_offset_cycles(CarrierTrack& c, uint64_t stream, uint64_t epoch, bool restart, double sigma_rad,
                               bool pilot, bool nlos) noexcept;
  /// o's SBAS estimates (o received, iono_m its ionospheric delay, m).
  void sbas_estimates(SatObservable& o, const time::GpsTime& t, uint64_t epoch, double orbit_clock_m,
                      double iono_m) noexcept;
  /// G_N, G_E of the azimuthal gradient at t for a receiver at lon_rad.
  void gradient_now(const SharedSky& sky, const time::GpsTime& t, double lon_rad) noexcept;

  WorldConfig config_;
  SharedSky own_sky_;
  MeasurementNoise noise_;  ///< code and range-rate noise versus C/N0 (shared with the fault stage)
  Observables obs_;

  // Error processes.
  CounterRng rng_;
  ReceiverClock clock_;
  // The shared processes at this epoch (the sky's unit values times this
  // world's sigmas; per satellite ones are read where used).
  std::array<double, 2> gradient_now_m_{};  ///< G_N, G_E this epoch (mean + daily cycle + process), m
  double iono_factor_ = 1.0;                ///< 1 + the common relative iono error
  double zwd_pert_m_ = 0.0;                 ///< zenith wet delay perturbation, m
  // Multipath per satellite (by SatId::index()), stepped when the satellite
  // is received, over the time since it last was.
  // Per band (index band, then SatId::index()).
  template <class T> using PerBand = std::array<std::array<T, kNumSats>, kNumBands>;
  PerBand<double> multipath_unit_{};         ///< unit multipath Gauss–Markov state
  PerBand<time::GpsTime> multipath_t_{};     ///< when it was last stepped
  PerBand<bool> multipath_started_{};
  // Residuals of the SBAS corrections per satellite (unit Gauss–Markov:
  // orbit/clock, ionosphere), stepped when the satellite is received.
  const SbasService* sbas_service_ = nullptr;  ///< the service whose area holds the antenna this epoch
  std::array<std::array<double, kNumSats>, 2> sbas_unit_{};
  std::array<time::GpsTime, kNumSats> sbas_t_{};
  std::array<bool, kNumSats> sbas_started_{};
  uint64_t epoch_ = 0;          ///< step() calls so far (random-stream counter)
  bool started_ = false;
  time::GpsTime t_prev_;
  double dt_s_ = 0.0;           ///< time since the previous step, s (0 at the first)
  // Sky stage.
  SystemSet tracked_ = SystemSet::all();            ///< set_tracked_systems()
  std::array<SatId, kNumSats> sats_{};              ///< the sky's satellites of this world's systems, in SatId order
  int n_sats_ = 0;
  const SharedSky* sats_of_ = nullptr;              ///< the sky sats_ was taken from, at sats_revision_
  long sats_revision_ = -1;
  std::array<SkySat, kNumSats> sky_{};
  std::array<const orbit::Ephemeris*, kNumSats> eph_{};
  std::array<SatId, kMaxSatsInView> in_sky_{};      ///< satellites above the horizon this epoch, in SatId order
  int n_in_sky_ = 0;
  std::array<SatId, kMaxSatsInView> above_{};       ///< satellites above the mask this epoch
  int n_above_ = 0;
  // Propagation stage.
  AtmospherePropagation atmosphere_;
  atmosphere::SlowTermCache<kSlowTermCount> cache_;
  Ecef cache_pos_m_;                                ///< receiver position the cache belongs to
  double cache_height_m_ = 0.0;
  bool cache_pos_valid_ = false;
  long atmosphere_evaluations_ = 0;
  std::array<PathEffects, kNumSats> path_{};
  // Scene (optional part of the propagation stage).
  std::unique_ptr<scene::Propagator> propagator_;
  std::unique_ptr<geo::LocalFrame> scene_frame_;
  std::array<scene::SatQuery, kMaxSatsInView> scene_query_{};
  std::array<scene::SatPath, kMaxSatsInView> scene_out_{};
  std::array<scene::SatPath, kNumSats> scene_path_{};  ///< per satellite, this epoch
  // Signal stage.
  signal::LinkBudgetModel link_;
  std::array<double, kNumSats> cn0_dbhz_{};
  // Carrier (observables stage).
  PerBand<CarrierTrack> carrier_{};
  PerBand<bool> carrier_seen_{};  ///< received this epoch
};

}  // namespace gnssemu::world

#pragma once
// Receiver: one GNSS receiver. step() turns vehicle truth at an epoch into
// the Fix a real receiver would report. Pure and deterministic for a seed;
// no exceptions and no allocation on step() after construction.
#include <array>
#include <cstdint>

#include <memory>

#include "core/common/vec3.hpp"
#include "core/geo/local_frame.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/receiver/error_processes.hpp"
#include "core/receiver/fix.hpp"
#include "core/receiver/random.hpp"
#include "core/receiver/receiver_config.hpp"
#include "core/receiver/sky.hpp"
#include "core/receiver/solver.hpp"
#include "core/scene/propagator.hpp"

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

  /// Buildings: the scene (built in the ENU frame of origin) decides per
  /// satellite direct / reflected (extra delay in the pseudorange, loss in
  /// C/N0) / not received. scene must outlive the receiver. Setup only
  /// (allocates); throws gnssemu::Error on a bad search config.
  void attach_scene(const scene::Scene& scene, const Lla& origin, const scene::SearchConfig& search);
  /// The scene stage of the last epoch (null without a scene).
  const scene::Propagator* propagator() const noexcept { return propagator_.get(); }

  /// World truth of the receiver oscillator at the last epoch (for error
  /// analysis; the solver never reads it).
  double true_clock_bias_s() const noexcept { return clock_.bias_s(); }
  double true_clock_drift_s_s() const noexcept { return clock_.drift_s_s(); }

private:
  void advance_world(const time::GpsTime& t) noexcept;
  void no_fix_epoch() noexcept;
  void fill_solution() noexcept;

  const orbit::EphemerisStore& store_;
  ReceiverConfig config_;
  Fix fix_;

  // World side.
  CounterRng rng_;
  ReceiverClock clock_;
  std::array<double, kMaxGpsPrn> orbit_clock_m_{};  ///< Gauss–Markov state per PRN, m
  /// Extra propagation delay the world adds per PRN (atmosphere, scene), m.
  /// Zero until the atmosphere module fills it.
  std::array<double, kMaxGpsPrn> world_delay_m_{};
  std::array<SkySat, kMaxGpsPrn> sky_{};
  std::array<bool, kMaxGpsPrn> in_sky_{};
  uint64_t epoch_ = 0;          ///< step() calls so far (random-stream counter)
  bool started_ = false;
  time::GpsTime t_prev_;

  // Scene stage (optional).
  std::unique_ptr<scene::Propagator> propagator_;
  std::unique_ptr<geo::LocalFrame> scene_frame_;
  std::array<scene::SatQuery, kMaxGpsPrn> scene_query_{};
  std::array<scene::SatPath, kMaxGpsPrn> scene_out_{};
  std::array<scene::SatPath, kMaxGpsPrn> scene_path_{};  ///< per PRN, this epoch

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

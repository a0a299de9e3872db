// SPDX-License-Identifier: Apache-2.0
#pragma once
// SkyErrors: the error processes every receiver under one sky sees alike —
// each satellite's broadcast orbit/clock residual and ionospheric TEC
// perturbation, and the regional atmosphere's common relative ionospheric
// error, tropospheric gradient and zenith wet delay perturbation. Each is a
// unit-variance first-order Gauss–Markov process (a receiver scales it by
// its own sigma), laid on a fixed time grid from the sky's first epoch, so
// that a value is a pure function of (seed, process, satellite, time): which
// receivers read, how often, and which satellites they see change nothing.
//
// The grid is GPS time's own: fine node k is second k since the GPS epoch,
// coarse node n is fine node n * kSkyFinePerCoarse. A coarse node's value is
// the exact Gauss–Markov chain walked from a stationary draw at the start of
// the block before its own (blocks of ~20 correlation times), so that it is
// a function of the node alone and not of when the sky started; the walk
// from the next block's start, kept beside it, takes over at that block
// (they differ there by e^-20 of the process's sigma, from the forgotten
// start). Fine nodes every kSkyFineStep_s between two coarse nodes are drawn
// from the process conditioned on both (the Gauss–Markov bridge: Gaussian
// conditioning of the exact discretisation, Brown & Hwang, Introduction to
// Random Signals and Applied Kalman Filtering, 4th ed., §2.9), only for
// satellites an antenna sees: a rising satellite catches up from its last
// coarse node in at most kSkyFinePerCoarse steps. A value between fine
// nodes is their linear interpolation. Never throws, never allocates.
//
// A process slower than kSkySmoothTaus coarse steps (the broadcast
// orbit/clock residual and the TEC perturbation, tau 1800 s) takes the
// bridge's mean without its draw, scaled back to unit variance: such errors
// drift over hours and are smooth over seconds, where a first-order path
// moves ~3 % of its sigma each second (4 cm at the orbit/clock's 1.2 m) and
// would not cancel against a 1-s-old RTK base (docs/models.md). Faster
// processes keep the bridge's draws: their roughness is their own.
#include <array>
#include <cstdint>
#include <span>

#include "core/common/sat_id.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/random.hpp"

namespace gnssemu::world {

struct WorldConfig;

/// The shared processes: the first two are one per satellite.
enum class SkyProcess : int {
  kOrbitClock = 0,  ///< broadcast orbit/clock residual (per satellite)
  kIono,            ///< vertical TEC perturbation along the line of sight (per satellite)
  kIonoScale,       ///< common relative ionospheric error
  kGradientNorth,   ///< azimuthal tropospheric gradient, north component
  kGradientEast,    ///< east component
  kZwd,             ///< zenith wet delay perturbation
};
inline constexpr int kNumSkyProcesses = 6;
inline constexpr int kNumSatProcesses = 2;

/// Fine grid step, s, and fine steps per coarse step.
inline constexpr double kSkyFineStep_s = 1.0;
inline constexpr int kSkyFinePerCoarse = 64;
inline constexpr double kSkyCoarseStep_s = kSkyFineStep_s * kSkyFinePerCoarse;
/// Correlation times per block (the start's weight e^-20 at the block's
/// end), and the most coarse nodes in a block (~73 h: a cold start walks at
/// most twice as many per satellite).
inline constexpr double kSkyBlockTaus = 20.0;
inline constexpr int64_t kSkyMaxBlock = 4096;
/// Processes with tau at least this many coarse steps are smooth between nodes.
inline constexpr double kSkySmoothTaus = 8.0;

struct SkyErrorsConfig {
  /// Seed of the sky's draws: the run's top-level seed, shared by every
  /// receiver under the sky whatever its own seed.
  uint64_t seed = 1;
  /// Correlation time of each process (SkyProcess order), s; 0: off (its value stays 0).
  std::array<double, kNumSkyProcesses> tau_s{1800.0, 1800.0, 0.0, 0.0, 0.0, 3600.0};
};

/// The sky processes c uses (on where c's sigma is > 0 and its stage on),
/// with their correlation times, seeded by c's sky seed.
SkyErrorsConfig sky_errors_config(const WorldConfig& c) noexcept;

class SkyErrors {
public:
  explicit SkyErrors(const SkyErrorsConfig& config) noexcept;

  /// Move to time t (GPS): the coarse chains of every satellite of sats and
  /// the regional processes. sats_revision changes whenever sats does (the
  /// chains are walked only then or at a new coarse node). Time going back
  /// holds every value.
  void begin(const time::GpsTime& t, std::span<const SatId> sats, long sats_revision) noexcept;
  /// Bring sat's processes to the time of the last begin() (its fine nodes).
  void step(SatId sat) noexcept;

  /// Unit value of a per-satellite process of sat at the last step(sat).
  double value(SkyProcess p, SatId sat) const noexcept {
    return sat_[static_cast<std::size_t>(p)][static_cast<std::size_t>(sat.index())].value;
  }
  /// Unit value of a regional process at the last begin().
  double value(SkyProcess p) const noexcept { return regional_[static_cast<std::size_t>(p)].value; }

  const SkyErrorsConfig& config() const noexcept { return config_; }

private:
  /// One process on the grid: coarse nodes c0 (index coarse) and c1 (the
  /// next) of the walk from the block before coarse's, next1 node coarse + 1
  /// of the walk from coarse's block's start, fine nodes f0 (index fine in
  /// the coarse step) and f1 (the next).
  struct Grid {
    bool started = false;
    int64_t coarse = 0;
    double c0 = 0.0, c1 = 0.0, next1 = 0.0;
    int fine = -1;  ///< -1: no fine node yet in this coarse step
    double f0 = 0.0, f1 = 0.0;
    double value = 0.0;
  };
  /// Constants of one process's steps.
  struct Coefficients {
    bool on = false;
    double tau_s = 0.0;
    double phi_coarse = 0.0, sd_coarse = 0.0;
    int64_t block = 1;  ///< coarse nodes per block
    /// Fine node j+1 = a[j] f_j + b[j] c1 + sd[j] w.
    std::array<double, kSkyFinePerCoarse> a{}, b{}, sd{};
    /// Smooth: no draws, fine node j is the bridge's mean times scale[j].
    bool smooth = false;
    std::array<double, kSkyFinePerCoarse + 1> scale{};
  };

  void coarse_to(Grid& g, const Coefficients& k, uint64_t stream) const noexcept;
  /// The coarse chain's value at node n + 1 from its value x at node n.
  double coarse_next(double x, const Coefficients& k, uint64_t stream, int64_t n) const noexcept;
  void fine_to(Grid& g, const Coefficients& k, uint64_t stream) const noexcept;

  SkyErrorsConfig config_;
  CounterRng rng_;
  std::array<Coefficients, kNumSkyProcesses> coef_{};
  bool started_ = false;
  int64_t node_ = 0;      ///< fine node (GPS second) at or before the current time
  double frac_ = 0.0;     ///< position of the current time between node_ and node_ + 1, [0, 1)
  int64_t chains_at_ = -1;    ///< coarse node the satellites' chains were last brought to
  long chains_revision_ = 0;  ///< of the satellite list then
  std::array<std::array<Grid, kNumSats>, kNumSatProcesses> sat_{};
  std::array<Grid, kNumSkyProcesses> regional_{};  ///< the regional ones (index >= kNumSatProcesses)
};

}  // namespace gnssemu::world

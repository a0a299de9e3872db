// SPDX-License-Identifier: Apache-2.0
#pragma once
// SharedSky: what every receiver sees the same at one epoch — each
// satellite's broadcast orbit and clock (position, velocity, acceleration,
// clock, clock drift) at the epoch's time, for the satellites of the
// configured systems. The broadcast model is evaluated in full only at
// nodes kSkyNodeSpacing_s apart on the GPS-time grid; an epoch between two
// nodes takes the cubic Hermite through their positions and velocities
// (clock: bias and drift): < 0.5 um from the full evaluation for the
// Keplerian systems and < 7 um for GLONASS (its RK4 output), < 1e-18 s in
// clock (tests/unit/world/test_shared_sky.cpp), the same whenever the run
// started. Light time (~65-90 ms) and a
// receiver's transmit time are short Taylor steps from it (second order in
// position, first in velocity and clock: < 1e-7 m over 80 ms for every
// system, tests/unit/world/test_shared_sky.cpp). Owned outside the worlds
// that read it: one per epoch serves every receiver of a fleet, each of
// which keeps what depends on its antenna (geometry, blockage, its own
// noise, multipath and clock). The error processes common to the sky
// (satellite orbit/clock residuals, atmosphere: SkyErrors) step with it.
// update() never throws and never allocates.
#include <array>
#include <cstdint>
#include <span>

#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/sky/sky_errors.hpp"

namespace gnssemu::world {

/// Longest Taylor step from an evaluation, s; farther the orbit is evaluated
/// in full (jerk dt^3 / 6 at 1 s: ~1.5e-5 m for GPS).
inline constexpr double kMaxTaylorStep_s = 1.0;

/// Spacing of the sky's full broadcast evaluations, s (divides a week).
/// The cubic Hermite's error is ~H^4 / 384 |x| with |x| ~ n^4 r
/// ~1.2e-8 m/s^4 for a GNSS orbit: ~3e-7 m at 10 s.
inline constexpr double kSkyNodeSpacing_s = 10.0;

/// One satellite's broadcast state at an evaluation time.
struct SkyState {
  const orbit::Ephemeris* eph = nullptr;  ///< the set selected at the sky's epoch; null: none usable
  time::GpsTime t;                        ///< when pos/vel/acc/clock were evaluated (GPS)
  Ecef pos_m;                             ///< ECEF of t, m
  Ecef vel_m_s;                           ///< m/s
  Ecef acc_m_s2;                          ///< m/s^2 (orbit::ecef_acceleration_m_s2)
  double clk_bias_s = 0.0;                ///< relativity included, TGD excluded, s
  double clk_drift_s_s = 0.0;             ///< s/s
  /// Evaluated at the sky's epoch (false: a culled satellite's older
  /// evaluation, good only for the horizon test).
  bool current = false;
};

/// The state dt_s after s.t by Taylor steps (second order in position,
/// first in velocity and clock).
orbit::SatState taylor_state(const SkyState& s, double dt_s) noexcept;

class SharedSky {
public:
  /// store must outlive the sky (it may be replaced in place between
  /// epochs: a changed fingerprint rebuilds the satellite list). systems:
  /// the satellites evaluated (the union of every receiver's systems).
  /// errors: the shared error processes (sky_errors_config() of the run's
  /// world config; the default is a default WorldConfig's).
  SharedSky(const orbit::EphemerisStore& store, SystemSet systems, const SkyErrorsConfig& errors = {}) noexcept;

  /// Evaluate the sky at epoch t (GPS). antennas_m: the ECEF positions of
  /// every receiver that will read this epoch; a satellite more than ~1°
  /// below every one's horizon is not evaluated (its older evaluation,
  /// refreshed every couple of minutes, tells). Empty: every satellite.
  /// The shared error processes move to t, their fine steps for the
  /// satellites evaluated. needed: the systems some reader tracks (a world's
  /// own sky: its receiver's CFG-GNSS); the others' satellites are left
  /// unevaluated as culled ones are.
  void update(const time::GpsTime& t, std::span<const Ecef> antennas_m = {},
              SystemSet needed = SystemSet::all()) noexcept;

  time::GpsTime t() const noexcept { return t_; }
  SystemSet systems() const noexcept { return systems_; }
  /// The satellites of the systems with sets in the store, in SatId order.
  std::span<const SatId> sats() const noexcept { return {sats_.data(), static_cast<std::size_t>(n_sats_)}; }
  const SkyState& state(SatId sat) const noexcept { return state_[static_cast<std::size_t>(sat.index())]; }

  /// The broadcast state of eph's satellite at t_eval: a Taylor step from
  /// this epoch's evaluation when eph is the set it used and t_eval is
  /// within kMaxTaylorStep_s, else eph evaluated in full.
  orbit::SatState state_at(const orbit::Ephemeris& eph, const time::GpsTime& t_eval) const noexcept;

  /// The shared error processes at the epoch (per satellite: of the
  /// satellites evaluated at it).
  const SkyErrors& errors() const noexcept { return errors_; }

  /// Changes whenever the satellite list is rebuilt (a reader's copy of it is stale).
  long revision() const noexcept { return revision_; }
  /// Full orbit evaluations (nodes) so far (for benchmarks).
  long evaluations() const noexcept { return evaluations_; }

private:
  /// A full evaluation of one set at a grid time.
  struct Node {
    const orbit::Ephemeris* eph = nullptr;
    time::GpsTime toe;  ///< of eph when evaluated (a set replaced at the same address differs)
    time::GpsTime t;
    Ecef pos_m, vel_m_s, acc_m_s2;
    double clk_bias_s = 0.0, clk_drift_s_s = 0.0;
    bool of(const orbit::Ephemeris& e, const time::GpsTime& at) const noexcept {
      return eph == &e && toe == e.toe && t == at;
    }
  };

  void rebuild() noexcept;
  Node evaluate(SatId sat, const orbit::Ephemeris& eph, const time::GpsTime& t) noexcept;
  /// ta: the grid node at or before t (t - fmod(tow, H), once per epoch).
  void interpolate(SatId sat, const orbit::Ephemeris& eph, const time::GpsTime& t, const time::GpsTime& ta) noexcept;

  const orbit::EphemerisStore& store_;
  SystemSet systems_;
  std::uint64_t fingerprint_ = 0;
  bool built_ = false;
  time::GpsTime t_;
  std::array<SatId, kNumSats> sats_{};
  int n_sats_ = 0;
  std::array<SkyState, kNumSats> state_{};
  std::array<Node, kNumSats> node_a_{}, node_b_{};  ///< the grid interval around the last epoch
  // The store's selection per satellite and the span [from, until) it holds for.
  std::array<const orbit::Ephemeris*, kNumSats> selected_{};
  std::array<time::GpsTime, kNumSats> selected_from_{}, selected_until_{};
  std::array<orbit::GlonassNode, kNumSats> glonass_{};
  long evaluations_ = 0;
  long revision_ = 0;
  SkyErrors errors_;
};

}  // namespace gnssemu::world

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Navigator: the receiver's filtered navigation (NavFilterType::kKalman).
// Starts the Kalman filter from a snapshot solution, then each epoch
// predicts with the dynamic model, updates with the pseudoranges and range
// rates the solver linearises at the prediction (gating outliers, following
// millisecond clock steps, a held height with three satellites), coasts on
// the prediction for a limited time without enough satellites, restarts from
// the snapshot when the two disagree (the antenna was moved), and applies
// static hold. Its output has the snapshot solver's form. No allocation.
#include <array>

#include "core/receiver/solution/dynamic_model.hpp"
#include "core/receiver/solution/nav_filter.hpp"
#include "core/receiver/solution/solver.hpp"

namespace gnssemu::receiver {

class Navigator {
public:
  /// cfg: filter settings; solver: the receiver's solver settings (range-rate
  /// sigma, held-height sigma).
  Navigator(const NavFilterConfig& cfg, const SolverConfig& solver) noexcept;

  void set_dynamic_model(DynamicModel m) noexcept { cfg_.dynamic_model = m; }
  /// CFG-NAV5 static hold: speed threshold (m/s, 0 off) and distance (m, 0: none).
  void set_static_hold(double speed_m_s, double max_dist_m) noexcept;
  const NavFilterConfig& config() const noexcept { return cfg_; }

  /// Forget the filter, the held height and the static hold (a restart).
  void reset() noexcept;

  /// One epoch dt_s (s) after the last: in holds the usable measurements,
  /// snapshot the solver's solution of them (type kNone when it failed).
  /// out receives the filtered solution (type kNone: no fix). Residuals and
  /// exclusions are indexed like in.meas.
  void step(double dt_s, const SolverInput& in, const SolverOutput& snapshot, Solver& solver, SolverOutput& out) noexcept;

  /// The last output came from the prediction alone (too few satellites):
  /// reported as FixType::kDeadReckoning.
  bool coasting() const noexcept { return coasting_; }
  /// Static hold froze the last output.
  bool holding() const noexcept { return holding_; }
  /// Epoch updates since the filter last (re)started from a snapshot (for tests).
  long updates() const noexcept { return updates_; }
  long restarts() const noexcept { return restarts_; }

private:
  void start_from(const SolverOutput& snapshot, SolverOutput& out) noexcept;
  /// out from the filter state: position, velocity, clock, ENU covariances.
  void fill_state(FixType type, SolverOutput& out) noexcept;
  void apply_static_hold(SolverOutput& out) noexcept;

  NavFilterConfig cfg_;
  double rate_sigma_m_s_;
  double height_sigma_m_;
  NavFilter kf_;
  std::array<MeasurementRow, kMaxSatsInView> rows_{};
  FixType last_type_ = FixType::kNone;
  double coast_s_ = 0.0;
  bool coasting_ = false;
  bool have_height_ = false;
  double held_height_m_ = 0.0;
  Dop last_dop_;
  /// Reported variances (E, N, U, clock) from the geometry at the last
  /// update, and the filter's own then: coasting grows from them.
  std::array<double, 4> floor_var_{};
  std::array<double, 4> kf_var_at_update_{};
  bool holding_ = false;
  Ecef hold_pos_m_;
  Lla hold_lla_;
  long updates_ = 0;
  long restarts_ = 0;
};

}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Carrier smoothing of code for one satellite (R. Hatch, "The synergism of
// GPS code and carrier measurements", 1982): the smoothed pseudorange follows
// the carrier's change from epoch to epoch and averages the code around it
// over a window, so the code's thermal noise and multipath shrink while the
// delays common to code and carrier pass through. Restarted when the carrier
// is not continuous; no allocation.
#include <algorithm>
#include <cmath>

namespace gnssemu::receiver {

class HatchFilter {
public:
  /// Code minus carrier jumping by more than this since the last epoch is an
  /// undetected slip or a new path: the filter restarts, m.
  static constexpr double kDivergenceJump_m = 30.0;

  /// The smoothed pseudorange (m) from this epoch's code_m and carrier_m (m,
  /// the phase times the wavelength), dt_s after the last update (s, > 0),
  /// averaging over window_s (s); restart: the carrier is not continuous
  /// since the last update (new lock, slip, gap).
  double update(double code_m, double carrier_m, double dt_s, double window_s, bool restart) noexcept {
    if (!restart && n_ > 0.0) {
      const double predicted_m = smoothed_m_ + (carrier_m - carrier_m_);
      restart = !(std::fabs(code_m - predicted_m) <= kDivergenceJump_m);
    }
    if (restart || n_ <= 0.0 || !(dt_s > 0.0)) {
      n_ = 1.0;
      smoothed_m_ = code_m;
    } else {
      n_ = std::min(n_ + 1.0, std::max(1.0, window_s / dt_s));
      smoothed_m_ = code_m / n_ + (n_ - 1.0) / n_ * (smoothed_m_ + (carrier_m - carrier_m_));
    }
    carrier_m_ = carrier_m;
    return smoothed_m_;
  }

  void reset() noexcept { n_ = 0.0; }
  /// Epochs averaged in the last output (1 right after a restart, 0 never updated).
  double epochs() const noexcept { return n_; }

private:
  double n_ = 0.0;
  double smoothed_m_ = 0.0;
  double carrier_m_ = 0.0;
};

}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Built-in demo: a circle around the configured origin, counter-clockwise
// seen from above, starting due east. Drives the receiver while no simulator sends.
#include "core/geo/local_frame.hpp"
#include "core/world/truth.hpp"

namespace gnssemu::daemon {

class DemoTrajectory {
public:
  /// radius_m (> 0), speed_m_s (>= 0), height_m above the origin.
  DemoTrajectory(const geo::LocalFrame& frame, double radius_m, double speed_m_s, double height_m) noexcept;

  /// ENU position (m) and velocity (m/s) elapsed_s after the demo began.
  Enu position_enu(double elapsed_s) const noexcept;
  Enu velocity_enu(double elapsed_s) const noexcept;
  /// Valid truth at GPS time t, elapsed_s (s) after the demo began.
  world::Truth truth(const time::GpsTime& t, double elapsed_s) const noexcept;

private:
  const geo::LocalFrame& frame_;
  double radius_m_;
  double omega_rad_s_;
  double height_m_;
};

}  // namespace gnssemu::daemon

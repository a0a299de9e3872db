// SPDX-License-Identifier: Apache-2.0
#include "daemon/truth/demo_trajectory.hpp"

#include <cmath>

namespace gnssemu::daemon {

DemoTrajectory::DemoTrajectory(const geo::LocalFrame& frame, double radius_m, double speed_m_s,
                               double height_m) noexcept
    : frame_(frame),
      radius_m_(radius_m),
      omega_rad_s_(radius_m > 0.0 ? speed_m_s / radius_m : 0.0),
      height_m_(height_m) {}

Enu DemoTrajectory::position_enu(double elapsed_s) const noexcept {
  const double a = omega_rad_s_ * elapsed_s;
  return Enu(radius_m_ * std::cos(a), radius_m_ * std::sin(a), height_m_);
}

Enu DemoTrajectory::velocity_enu(double elapsed_s) const noexcept {
  const double a = omega_rad_s_ * elapsed_s;
  const double v = radius_m_ * omega_rad_s_;
  return Enu(-v * std::sin(a), v * std::cos(a), 0.0);
}

world::Truth DemoTrajectory::truth(const time::GpsTime& t, double elapsed_s) const noexcept {
  world::Truth out;
  out.t = t;
  out.pos_m = frame_.to_ecef(position_enu(elapsed_s));
  out.vel_m_s = Ecef(frame_.vector_to_ecef(velocity_enu(elapsed_s)));
  out.valid = true;
  return out;
}

}  // namespace gnssemu::daemon

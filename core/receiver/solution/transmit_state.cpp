// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/solution/transmit_state.hpp"

#include "core/common/constants.hpp"

namespace gnssemu::receiver {

TransmitState transmit_state(const orbit::Ephemeris& eph, const time::GpsTime& t_rx_local,
                             double pseudorange_m) noexcept {
  return transmit_state(nullptr, eph, t_rx_local, pseudorange_m);
}

TransmitState transmit_state(const world::SharedSky* sky, const orbit::Ephemeris& eph,
                             const time::GpsTime& t_rx_local, double pseudorange_m) noexcept {
  const time::GpsTime t_sv = t_rx_local - pseudorange_m / kSpeedOfLight_m_s;
  TransmitState s;
  if (sky != nullptr) {
    const double dt0_s = sky->state_at(eph, t_sv).clk_bias_s - eph.tgd_s;
    s.t_tx = t_sv - dt0_s;
    s.state = sky->state_at(eph, s.t_tx);
    return s;
  }
  const double dt0_s = orbit::sat_state(eph, t_sv).clk_bias_s - eph.tgd_s;
  s.t_tx = t_sv - dt0_s;
  s.state = orbit::sat_state(eph, s.t_tx);
  return s;
}

}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/transmit_state.hpp"

#include "core/common/constants.hpp"

namespace gnssemu::receiver {

TransmitState transmit_state(const orbit::Ephemeris& eph, const time::GpsTime& t_rx_local,
                             double pseudorange_m) noexcept {
  const time::GpsTime t_sv = t_rx_local - pseudorange_m / kSpeedOfLight_m_s;
  const double dt0_s = orbit::sat_state(eph, t_sv).clk_bias_s - eph.tgd_s;
  TransmitState s;
  s.t_tx = t_sv - dt0_s;
  s.state = orbit::sat_state(eph, s.t_tx);
  return s;
}

}  // namespace gnssemu::receiver

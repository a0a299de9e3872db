// SPDX-License-Identifier: Apache-2.0
#pragma once
// The satellite at the time it sent a code measurement, as a receiver derives
// it from the pseudorange (IS-GPS-200 §20.3.3.3.3.1-2): the receiver's own
// solver and `gnssemu calibrate` on real observations use this one derivation.
#include "core/orbit/ephemeris.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/sky/shared_sky.hpp"

namespace gnssemu::receiver {

struct TransmitState {
  time::GpsTime t_tx;     ///< transmit time, GPS
  orbit::SatState state;  ///< the ephemeris at t_tx (ECEF frame of t_tx)
};

/// t_sv = t_rx_local - pseudorange_m / c, then t_tx = t_sv - (dt_sv - TGD)
/// with the broadcast clock at t_sv; one pass suffices (the clock changes by
/// < 1e-11 s over the correction). t_rx_local: receive time on the
/// receiver's clock; pseudorange_m: code pseudorange, m.
TransmitState transmit_state(const orbit::Ephemeris& eph, const time::GpsTime& t_rx_local,
                             double pseudorange_m) noexcept;
/// The same with the epoch's broadcast orbits from sky (SharedSky::state_at:
/// Taylor steps from its evaluation, or eph in full); sky null: as above.
TransmitState transmit_state(const world::SharedSky* sky, const orbit::Ephemeris& eph,
                             const time::GpsTime& t_rx_local, double pseudorange_m) noexcept;

}  // namespace gnssemu::receiver

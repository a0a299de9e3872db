// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu satpos`: broadcast satellite states at one GPS time.
#include <ostream>

#include "core/orbit/ephemeris_store.hpp"

namespace gnssemu::cli {

/// Writes `sat,prn,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,clk_bias_s,toe_tow_s,iode`
/// (sat: RINEX name, G05; prn: the system's PRN) for every satellite of
/// systems, in SatId order, with a healthy ephemeris valid at t (GPS system time), evaluated
/// at t itself. clk_bias_s includes the relativistic term, excludes TGD.
/// Positions to 0.1 mm, clock to 1e-15 s. Returns the number of rows.
int write_satpos(const orbit::EphemerisStore& store, const time::GpsTime& t, std::ostream& out,
                 SystemSet systems = SystemSet::all());

}  // namespace gnssemu::cli

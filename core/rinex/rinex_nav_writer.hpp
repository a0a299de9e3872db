// SPDX-License-Identifier: Apache-2.0
#pragma once
// RINEX 3.04 mixed navigation file writer: the header's broadcast
// ionosphere (GPSA/GPSB, BDSA/BDSB, GAL), time system corrections
// (GPUT, GLUT) and leap seconds, then one record per ephemeris — GPS,
// Galileo, BeiDou, QZSS Keplerian sets (Tables A6, A8, A14, A12), GLONASS
// state vectors (Table A10, 4 lines) and SBAS (Table A16) — in the layout
// orbit::read_rinex_nav reads back.
#include <ostream>

#include "core/orbit/nav_data.hpp"

namespace gnssemu::rinex {

/// Write nav's header parameters and every ephemeris of nav.ephemerides.
/// GLONASS epochs are UTC with nav.leap_seconds (else the built-in table),
/// BeiDou's BDT, the others GPST.
void write_nav(std::ostream& out, const orbit::NavData& nav);

}  // namespace gnssemu::rinex

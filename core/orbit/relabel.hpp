// SPDX-License-Identifier: Apache-2.0
#pragma once
// Broadcast data moved in time with the orbits' ECEF geometry unchanged:
// the satellites stand Δ later where they stood before (docs/models.md
// §Orbits for any date). gps-sdr-sim's -T moves toe/toc alone, which keeps
// the geometry only for whole weeks: IS-GPS-200 Table 20-IV refers Ω0 to the
// start of toe's week (Ω_k = Ω0 + (Ω̇ − ω̇e)·t_k − ω̇e·toe), so a shift that
// moves toe's time of week by d also turns the orbit by ω̇e·d; Ω0 takes it back.
#include "core/orbit/almanac.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/orbit/nav_data.hpp"

namespace gnssemu::orbit {

/// eph moved by shift_s (s, any finite value): toc, toe and the transmission
/// time move by shift_s; for the Keplerian systems Ω0 moves by
/// ω̇e·(toe'.tow − toe.tow) (the system's own ω̇e and week: BDT for
/// BeiDou); GLONASS and SBAS state vectors stay as they are (ECEF, and
/// their ECEF motion does not depend on the date). So
/// sat_state(result, t + shift_s) equals sat_state(eph, t) for every system
/// (positions to rounding, ~1e-8 m; clock and velocity alike).
Ephemeris relabel(const Ephemeris& eph, double shift_s) noexcept;

/// An almanac entry moved by shift_s, as relabel() for an ephemeris (toa
/// plays toe).
AlmanacEntry relabel(const AlmanacEntry& alm, double shift_s) noexcept;

/// Every ephemeris of nav moved by shift_s; the header's GPS-UTC reference
/// time moves too. The header's leap-second count is dropped: it belongs to
/// the old date, and the new date's count comes from the built-in table.
NavData relabel(const NavData& nav, double shift_s);

}  // namespace gnssemu::orbit

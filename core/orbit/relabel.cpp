// SPDX-License-Identifier: Apache-2.0
#include "core/orbit/relabel.hpp"

#include <cmath>

#include "core/common/constants.hpp"

namespace gnssemu::orbit {

namespace {

/// Angle in (-pi, pi].
double wrap_pi(double a_rad) noexcept {
  const double w = std::remainder(a_rad, 2.0 * kPi);
  return w <= -kPi ? w + 2.0 * kPi : w;
}

/// Ω0 that keeps Ω_k for a reference time moved from old_tow_s to new_tow_s
/// (seconds of the system's week; IS-GPS-200 Table 20-IV: the −ω̇e·toe term
/// uses toe's time of week).
double moved_omega0(double omega0_rad, double omega_e_rad_s, double old_tow_s, double new_tow_s) noexcept {
  return wrap_pi(omega0_rad + omega_e_rad_s * (new_tow_s - old_tow_s));
}

}  // namespace

Ephemeris relabel(const Ephemeris& eph, double shift_s) noexcept {
  Ephemeris e = eph;
  e.toe = eph.toe + shift_s;
  e.toc = eph.toc + shift_s;
  // Keplerian sets: Ω0 takes back the Earth's turn between the old and the
  // new toe's time of week. GLONASS and SBAS states are ECEF at toe and
  // their motion in ECEF does not depend on the date (the ICD force model
  // is autonomous in the rotating frame, its luni-solar term is broadcast
  // as a constant), so moving toe alone keeps their geometry: no rotation.
  if (system_info(eph.sat.system).orbit == OrbitKind::kKepler) {
    e.omega0_rad = moved_omega0(eph.omega0_rad, system_info(eph.sat.system).omega_e_rad_s, toe_of_week_s(eph),
                                toe_of_week_s(e));
  }
  // Seconds from the start of toe's week: the same instant, shift_s later.
  if (e.transmit_known) e.transmit_tow_s = eph.transmit_tow_s + (e.toe.tow_s() - eph.toe.tow_s());
  return e;
}

AlmanacEntry relabel(const AlmanacEntry& alm, double shift_s) noexcept {
  AlmanacEntry a = alm;
  a.toa = alm.toa + shift_s;
  a.omega0_rad = moved_omega0(alm.omega0_rad, kOmegaEarth_rad_s, alm.toa.tow_s(), a.toa.tow_s());
  return a;
}

NavData relabel(const NavData& nav, double shift_s) {
  NavData out = nav;
  for (Ephemeris& e : out.ephemerides) e = relabel(e, shift_s);
  for (UtcParams* p : {&out.utc, &out.glonass_utc}) {
    if (!p->valid) continue;
    const time::GpsTime tot = time::GpsTime(p->wnt, p->tot_s) + shift_s;
    p->wnt = tot.week();
    p->tot_s = tot.tow_s();
  }
  out.leap_seconds.reset();
  return out;
}

}  // namespace gnssemu::orbit

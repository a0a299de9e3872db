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

/// Ω0 that keeps Ω_k for a reference time moved from old_ref to new_ref
/// (IS-GPS-200 Table 20-IV: the −ω̇e·toe term uses toe's time of week).
double moved_omega0(double omega0_rad, const time::GpsTime& old_ref, const time::GpsTime& new_ref) noexcept {
  return wrap_pi(omega0_rad + kOmegaEarth_rad_s * (new_ref.tow_s() - old_ref.tow_s()));
}

}  // namespace

Ephemeris relabel(const Ephemeris& eph, double shift_s) noexcept {
  Ephemeris e = eph;
  e.toe = eph.toe + shift_s;
  e.toc = eph.toc + shift_s;
  e.omega0_rad = moved_omega0(eph.omega0_rad, eph.toe, e.toe);
  // Seconds from the start of toe's week: the same instant, shift_s later.
  if (e.transmit_known) e.transmit_tow_s = eph.transmit_tow_s + (e.toe.tow_s() - eph.toe.tow_s());
  return e;
}

AlmanacEntry relabel(const AlmanacEntry& alm, double shift_s) noexcept {
  AlmanacEntry a = alm;
  a.toa = alm.toa + shift_s;
  a.omega0_rad = moved_omega0(alm.omega0_rad, alm.toa, a.toa);
  return a;
}

NavData relabel(const NavData& nav, double shift_s) {
  NavData out = nav;
  for (Ephemeris& e : out.ephemerides) e = relabel(e, shift_s);
  if (out.utc.valid) {
    const time::GpsTime tot = time::GpsTime(out.utc.wnt, out.utc.tot_s) + shift_s;
    out.utc.wnt = tot.week();
    out.utc.tot_s = tot.tow_s();
  }
  out.leap_seconds.reset();
  return out;
}

}  // namespace gnssemu::orbit

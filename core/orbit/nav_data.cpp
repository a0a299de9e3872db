// SPDX-License-Identifier: Apache-2.0
#include "core/orbit/nav_data.hpp"

namespace gnssemu::orbit {

NavData merge(const std::vector<NavData>& files) {
  if (files.size() == 1) return files.front();
  NavData out;
  bool leap_conflict = false;
  for (const NavData& f : files) {
    out.source += (out.source.empty() ? "" : " + ") + f.source;
    if (out.rinex_version == 0.0) out.rinex_version = f.rinex_version;
    out.ephemerides.insert(out.ephemerides.end(), f.ephemerides.begin(), f.ephemerides.end());
    if (!out.klobuchar.valid && f.klobuchar.valid) out.klobuchar = f.klobuchar;
    if (!out.utc.valid && f.utc.valid) out.utc = f.utc;
    if (!out.beidou_klobuchar.valid && f.beidou_klobuchar.valid) out.beidou_klobuchar = f.beidou_klobuchar;
    if (!out.galileo_nequick.valid && f.galileo_nequick.valid) out.galileo_nequick = f.galileo_nequick;
    if (!out.glonass_utc.valid && f.glonass_utc.valid) out.glonass_utc = f.glonass_utc;
    if (f.leap_seconds) {
      if (out.leap_seconds && *out.leap_seconds != *f.leap_seconds) leap_conflict = true;
      if (!out.leap_seconds) out.leap_seconds = f.leap_seconds;
    }
    out.skipped_records += f.skipped_records;
  }
  if (leap_conflict) out.leap_seconds.reset();
  return out;
}

SystemSet systems_of(const NavData& nav) noexcept {
  SystemSet s;
  for (const Ephemeris& e : nav.ephemerides) s = s.with(e.sat.system);
  return s;
}

}  // namespace gnssemu::orbit

// SPDX-License-Identifier: Apache-2.0
// orbit_continuity_bench: how far the orbits the emulator flies past its nav
// data are from the real ones, checked on data held out (docs/models.md
// §Orbits for any date). Prints Markdown; not a test.
//  1. each satellite's last broadcast set propagated (StoreOptions::
//     continue_after_data) against the real broadcast sets of later hours
//     or days it never saw: the first half of a day against the second half
//     (three daily files), and NYA1 2024-05-03 against 2024-05-06;
//  2. a YUMA almanac propagated 31 days against the almanac of that day;
//  3. the alternative not taken: the day chained onto itself (relabelled by
//     one solar or one sidereal day) and the jump at the seam;
//  4. relabel's own error (the geometry moved by whole days).
//   orbit_continuity_bench [data_dir]   (default: tests/data of the source tree)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/almanac.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/relabel.hpp"
#include "core/orbit/rinex_nav.hpp"

namespace {

using namespace gnssemu;
using namespace gnssemu::orbit;

struct Stats {
  std::vector<double> pos_km, el_deg, az_deg;
  int visible_disagree = 0, pairs = 0;
};

double pct(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

/// Look angles of sat from site (rad).
void look(const Ecef& sat, const Lla& site, double& az, double& el) {
  const Ecef rx = geo::ecef_from_lla(site);
  const Vec3 d = sat - rx;
  const double sl = std::sin(site.lat_rad), cl = std::cos(site.lat_rad);
  const double so = std::sin(site.lon_rad), co = std::cos(site.lon_rad);
  const double e = -so * d.x + co * d.y;
  const double n = -sl * co * d.x - sl * so * d.y + cl * d.z;
  const double u = cl * co * d.x + cl * so * d.y + sl * d.z;
  az = std::atan2(e, n);
  el = std::atan2(u, std::hypot(e, n));
}

/// Positions of `model` against `truth` at every step in [from, to].
void compare(const EphemerisStore& model, const EphemerisStore& truth, const time::GpsTime& from,
             const time::GpsTime& to, double step_s, const Lla& site, Stats& s) {
  for (time::GpsTime t = from; !(to < t); t += step_s) {
    for (int i = 0; i < kNumSats; ++i) {
      const SatId sat = SatId::from_index(i);
      const Ephemeris* a = model.select(sat, t);
      const Ephemeris* b = truth.select(sat, t);
      if (a == nullptr || b == nullptr) continue;
      const Ecef pa = sat_state(*a, t).pos_m, pb = sat_state(*b, t).pos_m;
      s.pos_km.push_back((pa - pb).norm() / 1e3);
      double aza, ela, azb, elb;
      look(pa, site, aza, ela);
      look(pb, site, azb, elb);
      if (elb > 0.0) {
        s.el_deg.push_back(std::fabs(ela - elb) * kRadToDeg);
        s.az_deg.push_back(std::fabs(std::remainder(aza - azb, 2.0 * kPi)) * kRadToDeg);
      }
      ++s.pairs;
      s.visible_disagree += (ela >= 5.0 * kDegToRad) != (elb >= 5.0 * kDegToRad);
    }
  }
}

void row(const char* what, const char* horizon, const Stats& s) {
  std::printf("| %s | %s | %.2f / %.2f / %.2f | %.3f / %.3f | %.3f / %.3f | %.2f %% |\n", what, horizon,
              pct(s.pos_km, 0.5), pct(s.pos_km, 0.95), pct(s.pos_km, 1.0), pct(s.el_deg, 0.5), pct(s.el_deg, 1.0),
              pct(s.az_deg, 0.5), pct(s.az_deg, 1.0), 100.0 * s.visible_disagree / std::max(1, s.pairs));
}

/// A daily file cut at noon: the morning's last sets propagated over the afternoon.
void half_day(const std::string& path, const char* name, const Lla& site) {
  const NavData d = read_rinex_nav(path);
  const EphemerisStore all(d.ephemerides);
  const time::GpsTime first = all.first_valid() + 7200.0;
  const time::GpsTime noon = first + 12.0 * 3600.0;
  std::vector<Ephemeris> am;
  for (const Ephemeris& e : d.ephemerides)
    if (e.toe < noon) am.push_back(e);
  const EphemerisStore model(am, StoreOptions{true});
  Stats s6, s12;
  // The hour after noon is still inside the last morning sets' window: start later.
  compare(model, all, noon + 2.0 * 3600.0, noon + 6.0 * 3600.0, 300.0, site, s6);
  compare(model, all, noon + 10.0 * 3600.0, noon + 12.0 * 3600.0, 300.0, site, s12);
  row(name, "2-6 h", s6);
  row(name, "10-12 h", s12);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string dir = argc > 1 ? argv[1] : std::string(GNSSEMU_SOURCE_DIR) + "/tests/data";
    const Lla paris{48.8738 * kDegToRad, 2.295 * kDegToRad, 100.0};
    const Lla nya1{78.93 * kDegToRad, 11.87 * kDegToRad, 80.0};

    std::printf("## 1. Last broadcast set propagated, against real sets held out\n\n");
    std::printf("| data | after the last set | position km (median / 95 %% / max) | elevation deg (median / max) | "
                "azimuth deg (median / max) | above/below 5 deg disagree |\n|---|---|---|---|---|---|\n");
    half_day(dir + "/nav/brdc0010.22n", "brdc0010.22n (2022-01-01), Paris", paris);
    half_day(dir + "/nav/NYA100NOR_S_20241240000_01D_GN.rnx", "NYA1 2024-05-03, NYA1", nya1);
    half_day(dir + "/nav/ab422100.18n", "AB42 2018-07-29, Paris", paris);
    {
      const NavData a = read_rinex_nav(dir + "/nav/NYA100NOR_S_20241240000_01D_GN.rnx");
      const NavData b = read_rinex_nav(dir + "/nav/NYA100NOR_S_20241270000_01D_GN.rnx");
      const EphemerisStore model(a.ephemerides, StoreOptions{true}), truth(b.ephemerides);
      Stats s;
      compare(model, truth, time::GpsTime::from_calendar({2024, 5, 6, 0, 0, 0.0}),
              time::GpsTime::from_calendar({2024, 5, 6, 23, 55, 0.0}), 300.0, nya1, s);
      row("NYA1 05-03 against 05-06, NYA1", "48-72 h", s);
      Stats p;
      compare(model, truth, time::GpsTime::from_calendar({2024, 5, 6, 0, 0, 0.0}),
              time::GpsTime::from_calendar({2024, 5, 6, 23, 55, 0.0}), 300.0, paris, p);
      row("NYA1 05-03 against 05-06, Paris", "48-72 h", p);
    }

    std::printf("\n## 2. YUMA almanac propagated, against the almanac of the later day\n\n");
    std::printf("| almanac | propagated | position km (median / 95 %% / max) | elevation deg (median / max) | "
                "azimuth deg (median / max) | above/below 5 deg disagree |\n|---|---|---|---|---|---|\n");
    {
      const std::vector<AlmanacEntry> early = read_yuma(dir + "/almanac/yuma_week862_toa319488.alm", 1886);
      const std::vector<AlmanacEntry> late = read_yuma(dir + "/almanac/yuma_week866_toa589824_20160331.alm", 1890);
      std::vector<Ephemeris> e, l;
      for (const AlmanacEntry& a : early) e.push_back(to_ephemeris(a));
      for (const AlmanacEntry& a : late) l.push_back(to_ephemeris(a));
      const EphemerisStore model(e, StoreOptions{true}), truth(l);
      const time::GpsTime toa = late.front().toa;
      Stats s;
      compare(model, truth, toa - 7200.0, toa + 7200.0, 300.0, paris, s);
      char horizon[64];
      std::snprintf(horizon, sizeof horizon, "%.1f days", (toa - early.front().toa) / kSecondsPerDay);
      row("2016-03-02 (week 862) against 2016-04-02 (week 866), Paris", horizon, s);
    }

    std::printf("\n## 3. Not taken: the day chained onto itself, the jump at the seam\n\n");
    std::printf("| chain step | position jump at the seam km (median / 95 %% / max) |\n|---|---|\n");
    {
      const NavData d = read_rinex_nav(dir + "/nav/brdc0010.22n");
      const EphemerisStore day(d.ephemerides);
      const time::GpsTime seam = time::GpsTime::from_calendar({2022, 1, 2, 0, 0, 0.0});
      for (const double step : {kSecondsPerDay, 86164.0905}) {
        std::vector<Ephemeris> next;
        for (const Ephemeris& e : d.ephemerides) next.push_back(relabel(e, step));
        const EphemerisStore chained(next);
        std::vector<double> jump;
        for (int i = 0; i < kNumSats; ++i) {
          const SatId sat = SatId::from_index(i);
          const Ephemeris* a = day.select(sat, seam);
          // The chained copy's earliest set (its toe 00:00 + step) at the seam.
          const Ephemeris* b = chained.select(sat, seam + 7200.0);
          if (a == nullptr || b == nullptr) continue;
          jump.push_back((sat_state(*a, seam).pos_m - sat_state(*b, seam).pos_m).norm() / 1e3);
        }
        std::printf("| %s (%.4f s) | %.0f / %.0f / %.0f |\n", step == kSecondsPerDay ? "solar day" : "sidereal day", step,
                    pct(jump, 0.5), pct(jump, 0.95), pct(jump, 1.0));
      }
    }

    std::printf("\n## 4. Relabel: brdc0010.22n moved +1788 days, every set over its 4 h window\n\n");
    {
      const NavData d = read_rinex_nav(dir + "/nav/brdc0010.22n");
      const double shift = 1788.0 * kSecondsPerDay;
      double worst_m = 0.0, worst_clk_s = 0.0;
      for (const Ephemeris& e : d.ephemerides) {
        const Ephemeris m = relabel(e, shift);
        for (double dt = -7200.0; dt <= 7200.0; dt += 60.0) {
          const SatState a = sat_state(e, e.toe + dt), b = sat_state(m, m.toe + dt);
          worst_m = std::max(worst_m, (a.pos_m - b.pos_m).norm());
          worst_clk_s = std::max(worst_clk_s, std::fabs(a.clk_bias_s - b.clk_bias_s));
        }
      }
      std::printf("largest position difference %.3g m, clock %.3g s (%zu sets)\n", worst_m, worst_clk_s,
                  d.ephemerides.size());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "orbit_continuity_bench: %s\n", e.what());
    return 1;
  }
}

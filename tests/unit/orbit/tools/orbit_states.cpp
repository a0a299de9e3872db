// SPDX-License-Identifier: Apache-2.0
// Satellite states of every satellite at given receive epochs, for the
// RTKLIB cross-check (tools/reference/check_against_rtklib.py). Not a unit
// test: a harness that prints what core/orbit computes.
//
// orbit_states NAV... -- WEEK:TOW_RX...
// For each receive epoch t_rx and every satellite with a set selected at
// t_rx (health ignored: RTKLIB computes unhealthy satellites' states too),
// the state at t_tx = t_rx - 0.075 s. One CSV line each:
// sat,rx_week,rx_tow_s,tx_week,tx_tow_s,toe_week,toe_tow_s,iode,x_m,y_m,z_m,clk_bias_s,clk_no_rel_s,fnav_first
// fnav_first = 1: a Galileo F/NAV set of the same toe and IODnav was
// transmitted before the I/NAV set used (RTKLIB 2.4.3's uniqeph() then keeps
// the F/NAV set alone and seleph() skips it: RTKLIB uses an older toe).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/common/error.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"

using namespace gnssemu;

int main(int argc, char** argv) {
  std::vector<std::string> navs;
  std::vector<time::GpsTime> epochs;
  bool after = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") {
      after = true;
    } else if (!after) {
      navs.push_back(a);
    } else {
      const auto colon = a.find(':');
      if (colon == std::string::npos) return 2;
      epochs.emplace_back(std::atoi(a.substr(0, colon).c_str()), std::atof(a.substr(colon + 1).c_str()));
    }
  }
  try {
    orbit::NavData nav = orbit::read_rinex_nav_files(navs);
    for (orbit::Ephemeris& e : nav.ephemerides) e.health = 0;
    const orbit::EphemerisStore store(nav.ephemerides);
    std::printf(
        "sat,rx_week,rx_tow_s,tx_week,tx_tow_s,toe_week,toe_tow_s,iode,x_m,y_m,z_m,clk_bias_s,clk_no_rel_s,fnav_first\n");
    for (const time::GpsTime& rx : epochs) {
      const time::GpsTime tx = rx - 0.075;
      for (int i = 0; i < kNumSats; ++i) {
        const SatId sat = SatId::from_index(i);
        const orbit::Ephemeris* e = store.select(sat, rx);
        if (e == nullptr) continue;
        const orbit::SatState s = orbit::sat_state(*e, tx);
        int fnav_first = 0;
        for (const orbit::Ephemeris& f : nav.ephemerides) {
          fnav_first |= f.sat == sat && f.toe == e->toe && f.iode == e->iode &&
                        (f.gal_data_sources & orbit::kGalClockE5a) != 0 && f.transmit_known &&
                        (!e->transmit_known || f.transmit_tow_s < e->transmit_tow_s);
        }
        std::printf("%s,%d,%.17g,%d,%.17g,%d,%.17g,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%d\n",
                    sat_name(sat).data(), rx.week(), rx.tow_s(), tx.week(), tx.tow_s(), e->toe.week(),
                    e->toe.tow_s(), e->iode, s.pos_m.x, s.pos_m.y, s.pos_m.z, s.clk_bias_s,
                    s.clk_bias_s - s.relativity_s, fnav_first);
      }
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}

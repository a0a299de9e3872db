// SPDX-License-Identifier: Apache-2.0
// RINEX 2/3 navigation files of every system (mixed, GLONASS, SBAS)
// through read_rinex_nav, then the ephemeris store and every ephemeris
// evaluated at its toe and 15 min later. Oracles: errors are
// gnssemu::Error naming the file (anything else escaping is a crash); an
// accepted ephemeris is finite and in range, and so is its satellite state.
#include <cmath>
#include <sstream>
#include <string>

#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace gnssemu;
using gnssemu::fuzz::expect;

const std::string kName = "fuzz.rnx";

bool finite_all(std::initializer_list<double> v) {
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

void check(const orbit::Ephemeris& e) {
  expect(e.sat.valid(), "ephemeris satellite in its system's range");
  expect(finite_all({e.toc.tow_s(), e.toe.tow_s(), e.af0_s, e.af1_s_s, e.af2_s_s2, e.crs_m, e.crc_m, e.cus_rad,
                     e.cuc_rad, e.cis_rad, e.cic_rad, e.delta_n_rad_s, e.m0_rad, e.e, e.sqrt_a_sqrtm, e.omega0_rad,
                     e.i0_rad, e.omega_rad, e.omega_dot_rad_s, e.idot_rad_s, e.tgd_s, e.sv_accuracy_m,
                     e.fit_interval_h, e.transmit_tow_s, e.tgd2_s, e.tau_n_s, e.gamma_n}),
         "ephemeris fields finite");
  expect(e.pos_m.finite() && e.vel_m_s.finite() && e.acc_m_s2.finite(), "state vector finite");
  expect(e.glo_channel >= kGlonassMinChannel && e.glo_channel <= kGlonassMaxChannel, "GLONASS channel in range");
  if (system_info(e.sat.system).orbit == OrbitKind::kKepler) {
    expect(e.e >= 0.0 && e.e < 1.0, "eccentricity in [0, 1)");
    expect(e.sqrt_a_sqrtm > 0.0, "sqrt(A) positive");
  }
  // Kepler systems: a bounded e and sqrt(A) keep the state finite at toe;
  // GLONASS/SBAS 15 min away: the integration over bounded inputs too.
  for (double dt : {0.0, 900.0}) {
    const orbit::SatState s = orbit::sat_state(e, e.toe + dt);
    expect(s.pos_m.finite() && s.vel_m_s.finite() && std::isfinite(s.clk_bias_s), "satellite state finite");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  orbit::NavData nav;
  try {
    nav = orbit::read_rinex_nav(in, kName);
  } catch (const Error& e) {
    fuzz::expect_names_file(e, kName);
    return 0;
  }
  for (const orbit::Ephemeris& e : nav.ephemerides) check(e);
  const orbit::EphemerisStore store(nav.ephemerides);
  if (store.size() == 0) return 0;
  const time::GpsTime t = nav.ephemerides.front().toe;
  for (int i = 0; i < kNumSats; ++i) {
    const SatId sat = SatId::from_index(i);
    if (const orbit::Ephemeris* e = store.select(sat, t)) expect(e->sat == sat, "store selects the asked satellite");
  }
  return 0;
}

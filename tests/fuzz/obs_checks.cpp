// SPDX-License-Identifier: Apache-2.0
#include "obs_checks.hpp"

#include <cmath>

#include "core/observation/rinex_obs.hpp"
#include "fuzz_support.hpp"

namespace gnssemu::fuzz {

void check_obs_file(const std::string& path) {
  observation::ObsData obs;
  try {
    obs = observation::read_rinex_obs(path);
  } catch (const Error& e) {
    expect_names_file(e, path);
    return;
  }
  if (obs.header.approx_pos_m) expect(obs.header.approx_pos_m->finite(), "approximate position finite");
  for (const observation::ObsEpoch& ep : obs.epochs) {
    expect(std::isfinite(ep.t.tow_s()) && ep.t.tow_s() >= 0.0 && ep.t.tow_s() < 604800.0, "epoch time in range");
    expect(ep.flag == 0 || ep.flag == 1, "epoch flag 0 or 1");
    expect(std::isfinite(ep.rcv_clock_offset_s), "receiver clock offset finite");
    for (const observation::SatObs& s : ep.sats) {
      expect(s.sat.valid(), "satellite in its system's range");
      expect(s.values.size() == obs.header.types_of(s.sat.system).size(), "one value per type of the system");
      for (const observation::ObsValue& v : s.values) {
        expect(!v.valid || std::isfinite(v.value), "valid value finite");
        // One digit each (RINEX 3.05 §5.7). The reader keeps an LLI of 8 or 9
        // as written although only bits 0-2 are defined.
        expect(v.lli >= 0 && v.lli <= 9 && v.ssi >= 0 && v.ssi <= 9, "LLI and SSI one digit");
      }
    }
  }
}

}  // namespace gnssemu::fuzz

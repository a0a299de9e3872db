// SPDX-License-Identifier: Apache-2.0
// RINEX 2/3 observation files (plain or gzip, as gnssemu spp and calibrate
// read them) through read_rinex_obs. Oracles: errors are gnssemu::Error
// naming the file; accepted epochs hold GPS PRNs 1..32, finite values and
// one-digit indicators.
#include <cmath>
#include <string>

#include "core/observation/rinex_obs.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace gnssemu;
using gnssemu::fuzz::expect;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A file, not a stream: the reader tells gzip from text by its magic.
  static fuzz::ScratchFile file(".rnx");
  const std::string& path = file.write({reinterpret_cast<const char*>(data), size});
  observation::ObsData obs;
  try {
    obs = observation::read_rinex_obs(path);
  } catch (const Error& e) {
    fuzz::expect_names_file(e, path);
    return 0;
  }
  const std::size_t types = obs.header.gps_types.size();
  if (obs.header.approx_pos_m) expect(obs.header.approx_pos_m->finite(), "approximate position finite");
  for (const observation::ObsEpoch& ep : obs.epochs) {
    expect(std::isfinite(ep.t.tow_s()) && ep.t.tow_s() >= 0.0 && ep.t.tow_s() < 604800.0, "epoch time in range");
    expect(ep.flag == 0 || ep.flag == 1, "epoch flag 0 or 1");
    expect(std::isfinite(ep.rcv_clock_offset_s), "receiver clock offset finite");
    for (const observation::SatObs& s : ep.sats) {
      expect(s.prn >= 1 && s.prn <= 32, "observation PRN 1..32");
      expect(s.values.size() <= types, "no more values than types");
      for (const observation::ObsValue& v : s.values) {
        expect(!v.valid || std::isfinite(v.value), "valid value finite");
        // One digit each (RINEX 3.05 §5.7). The reader keeps an LLI of 8 or 9
        // as written although only bits 0-2 are defined.
        expect(v.lli >= 0 && v.lli <= 9 && v.ssi >= 0 && v.ssi <= 9, "LLI and SSI one digit");
      }
    }
  }
  return 0;
}

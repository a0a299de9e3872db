// SPDX-License-Identifier: Apache-2.0
// RINEX 2/3 observation files (plain or gzip, as gnssemu spp and calibrate
// read them) through read_rinex_obs; oracles in obs_checks.hpp.
#include <string>

#include "fuzz_support.hpp"
#include "obs_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A file, not a stream: the reader tells gzip from text by its magic.
  static gnssemu::fuzz::ScratchFile file(".rnx");
  gnssemu::fuzz::check_obs_file(file.write({reinterpret_cast<const char*>(data), size}));
  return 0;
}

// SPDX-License-Identifier: Apache-2.0
// Compact RINEX (Hatanaka) 1.0/3.0 through read_rinex_obs; oracles in
// obs_checks.hpp. An input whose first line is not CRINEX VERS / TYPE gets
// a fixed CRINEX 3.0 header (G, R, E and I types) in front, so most runs
// spend their time in the epoch decoding rather than in the header.
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "obs_checks.hpp"

namespace {

constexpr std::string_view kHeader =
    "3.0                 COMPACT RINEX FORMAT                    CRINEX VERS   / TYPE\n"
    "fuzz                                    27-Nov-26 00:00     CRINEX PROG / DATE\n"
    "     3.05           OBSERVATION DATA    M                   RINEX VERSION / TYPE\n"
    "G    3 C1C L1C S1C                                          SYS / # / OBS TYPES\n"
    "R    2 C1C L1C                                              SYS / # / OBS TYPES\n"
    "E    1 C1X                                                  SYS / # / OBS TYPES\n"
    "I    1 C5A                                                  SYS / # / OBS TYPES\n"
    "                                                            END OF HEADER\n";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static gnssemu::fuzz::ScratchFile file(".crx");
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  const bool whole_file = in.size() >= 80 && in.substr(60, 20) == "CRINEX VERS   / TYPE";
  std::string text = whole_file ? std::string() : std::string(kHeader);
  text.append(in);
  gnssemu::fuzz::check_obs_file(file.write(text));
  return 0;
}

// SPDX-License-Identifier: Apache-2.0
// GPS almanacs: the same bytes through the YUMA and the SEM reader (each
// rejects the other's layout quickly). Oracles: errors are gnssemu::Error
// naming the file; accepted entries are finite and in range, and so is the
// satellite state at their time of applicability.
#include <cmath>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/orbit/almanac.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace gnssemu;
using gnssemu::fuzz::expect;

constexpr int kReferenceWeek = 2190;  // 2022-01-01, the shipped nav file's week

void check(const orbit::AlmanacEntry& a) {
  expect(a.sat.prn() >= 1 && a.sat.prn() <= system_size(GnssSystem::kGps), "almanac PRN 1..32");
  for (double x : {a.e, a.toa.tow_s(), a.i0_rad, a.omega_dot_rad_s, a.sqrt_a_sqrtm, a.omega0_rad, a.omega_rad,
                   a.m0_rad, a.af0_s, a.af1_s_s}) {
    expect(std::isfinite(x), "almanac fields finite");
  }
  expect(a.e >= 0.0 && a.e < 1.0, "almanac eccentricity in [0, 1)");
  expect(a.sqrt_a_sqrtm > 0.0, "almanac sqrt(A) positive");
  const orbit::SatState s = orbit::almanac_state(a, a.toa);
  expect(s.pos_m.finite() && s.vel_m_s.finite(), "almanac satellite state finite");
}

void read(std::vector<orbit::AlmanacEntry> (*reader)(const std::string&, int), const std::string& path) {
  try {
    for (const orbit::AlmanacEntry& a : reader(path, kReferenceWeek)) check(a);
  } catch (const Error& e) {
    fuzz::expect_names_file(e, path);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fuzz::ScratchFile file(".alm");
  const std::string& path = file.write({reinterpret_cast<const char*>(data), size});
  read(&orbit::read_yuma, path);
  read(&orbit::read_sem, path);
  return 0;
}

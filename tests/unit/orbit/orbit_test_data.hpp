// SPDX-License-Identifier: Apache-2.0
#pragma once
// The real nav data the orbit tests share, read once per test binary.
#include <string>

#include "core/orbit/rinex_nav.hpp"

namespace gnssemu::orbit::test {

inline const std::string kData = GNSSEMU_TEST_DATA;
/// The RINEX navigation files, with a trailing slash.
inline const std::string kNav = kData + "/nav/";

/// IGS brdc0010.22n (2022-01-01, 422 sets, 32 PRNs).
inline const NavData& brdc() {
  static const NavData d = read_rinex_nav(kData + "/nav/brdc0010.22n");
  return d;
}

}  // namespace gnssemu::orbit::test

#include <gtest/gtest.h>

#include <set>

#include "core/orbit/rinex_nav.hpp"

using namespace gnssemu;
using namespace gnssemu::orbit;

namespace {
const std::string kNav = std::string(GNSSEMU_TEST_DATA) + "/nav/";

std::size_t prn_count(const NavData& d) {
  std::set<int> s;
  for (const auto& e : d.ephemerides) s.insert(e.prn);
  return s.size();
}
}  // namespace

TEST(RinexNav, Counts) {
  for (auto [f, n, p, sk] : {std::tuple{"brdc0010.22n", 422, 32, 0}, {"ab422100.18n", 206, 31, 0},
                            {"NYA100NOR_S_20241240000_01D_GN.rnx", 215, 31, 0},
                            {"ELKO00USA_R_20182100000_01D_MN.rnx", 225, 32, 494 + 1293 + 106}}) {
    const NavData d = read_rinex_nav(kNav + f);
    EXPECT_EQ(d.ephemerides.size(), static_cast<std::size_t>(n)) << f;
    EXPECT_EQ(prn_count(d), static_cast<std::size_t>(p)) << f;
    EXPECT_EQ(d.skipped_records, sk) << f;
  }
}

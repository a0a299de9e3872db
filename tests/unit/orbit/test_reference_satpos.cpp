// sat_state and EphemerisStore::select against the independent Python
// reference (tools/reference/satpos_reference.py -> tests/data/reference/).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"

using namespace gnssemu;
using namespace gnssemu::orbit;

namespace {

const std::string kData = GNSSEMU_TEST_DATA;

struct Row {
  int prn, week, toe_week, iode;
  double tow_s, toe_tow_s;
  Vec3 pos, vel;
  double clk_s;
};

std::vector<Row> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "prn,week,tow_s,toe_week,toe_tow_s,iode,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,clk_bias_s");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ls(line);
    Row r{};
    ls >> r.prn >> r.week >> r.tow_s >> r.toe_week >> r.toe_tow_s >> r.iode >> r.pos.x >> r.pos.y >> r.pos.z >>
        r.vel.x >> r.vel.y >> r.vel.z >> r.clk_s;
    EXPECT_FALSE(ls.fail()) << path << ": " << line;
    rows.push_back(r);
  }
  return rows;
}

class ReferenceSatpos : public ::testing::TestWithParam<std::string> {};

TEST_P(ReferenceSatpos, MatchesIndependentImplementation) {
  const std::string nav = GetParam();
  const std::string csv = kData + "/reference/satpos_" + nav + ".csv";
  if (!std::filesystem::exists(csv)) GTEST_SKIP() << "reference file missing: " << csv;
  const NavData data = read_rinex_nav(kData + "/nav/" + nav);
  const EphemerisStore store(data.ephemerides);
  const std::vector<Row> rows = read_csv(csv);
  ASSERT_GT(rows.size(), 100u);

  double max_pos = 0, max_vel = 0, max_clk = 0;
  for (const Row& r : rows) {
    const time::GpsTime t(r.week, r.tow_s);
    const time::GpsTime toe(r.toe_week, r.toe_tow_s);
    const Ephemeris* eph = nullptr;
    for (const Ephemeris& e : data.ephemerides) {
      if (e.prn == r.prn && e.toe == toe && e.iode == r.iode && e.health == 0) eph = &e;
    }
    ASSERT_NE(eph, nullptr) << nav << ": no set PRN " << r.prn << " toe " << r.toe_week << "/" << r.toe_tow_s;
    const SatState s = sat_state(*eph, t);
    const double dp = (s.pos_m - r.pos).norm();
    const double dv = (s.vel_m_s - r.vel).norm();
    const double dc = std::fabs(s.clk_bias_s - r.clk_s);
    max_pos = std::max(max_pos, dp);
    max_vel = std::max(max_vel, dv);
    max_clk = std::max(max_clk, dc);
    EXPECT_LE(dp, 1e-3) << nav << " PRN " << r.prn << " t " << r.week << "/" << r.tow_s;
    EXPECT_LE(dv, 1e-4) << nav << " PRN " << r.prn << " t " << r.week << "/" << r.tow_s;
    EXPECT_LE(dc, 1e-12) << nav << " PRN " << r.prn << " t " << r.week << "/" << r.tow_s;

    const Ephemeris* sel = store.select(r.prn, t);
    ASSERT_NE(sel, nullptr) << nav << " PRN " << r.prn << " t " << r.week << "/" << r.tow_s;
    EXPECT_EQ(sel->toe, toe) << nav << " PRN " << r.prn << " t " << r.week << "/" << r.tow_s;
    EXPECT_EQ(sel->iode, r.iode) << nav << " PRN " << r.prn << " t " << r.week << "/" << r.tow_s;
  }
  std::printf("%s: %zu rows, max |dpos| %.3g m, |dvel| %.3g m/s, |dclk| %.3g s\n", nav.c_str(), rows.size(), max_pos,
              max_vel, max_clk);
}

INSTANTIATE_TEST_SUITE_P(NavFiles, ReferenceSatpos,
                         ::testing::Values("brdc0010.22n", "ab422100.18n", "NYA100NOR_S_20241240000_01D_GN.rnx",
                                           "ELKO00USA_R_20182100000_01D_MN.rnx"),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           std::string n = p.param.substr(0, p.param.find('.'));
                           return n.substr(0, 8);
                         });

}  // namespace

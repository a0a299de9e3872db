// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/orbit/almanac.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "orbit_test_data.hpp"

using namespace gnssemu;
using namespace gnssemu::orbit;
using test::kData;

namespace {
const std::string kYuma = kData + "/almanac/yuma_week862_toa319488.alm";
const std::string kSem = kData + "/almanac/sem_week862_toa319488.al3";

double wrap(double a) { return std::remainder(a, 2.0 * kPi); }

// An almanac made from a broadcast set: the Keplerian elements at toe, with
// the terms an almanac lacks (delta n, IDOT, harmonics, af2) dropped.
AlmanacEntry from_broadcast(const Ephemeris& e) {
  AlmanacEntry a;
  a.sat = e.sat;
  a.health = e.health;
  a.e = e.e;
  a.toa = e.toe;
  a.i0_rad = e.i0_rad;
  a.omega_dot_rad_s = e.omega_dot_rad_s;
  a.sqrt_a_sqrtm = e.sqrt_a_sqrtm;
  a.omega0_rad = e.omega0_rad;
  a.omega_rad = e.omega_rad;
  a.m0_rad = e.m0_rad;
  a.af0_s = e.af0_s + e.af1_s_s * (e.toe - e.toc);
  a.af1_s_s = e.af1_s_s;
  return a;
}
}  // namespace

TEST(Almanac, YumaFields) {
  const auto y = read_yuma(kYuma, 1886);
  ASSERT_EQ(y.size(), 31u);
  const AlmanacEntry& a = y.front();  // PRN 01 block, lines 1-14
  EXPECT_EQ(a.sat.prn(), 1);
  EXPECT_EQ(a.health, 0);
  EXPECT_DOUBLE_EQ(a.e, 0.5100727081E-002);
  EXPECT_EQ(a.toa, time::GpsTime(1886, 319488.0));  // week 862 mod 1024 -> 1886
  EXPECT_DOUBLE_EQ(a.i0_rad, 0.9639834877);
  EXPECT_DOUBLE_EQ(a.omega_dot_rad_s, -0.7817468486E-008);
  EXPECT_DOUBLE_EQ(a.sqrt_a_sqrtm, 5153.602539);
  EXPECT_DOUBLE_EQ(a.omega0_rad, -0.6558977526E+000);
  EXPECT_DOUBLE_EQ(a.omega_rad, 0.458945255);
  EXPECT_DOUBLE_EQ(a.m0_rad, 0.1430319489E+001);
  EXPECT_DOUBLE_EQ(a.af0_s, 0.1335144043E-004);
  EXPECT_DOUBLE_EQ(a.af1_s_s, 0.0);
  int unhealthy = 0;
  for (const auto& x : y) unhealthy += x.health != 0;
  EXPECT_EQ(unhealthy, 2);  // PRN 13 and 32: health 063

  const auto y2 = read_yuma(kData + "/almanac/yuma_week866_toa589824_20160331.alm", 1890);
  ASSERT_EQ(y2.size(), 31u);
  EXPECT_EQ(y2.front().toa, time::GpsTime(1890, 589824.0));
  // The same file resolved against a reference week 20 years later still
  // lands on the nearest candidate.
  EXPECT_EQ(read_yuma(kData + "/almanac/yuma_week866_toa589824_20160331.alm", 2900).front().toa.week(), 2914);
}

TEST(Almanac, SemFields) {
  const auto s = read_sem(kSem, 1886);
  ASSERT_EQ(s.size(), 31u);
  const AlmanacEntry& a = s.front();
  EXPECT_EQ(a.sat.prn(), 1);
  EXPECT_EQ(a.toa, time::GpsTime(1886, 319488.0));
  EXPECT_DOUBLE_EQ(a.e, 5.10072708129883E-03);
  EXPECT_DOUBLE_EQ(a.i0_rad, (0.30 + 6.84547424316406E-03) * kPiGps);
  EXPECT_DOUBLE_EQ(a.omega_dot_rad_s, -2.48837750405073E-09 * kPiGps);
  EXPECT_DOUBLE_EQ(a.sqrt_a_sqrtm, 5.15360253906250E+03);
  EXPECT_DOUBLE_EQ(a.af0_s, 1.33514404296875E-05);
  EXPECT_EQ(a.health, 0);
}

// The YUMA and SEM files are the same almanac (shared/data/README.md).
TEST(Almanac, YumaAndSemAgree) {
  const auto y = read_yuma(kYuma, 1886);
  const auto s = read_sem(kSem, 1886);
  ASSERT_EQ(y.size(), s.size());
  double worst_pos = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const AlmanacEntry& a = y[i];
    const AlmanacEntry& b = s[i];
    ASSERT_EQ(a.sat.prn(), b.sat.prn());
    EXPECT_EQ(a.health, b.health) << a.sat.prn();
    EXPECT_EQ(a.toa, b.toa);
    // YUMA prints 10 significant digits; SEM is the binary value.
    EXPECT_NEAR(a.e, b.e, 1e-10) << a.sat.prn();
    EXPECT_NEAR(a.sqrt_a_sqrtm, b.sqrt_a_sqrtm, 1e-6) << a.sat.prn();
    EXPECT_NEAR(a.i0_rad, b.i0_rad, 1e-9) << a.sat.prn();
    EXPECT_NEAR(a.omega_dot_rad_s, b.omega_dot_rad_s, 1e-17) << a.sat.prn();
    EXPECT_NEAR(wrap(a.omega0_rad - b.omega0_rad), 0.0, 1e-9) << a.sat.prn();
    EXPECT_NEAR(wrap(a.omega_rad - b.omega_rad), 0.0, 1e-9) << a.sat.prn();
    EXPECT_NEAR(wrap(a.m0_rad - b.m0_rad), 0.0, 1e-9) << a.sat.prn();
    EXPECT_NEAR(a.af0_s, b.af0_s, 1e-13) << a.sat.prn();
    EXPECT_NEAR(a.af1_s_s, b.af1_s_s, 1e-20) << a.sat.prn();
    for (double dt : {0.0, 86400.0, -86400.0}) {
      const double d = (almanac_state(a, a.toa + dt).pos_m - almanac_state(b, b.toa + dt).pos_m).norm();
      worst_pos = std::max(worst_pos, d);
      EXPECT_LT(d, 1.0) << a.sat.prn();
    }
  }
  std::printf("YUMA vs SEM: worst position difference %.3f m over +-1 day\n", worst_pos);
}

// Almanac propagation against the full broadcast model at the same time: the
// dropped terms (delta n, IDOT, harmonics) cost at most a few km over +-2 h.
TEST(Almanac, AgreesWithBroadcastEphemerisAtKmLevel) {
  const NavData d = read_rinex_nav(kData + "/nav/brdc0010.22n");
  double worst = 0;
  for (const Ephemeris& e : d.ephemerides) {
    const AlmanacEntry a = from_broadcast(e);
    for (double dt : {-7200.0, -3600.0, 0.0, 3600.0, 7200.0}) {
      const time::GpsTime t = e.toe + dt;
      const SatState sa = almanac_state(a, t);
      const SatState se = sat_state(e, t);
      const double dp = (sa.pos_m - se.pos_m).norm();
      worst = std::max(worst, dp);
      EXPECT_LT(dp, 5000.0) << "PRN " << e.sat.prn() << " dt " << dt;
      EXPECT_GT(dp, 0.0);
      // No relativistic term in the almanac clock (RTKLIB alm2pos).
      EXPECT_EQ(sa.relativity_s, 0.0);
      EXPECT_NEAR(sa.clk_bias_s, se.clk_bias_s - se.relativity_s, 1e-9);
    }
  }
  std::printf("almanac vs broadcast: worst %.0f m over +-2 h\n", worst);
}

TEST(Almanac, VelocityMatchesFiniteDifference) {
  for (const AlmanacEntry& a : read_yuma(kYuma, 1886)) {
    const time::GpsTime t = a.toa + 5000.0;
    const Vec3 fd = (almanac_state(a, t + 0.5).pos_m - almanac_state(a, t - 0.5).pos_m) / 1.0;
    EXPECT_LE((almanac_state(a, t).vel_m_s - fd).norm(), 1e-3) << a.sat.prn();
  }
}

TEST(Almanac, ToEphemeris) {
  const AlmanacEntry a = read_yuma(kYuma, 1886).front();
  const Ephemeris e = to_ephemeris(a);
  EXPECT_EQ(e.sat.prn(), 1);
  EXPECT_EQ(e.toe, a.toa);
  EXPECT_EQ(e.toc, a.toa);
  EXPECT_EQ(e.crs_m, 0.0);
  EXPECT_EQ(e.delta_n_rad_s, 0.0);
  EXPECT_EQ(e.idot_rad_s, 0.0);
  EXPECT_EQ(e.i0_rad, a.i0_rad);
  // Position at toa: radius within the orbit's apsides.
  const double r = almanac_state(a, a.toa).pos_m.norm();
  const double sma = a.sqrt_a_sqrtm * a.sqrt_a_sqrtm;
  EXPECT_GT(r, sma * (1 - a.e) - 1.0);
  EXPECT_LT(r, sma * (1 + a.e) + 1.0);
}

struct BadAlm {
  const char* file;
  bool sem;
  int line;
  const char* reason;
};

class AlmanacBad : public ::testing::TestWithParam<BadAlm> {};

TEST_P(AlmanacBad, ErrorNamesFileAndLine) {
  const BadAlm c = GetParam();
  const std::string path = kData + "/bad/" + c.file;
  try {
    if (c.sem) {
      (void)read_sem(path, 1886);
    } else {
      (void)read_yuma(path, 1886);
    }
    FAIL() << "no error for " << c.file;
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), c.line) << e.what();
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ":" + std::to_string(c.line) + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(c.reason), std::string::npos) << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(Files, AlmanacBad,
                         ::testing::Values(BadAlm{"yuma_missing_field.alm", false, 1, "Mean Anom"},
                                           BadAlm{"yuma_bad_number.alm", false, 4, "unparsable number"},
                                           // toa 1e300: refused before it becomes a GpsTime (UBSan found the overflow)
                                           BadAlm{"yuma_toa_1e300.alm", false, 5, "toa outside the week"},
                                           BadAlm{"sem_truncated.al3", true, 26, "truncated SEM file: 2 of 31"},
                                           BadAlm{"sem_bad_eccentricity.al3", true, 7, "eccentricity"}),
                         [](const ::testing::TestParamInfo<BadAlm>& p) {
                           std::string n = p.param.file;
                           return n.substr(0, n.find('.'));
                         });

TEST(Almanac, ReadAlmanacTellsYumaFromSem) {
  const std::vector<AlmanacEntry> y = read_almanac(kYuma, 1886), s = read_almanac(kSem, 1886);
  ASSERT_EQ(y.size(), s.size());
  EXPECT_EQ(y.front().sat, s.front().sat);
  EXPECT_EQ(y.front().toa, s.front().toa);
  EXPECT_EQ(y.size(), read_yuma(kYuma, 1886).size());
}

TEST(Almanac, MissingFile) {
  EXPECT_THROW((void)read_yuma(kData + "/almanac/none.alm", 1886), Error);
  EXPECT_THROW((void)read_sem(kData + "/almanac/none.al3", 1886), Error);
}

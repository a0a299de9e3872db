// SPDX-License-Identifier: Apache-2.0
// gnssemu sky and dop on real broadcast ephemerides: the transmit-time
// geometry solves the light-time equation, DOPs agree with an independent
// least-squares geometry computed here from the sky output.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "cli_test_util.hpp"
#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"

using namespace gnssemu;
using namespace gnssemu::cli::test;

namespace sky_dop_test {

namespace {

constexpr int kWeek = 2190;
constexpr double kTow = 521233.25;
const Lla kParis{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};

std::vector<std::string> site_args(const std::string& cmd, const std::string& mask) {
  return {cmd, "--nav", nav_path("brdc0010.22n"), "--week", std::to_string(kWeek), "--tow", "521233.25",
          "--lat", "48.8738", "--lon", "2.2950", "--height", "100", "--mask", mask};
}

const orbit::EphemerisStore& store() {
  static const orbit::EphemerisStore s(orbit::read_rinex_nav(nav_path("brdc0010.22n")).ephemerides);
  return s;
}

/// Inverse of a 4x4 matrix by Gauss-Jordan with partial pivoting.
std::array<std::array<double, 4>, 4> inverse4(std::array<std::array<double, 4>, 4> a) {
  std::array<std::array<double, 4>, 4> inv{};
  for (int i = 0; i < 4; ++i) inv[i][i] = 1.0;
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r) {
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    }
    std::swap(a[c], a[p]);
    std::swap(inv[c], inv[p]);
    const double d = a[c][c];
    for (int k = 0; k < 4; ++k) {
      a[c][k] /= d;
      inv[c][k] /= d;
    }
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = a[r][c];
      for (int k = 0; k < 4; ++k) {
        a[r][k] -= f * a[c][k];
        inv[r][k] -= f * inv[c][k];
      }
    }
  }
  return inv;
}

}  // namespace

TEST(Sky, SolvesTheLightTimeEquationWithSagnac) {
  const CliResult r = run(site_args("sky", "5"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
            "sat,prn,az_deg,el_deg,range_m,iono_klobuchar_m,tropo_zhd_m,nmf_hydro,nmf_wet,atten_db,cn0_dbhz");
  const Csv sky = parse_csv(r.out);
  ASSERT_GE(sky.rows.size(), 6u);
  const Ecef rx = geo::ecef_from_lla(kParis);
  const time::GpsTime t(kWeek, kTow);
  int moved_over_10m = 0;
  for (std::size_t i = 0; i < sky.rows.size(); ++i) {
    const int prn = std::stoi(sky.cell(i, "prn"));
    const double az = sky.num(i, "az_deg"), el = sky.num(i, "el_deg"), range = sky.num(i, "range_m");
    EXPECT_GE(el, 5.0);
    EXPECT_LE(el, 90.0);
    EXPECT_GE(az, 0.0);
    EXPECT_LT(az, 360.0);
    EXPECT_GT(range, 19.5e6);  // 20 180 km at zenith, 25 230 km at 5 deg (gps-orbits.md §4)
    EXPECT_LT(range, 26.0e6);
    // Satellite at t - range/c, rotated into the receive-time frame by the
    // Earth's rotation during the flight, lies exactly `range` away.
    const orbit::Ephemeris* eph = store().select(SatId::gps(prn), t);
    ASSERT_NE(eph, nullptr);
    const double tau_s = range / kSpeedOfLight_m_s;
    const Ecef s = orbit::sat_state(*eph, t - tau_s).pos_m;
    const double th = kOmegaEarth_rad_s * tau_s;
    const Ecef s_rot(std::cos(th) * s.x + std::sin(th) * s.y, -std::sin(th) * s.x + std::cos(th) * s.y, s.z);
    const geo::LookAngles la = geo::look_angles(rx, kParis, s_rot);
    EXPECT_NEAR(la.range_m, range, 1e-3) << prn;
    EXPECT_NEAR(la.el_rad * kRadToDeg, el, 2e-6) << prn;
    EXPECT_NEAR(la.az_rad * kRadToDeg, az, 2e-6 / std::cos(el * kDegToRad)) << prn;
    // Without light time and Sagnac the range is tens of metres off.
    const geo::LookAngles naive = geo::look_angles(rx, kParis, orbit::sat_state(*eph, t).pos_m);
    EXPECT_NEAR(naive.el_rad * kRadToDeg, el, 0.01) << prn;
    EXPECT_LT(std::fabs(naive.range_m - range), 200.0) << prn;
    if (std::fabs(naive.range_m - range) > 10.0) ++moved_over_10m;
  }
  EXPECT_GT(moved_over_10m, 0);
}

TEST(Sky, MaskSelectsBySatelliteElevation) {
  const Csv low = parse_csv(run(site_args("sky", "0")).out);
  const Csv mid = parse_csv(run(site_args("sky", "30")).out);
  ASSERT_GT(low.rows.size(), mid.rows.size());
  std::size_t above_30 = 0;
  for (std::size_t i = 0; i < low.rows.size(); ++i) {
    EXPECT_GE(low.num(i, "el_deg"), 0.0);
    if (low.num(i, "el_deg") >= 30.0) ++above_30;
  }
  EXPECT_EQ(above_30, mid.rows.size());
  // Half the constellation (~29 healthy) is above the horizon, give or take.
  EXPECT_GE(low.rows.size(), 8u);
  EXPECT_LE(low.rows.size(), 16u);
}

TEST(Sky, SatelliteAtZenith) {
  const time::GpsTime t(kWeek, kTow);
  const orbit::Ephemeris* eph = store().select(SatId::gps(1), t);
  ASSERT_NE(eph, nullptr);
  const Lla sub = geo::lla_from_ecef(orbit::sat_state(*eph, t).pos_m);
  const CliResult r = run({"sky", "--nav", nav_path("brdc0010.22n"), "--week", "2190", "--tow", "521233.25",
                           "--lat", std::to_string(sub.lat_rad * kRadToDeg), "--lon",
                           std::to_string(sub.lon_rad * kRadToDeg), "--height", "0", "--mask", "85"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv sky = parse_csv(r.out);
  ASSERT_EQ(sky.rows.size(), 1u);
  EXPECT_EQ(sky.cell(0, "prn"), "1");
  EXPECT_EQ(sky.cell(0, "sat"), "G01");
  // The satellite moves ~270 m during the flight time: ~0.01 deg off zenith.
  EXPECT_GT(sky.num(0, "el_deg"), 89.9);
  EXPECT_NEAR(sky.num(0, "range_m"), 20.2e6, 0.6e6);  // a - R_E, e up to 0.02
}

TEST(Dop, ConsistentWithTheSkyGeometry) {
  for (const char* mask : {"5", "15"}) {
    const Csv sky = parse_csv(run(site_args("sky", mask)).out);
    const CliResult r = run(site_args("dop", mask));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "gdop,pdop,hdop,vdop,tdop,nsat");
    const Csv dop = parse_csv(r.out);
    ASSERT_EQ(dop.rows.size(), 1u);
    EXPECT_EQ(dop.num(0, "nsat"), static_cast<double>(sky.rows.size())) << mask;
    const double g = dop.num(0, "gdop"), p = dop.num(0, "pdop"), h = dop.num(0, "hdop"), v = dop.num(0, "vdop"),
                 t = dop.num(0, "tdop");
    EXPECT_NEAR(p * p, h * h + v * v, 2e-3 * p);
    EXPECT_NEAR(g * g, p * p + t * t, 2e-3 * g);
    EXPECT_GT(h, 0.4);
    EXPECT_LT(h, 3.0);
    EXPECT_GT(v, h);  // no satellites below the horizon: vertical is weaker at mid latitude
    // Independent DOP: unweighted G^T G from the printed az/el.
    std::array<std::array<double, 4>, 4> n{};
    for (std::size_t i = 0; i < sky.rows.size(); ++i) {
      const double az = sky.num(i, "az_deg") * kDegToRad, el = sky.num(i, "el_deg") * kDegToRad;
      const std::array<double, 4> row{std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el), 1.0};
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) n[a][b] += row[a] * row[b];
    }
    const auto q = inverse4(n);
    EXPECT_NEAR(h, std::sqrt(q[0][0] + q[1][1]), 1e-3) << mask;
    EXPECT_NEAR(v, std::sqrt(q[2][2]), 1e-3) << mask;
    EXPECT_NEAR(t, std::sqrt(q[3][3]), 1e-3) << mask;
    EXPECT_NEAR(g, std::sqrt(q[0][0] + q[1][1] + q[2][2] + q[3][3]), 1e-3) << mask;
  }
}

TEST(Dop, HigherMaskMeansWorseGeometry) {
  const Csv low = parse_csv(run(site_args("dop", "5")).out);
  const Csv high = parse_csv(run(site_args("dop", "25")).out);
  EXPECT_GT(low.num(0, "nsat"), high.num(0, "nsat"));
  EXPECT_GT(high.num(0, "pdop"), low.num(0, "pdop"));
}

TEST(Dop, UndefinedWithFewerThanFourSatellites) {
  const Csv sky = parse_csv(run(site_args("sky", "70")).out);
  ASSERT_LT(sky.rows.size(), 4u);
  const CliResult r = run(site_args("dop", "70"));
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, "gdop,pdop,hdop,vdop,tdop,nsat\n,,,,," + std::to_string(sky.rows.size()) + "\n");
  EXPECT_NE(r.err.find("DOP undefined"), std::string::npos) << r.err;
}

}  // namespace sky_dop_test

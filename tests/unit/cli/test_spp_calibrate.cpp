// SPDX-License-Identifier: Apache-2.0
// gnssemu spp and calibrate on real observations: NYA1 (RINEX 3.05, IGS
// station with known coordinates) and LARM (3.02, with brdc0010.22n).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "config/config.hpp"
#include "tools/gnssemu/stations/calibrate.hpp"

using namespace gnssemu;
using namespace gnssemu::cli::test;

namespace {

std::string obs_path(const std::string& name) { return std::string(GNSSEMU_TEST_DATA) + "/obs/" + name; }

const std::string kNyaObs = obs_path("NYA100NOR_S_20241240000_90M_30S_MO.rnx");
const std::string kNyaDay = obs_path("NYA100NOR_S_20241240000_01D_30S_GO_L1.rnx.gz");
const std::string kNyaNav = nav_path("NYA100NOR_S_20241240000_01D_GN.rnx");
const std::string kNyaStation = "1202434.1303,252632.2212,6237772.4351";

}  // namespace

TEST(Spp, Nya1AllEpochsNearTheStation) {
  const CliResult r = run({"spp", "--obs", kNyaObs, "--nav", kNyaNav, "--mask", "10", "--station", kNyaStation});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv csv = parse_csv(r.out);
  ASSERT_EQ(csv.rows.size(), 180u);
  EXPECT_EQ(csv.header, (std::vector<std::string>{"gps_week", "tow_s", "x_m", "y_m", "z_m", "nsat", "pdop", "e_m",
                                                  "n_m", "u_m"}));
  double se = 0, sn = 0, su = 0, me = 0, mn = 0, mu = 0;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    EXPECT_EQ(csv.cell(i, "gps_week"), "2312");
    EXPECT_DOUBLE_EQ(csv.num(i, "tow_s"), 432000.0 + 30.0 * static_cast<double>(i));
    EXPECT_GE(csv.num(i, "nsat"), 8);
    EXPECT_LT(csv.num(i, "pdop"), 3.0);
    const double e = csv.num(i, "e_m"), n = csv.num(i, "n_m"), u = csv.num(i, "u_m");
    EXPECT_LT(std::hypot(e, n), 2.0) << i;
    EXPECT_LT(std::fabs(u), 5.0) << i;
    me += e, mn += n, mu += u;
    se += e * e, sn += n * n, su += u * u;
  }
  const double k = static_cast<double>(csv.rows.size());
  // Independent check in shared/data/README.md: mean E -0.05 N +0.02 U -0.43,
  // RMS E 0.21 N 0.28 U 1.05 m (10 deg mask, Klobuchar, Saastamoinen).
  EXPECT_NEAR(me / k, -0.05, 0.1);
  EXPECT_NEAR(mn / k, 0.02, 0.1);
  EXPECT_NEAR(mu / k, -0.43, 0.3);
  EXPECT_LT(std::sqrt(se / k), 0.35);
  EXPECT_LT(std::sqrt(sn / k), 0.40);
  EXPECT_LT(std::sqrt(su / k), 1.3);
  EXPECT_NE(r.err.find("180 epochs, 180 with a fix"), std::string::npos) << r.err;
}

TEST(Spp, LarmWithBrdcSmokeTest) {
  // Broadcast residuals of 2-3 m on this day: with the default sigma model
  // (a = 1.2 m) the corrected, masked solutions still pass the chi-square
  // test (fault exclusion at most once), keep >= 5 satellites and metre
  // errors. (The cold, uncorrected first solution only places the mask and
  // is not tested: it would fail.)
  const CliResult strict = run({"spp", "--obs", obs_path("LARM0010.22O"), "--nav", nav_path("brdc0010.22n"),
                                "--station", "4549397.1706,1874003.1392,4045167.6109"});
  ASSERT_EQ(strict.status, 0) << strict.err;
  EXPECT_NE(strict.err.find("4 epochs, 4 with a fix"), std::string::npos) << strict.err;
  const Csv sc = parse_csv(strict.out);
  TempDir dir;
  const std::string cfg =
      dir.write("no_test.toml", config_text(nav_path("brdc0010.22n"), "[receiver.solver]\nresidual_test_pfa = 0.0\n"));
  const CliResult r = run({"spp", "--obs", obs_path("LARM0010.22O"), "--nav", nav_path("brdc0010.22n"), "--station",
                           "4549397.1706,1874003.1392,4045167.6109", "--config", cfg});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv csv = parse_csv(r.out);
  ASSERT_EQ(csv.rows.size(), 4u);
  ASSERT_EQ(sc.rows.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_LT(std::hypot(csv.num(i, "e_m"), csv.num(i, "n_m")), 3.0);
    EXPECT_LT(std::fabs(csv.num(i, "u_m")), 5.0);
    EXPECT_LE(sc.num(i, "nsat"), csv.num(i, "nsat"));
    EXPECT_GE(sc.num(i, "nsat"), 5.0);
    EXPECT_LT(std::hypot(sc.num(i, "e_m"), sc.num(i, "n_m")), 3.0);
    EXPECT_LT(std::fabs(sc.num(i, "u_m")), 5.0);
  }
}

TEST(Spp, MaskRemovesLowSatellites) {
  const CliResult lo = run({"spp", "--obs", kNyaObs, "--nav", kNyaNav, "--mask", "5"});
  const CliResult hi = run({"spp", "--obs", kNyaObs, "--nav", kNyaNav, "--mask", "30"});
  ASSERT_EQ(lo.status, 0);
  ASSERT_EQ(hi.status, 0);
  const Csv a = parse_csv(lo.out), b = parse_csv(hi.out);
  ASSERT_FALSE(a.rows.empty());
  double na = 0, nb = 0;
  for (std::size_t i = 0; i < a.rows.size(); ++i) na += a.num(i, "nsat");
  for (std::size_t i = 0; i < b.rows.size(); ++i) nb += b.num(i, "nsat");
  EXPECT_GT(na / static_cast<double>(a.rows.size()),
            nb / static_cast<double>(std::max<std::size_t>(b.rows.size(), 1)) + 2.0);
}

TEST(Spp, BadInputsGiveClearMessages) {
  CliResult r = run({"spp", "--obs", obs_path("missing.rnx"), "--nav", kNyaNav});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("missing.rnx: observation file not found"), std::string::npos) << r.err;
  r = run({"spp", "--obs", kNyaObs, "--nav", nav_path("brdc0010.22n")});  // 2022 nav for 2024 data
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("outside the nav file"), std::string::npos) << r.err;
  r = run({"spp", "--obs", kNyaObs, "--nav", kNyaNav, "--mask", "95"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--mask"), std::string::npos) << r.err;
  r = run({"spp", "--obs", kNyaObs, "--nav", kNyaNav, "--station", "1,2"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--station"), std::string::npos) << r.err;
  r = run({"spp", "--obs", std::string(GNSSEMU_TEST_DATA) + "/bad/obs_v3_bad_flag.rnx", "--nav", kNyaNav});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("obs_v3_bad_flag.rnx:43: epoch flag 7"), std::string::npos) << r.err;
}

TEST(Calibrate, FitsNya1DayAndWritesALoadableConfig) {
  TempDir dir;
  const std::string out = dir.file("nya1.toml");
  const CliResult r = run({"calibrate", "--obs", kNyaDay, "--nav", kNyaNav, "--station", kNyaStation, "--mask", "10",
                           "--out", out});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv csv = parse_csv(r.out);
  std::map<std::string, double> v;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) v[csv.cell(i, "parameter")] = csv.num(i, "value");
  EXPECT_EQ(v["epochs"], 2880);
  EXPECT_GT(v["residuals"], 25000);
  // Residuals after broadcast orbits/clocks, Klobuchar and the standard
  // troposphere at an IGS station: decimetres to a metre.
  EXPECT_GT(v["residual_rms"], 0.3);
  EXPECT_LT(v["residual_rms"], 1.5);
  EXPECT_GT(v["gm_tau"], 600.0);  // single-point errors decorrelate over tens of minutes
  EXPECT_LT(v["white_sigma"], v["residual_rms"]);
  EXPECT_NEAR(v["gm_sigma"] * v["gm_sigma"] + v["white_sigma"] * v["white_sigma"],
              v["residual_rms"] * v["residual_rms"], 0.15);
  EXPECT_GT(v["cn0_zenith"], 45.0);
  EXPECT_LT(v["cn0_zenith"], 58.0);
  EXPECT_LT(v["cn0_rms"], 3.0);
  EXPECT_EQ(v["spp_fixes"], 2880);
  // The fitted model (docs/validation.md): the world's ionosphere near the
  // broadcast Klobuchar on this day (the Klobuchar term alone, no ZWD term:
  // 1.11; 0.77 pooled over the five station-days), a south-north azimuthal
  // pattern (longer ranges to the south at 79 N), white DLL noise of a
  // narrow carrier-aided loop, an hours-long orbit/clock process and a fast
  // multipath term.
  EXPECT_GT(v["klobuchar_scale"], 0.8);
  EXPECT_LT(v["klobuchar_scale"], 1.3);
  EXPECT_GT(std::fabs(v["bias_regressor_correlation"]), 0.8);  // reported: alpha and beta are nearly collinear
  EXPECT_GT(v["zwd_residual"], 0.0);  // what a free ZWD would take (diagnostic; the world keeps the receiver's)
  EXPECT_LT(v["gradient_north"], -0.2);
  EXPECT_GT(v["gradient_north"], -0.6);
  // What varies about the means is a random process: the pattern swings
  // with local time (afternoon several times the night's) -> a slow
  // gradient process of decimetres; the Klobuchar scale varies too.
  EXPECT_GT(v["gradient_sigma"], 0.1);
  EXPECT_LT(v["gradient_sigma"], 0.8);
  EXPECT_GT(v["gradient_tau"], 1800.0);
  EXPECT_GT(v["iono_scale_sigma"], 0.05);
  EXPECT_LT(v["iono_scale_sigma"], 1.0);
  EXPECT_GT(v["dll_bandwidth"], 0.03);
  EXPECT_LT(v["dll_bandwidth"], 0.5);
  EXPECT_GT(v["orbit_clock_sigma"], 0.2);
  EXPECT_LT(v["orbit_clock_sigma"], 1.0);
  EXPECT_GT(v["orbit_clock_tau"], 1800.0);
  EXPECT_LT(v["multipath_tau"], v["orbit_clock_tau"]);
  EXPECT_GE(v["iono_sigma"], 0.0);

  // The config loads as is and holds the fit, and batch runs it at the station.
  const config::Config c = config::load_config(out);
  const world::WorldConfig& rc = c.world;
  EXPECT_NEAR(rc.errors.orbit_clock.sigma_m, v["orbit_clock_sigma"], 1e-5);
  EXPECT_NEAR(rc.errors.orbit_clock.tau_s, v["orbit_clock_tau"], 1e-5 * v["orbit_clock_tau"]);
  EXPECT_NEAR(rc.errors.multipath.sigma_m, v["multipath_sigma_zenith"], 1e-5);
  EXPECT_NEAR(rc.errors.gradient.north_m, v["gradient_north"], 1e-5);
  EXPECT_NEAR(rc.errors.gradient.east_m, v["gradient_east"], 1e-5);
  EXPECT_NEAR(rc.errors.gradient.process.sigma_m, v["gradient_sigma"], 1e-5);
  EXPECT_NEAR(rc.errors.gradient.process.tau_s, v["gradient_tau"], 1e-5 * v["gradient_tau"]);
  EXPECT_EQ(rc.errors.gradient.north_diurnal_m, 0.0);  // no daily cycle: it does not hold at another site
  EXPECT_EQ(rc.errors.gradient.east_diurnal_m, 0.0);
  EXPECT_EQ(rc.errors.thermal_model, world::ThermalModel::kDll);
  EXPECT_NEAR(rc.signal.dll.loop_bandwidth_hz, v["dll_bandwidth"], 1e-5);
  EXPECT_NEAR(rc.atmosphere.ionosphere.klobuchar_scale, v["klobuchar_scale"], 1e-5);
  EXPECT_NEAR(rc.atmosphere.ionosphere.perturbation.sigma, v["iono_sigma"], 1e-5);
  EXPECT_EQ(rc.atmosphere.zwd_perturbation.sigma_m, 0.0);
  EXPECT_NEAR(c.receiver.elevation_mask_rad * 180.0 / 3.14159265358979, 10.0, 1e-9);
  EXPECT_NEAR(c.origin.lat_rad * 180.0 / 3.14159265358979, 78.93, 0.01);
  const std::string truth = dir.write("truth.csv",
                                      "gps_week,tow_s,x_m,y_m,z_m\n"
                                      "2312,432000,1202434.1303,252632.2212,6237772.4351\n"
                                      "2312,432600,1202434.1303,252632.2212,6237772.4351\n");
  const CliResult b = run({"batch", "--config", out, "--truth", truth, "--errors", "-"});
  ASSERT_EQ(b.status, 0) << b.err;
  const Csv e = parse_csv(b.out);
  ASSERT_EQ(e.rows.size(), 601u);
  int fixes = 0;
  for (std::size_t i = 0; i < e.rows.size(); ++i) fixes += e.cell(i, "fix_type") == "3";
  EXPECT_GT(fixes, 590);
}

namespace {

/// Deterministic uniform numbers in [0, 1) for synthetic residuals.
struct Lcg {
  uint64_t state;
  double operator()() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  }
};

/// A satellite of epoch grid at a random place in the sky (10-80 deg), with
/// the Klobuchar and wet regressors of that elevation; value_m left to the test.
cli::Residual synthetic_residual(Lcg& uniform, int grid, int prn) {
  cli::Residual r;
  r.grid = grid;
  r.sat = SatId::gps(prn);
  r.el_rad = (10.0 + 70.0 * uniform()) * 3.14159265358979 / 180.0;
  r.az_rad = 2.0 * 3.14159265358979 * uniform();
  r.klobuchar_m = 1.5 + 3.0 * uniform() / std::sin(r.el_rad + 0.2);
  r.nmf_wet = 1.0 / std::sin(r.el_rad);
  return r;
}

}  // namespace

TEST(Calibrate, CommonTermsRecoveredFromSyntheticResiduals) {
  // 2000 epochs of 9 satellites: residual = -0.3 K + 0.2 m_w + 0.5 cos az
  // - 0.1 sin az + clock + noise; the clock and the noise must not leak in.
  std::vector<cli::Residual> res;
  Lcg uniform{12345};
  for (int g = 0; g < 2000; ++g) {
    const double clock = 1000.0 * uniform();
    for (int s = 0; s < 9; ++s) {
      cli::Residual r = synthetic_residual(uniform, g, s + 1);
      const double noise = 0.3 * (uniform() + uniform() + uniform() - 1.5);
      r.value_m = -0.3 * r.klobuchar_m + 0.2 * r.nmf_wet + 0.5 * std::cos(r.az_rad) - 0.1 * std::sin(r.az_rad) +
                  clock + noise;
      res.push_back(r);
    }
  }
  const cli::AtmosphereBiasFit f = cli::fit_atmosphere_bias(res, true);
  EXPECT_NEAR(f.klobuchar_alpha, -0.3, 0.01);
  EXPECT_NEAR(f.zwd_beta_m, 0.2, 0.01);
  EXPECT_NEAR(f.gradient_north_m, 0.5, 0.01);
  EXPECT_NEAR(f.gradient_east_m, -0.1, 0.01);
  // The model's fit has no ZWD term: the gradient is unaffected, the wet
  // term goes to the Klobuchar scale as far as it can.
  const cli::AtmosphereBiasFit k = cli::fit_atmosphere_bias(res);
  EXPECT_EQ(k.zwd_beta_m, 0.0);
  EXPECT_GT(k.klobuchar_alpha, -0.3);
  EXPECT_NEAR(k.gradient_north_m, 0.5, 0.02);
  EXPECT_NEAR(k.gradient_east_m, -0.1, 0.02);
}

TEST(Calibrate, ErrorStatsAndGaussMarkovFit) {
  // Exponential autocovariance 0.5^2 exp(-lag / 900 s) + white 0.2^2 at lag 0.
  std::vector<double> acov;
  for (int k = 0; k <= 120; ++k) acov.push_back(0.25 * std::exp(-30.0 * k / 900.0) + (k == 0 ? 0.04 : 0.0));
  const cli::NoiseFit f = cli::fit_gauss_markov(acov, 30.0);
  EXPECT_NEAR(f.gm_sigma_m, 0.5, 0.005);
  EXPECT_NEAR(f.gm_tau_s, 900.0, 20.0);
  EXPECT_NEAR(f.white_sigma_m, 0.2, 0.01);

  // AR(1) series with phi = exp(-1/10): correlation time 10 steps.
  std::vector<Enu> s;
  double x = 0.0, y = 0.0, z = 0.0;
  uint64_t state = 12345;
  auto gauss = [&]() {
    double u = 0.0;
    for (int i = 0; i < 12; ++i) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      u += static_cast<double>(state >> 11) / 9007199254740992.0;
    }
    return u - 6.0;
  };
  const double phi = std::exp(-0.1), q = std::sqrt(1 - phi * phi);
  for (int i = 0; i < 20000; ++i) {
    x = phi * x + q * gauss();
    y = phi * y + q * gauss();
    z = phi * z + 2.0 * q * gauss();
    s.emplace_back(x, y, z);
  }
  const statistics::PositionErrorStats st = statistics::position_error_stats(s, 1.0);
  EXPECT_EQ(st.n, 20000);
  EXPECT_NEAR(st.sigma_e_m, 1.0, 0.1);
  EXPECT_NEAR(st.sigma_u_m, 2.0, 0.2);
  EXPECT_NEAR(st.corr_time_s, 10.0, 1.5);
  // Rayleigh with sigma ~1: median 1.177, 95 % 2.448.
  EXPECT_NEAR(st.cep50_m, 1.177, 0.12);
  EXPECT_NEAR(st.cep95_m, 2.448, 0.25);
}

TEST(Calibrate, NeedsStationAndEnoughData) {
  TempDir dir;
  CliResult r = run({"calibrate", "--obs", obs_path("LARM0010.22O"), "--nav", nav_path("brdc0010.22n"), "--station",
                     "4549397.1706,1874003.1392,4045167.6109", "--out", dir.file("x.toml")});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("only 4 epochs"), std::string::npos) << r.err;
  r = run({"calibrate", "--obs", kNyaObs, "--nav", kNyaNav, "--station", "0,0,0", "--out", dir.file("x.toml")});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("not near the surface"), std::string::npos) << r.err;
}

// SPDX-License-Identifier: Apache-2.0
// gnssemu sky model columns: broadcast Klobuchar from the nav header, the
// receiver's zenith hydrostatic delay, Niell mapping, attenuation and C/N0.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli_test_util.hpp"
#include "core/atmosphere/klobuchar.hpp"
#include "core/common/constants.hpp"
#include "core/orbit/rinex_nav.hpp"

using namespace gnssemu;
using namespace gnssemu::cli::test;

namespace {

// NYA1 (shared/data/README.md), 2024-05-03 11:00 GPST = week 2312, tow 471600
// (local noon: Klobuchar's daytime cosine, where the coefficients matter).
const std::vector<std::string> kNyaArgs{"sky",   "--nav",        nav_path("NYA100NOR_S_20241240000_01D_GN.rnx"),
                                        "--week", "2312",        "--tow",
                                        "471600", "--lat",       "78.9296",
                                        "--lon",  "11.8652",     "--height",
                                        "84.2",   "--mask",      "0"};

TEST(SkyAtmosphere, ColumnsFollowTheModels) {
  const CliResult r = run(kNyaArgs);
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv sky = parse_csv(r.out);
  ASSERT_GE(sky.rows.size(), 8u);
  const orbit::NavData nav = orbit::read_rinex_nav(nav_path("NYA100NOR_S_20241240000_01D_GN.rnx"));
  ASSERT_TRUE(nav.klobuchar.valid);
  const double lat = 78.9296 * kDegToRad, lon = 11.8652 * kDegToRad;
  bool ordered = true;
  for (std::size_t i = 0; i < sky.rows.size(); ++i) {
    const double az = sky.num(i, "az_deg") * kDegToRad, el = sky.num(i, "el_deg") * kDegToRad;
    // The nav header's GPSA/GPSB, not RTKLIB's defaults.
    const double k = atmosphere::klobuchar_delay_l1_m(nav.klobuchar, lat, lon, az, el, 471600.0);
    const double d = atmosphere::klobuchar_delay_l1_m(atmosphere::rtklib_default_klobuchar(), lat, lon, az, el,
                                                      471600.0);
    EXPECT_NEAR(sky.num(i, "iono_klobuchar_m"), k, 1e-4);
    EXPECT_GT(std::fabs(k - d), 1e-3);
    // Saastamoinen ZHD at 84 m, 79 deg N: 2.2768 * 1003.2 hPa / (1 + 0.00249 - 0.0000236) ~ 2.279 m.
    EXPECT_NEAR(sky.num(i, "tropo_zhd_m"), 2.279, 0.003);
    const double nh = sky.num(i, "nmf_hydro"), nw = sky.num(i, "nmf_wet");
    EXPECT_GE(nh, 0.999);
    EXPECT_GE(nw, 0.999);
    // Niell stays below the flat-Earth 1/sin(el) and within 4 % of it above 10 deg.
    EXPECT_LE(nh, 1.0 / std::sin(std::max(el, kDegToRad)) + 1e-3);
    if (el > 10.0 * kDegToRad) {
      EXPECT_NEAR(nh * std::sin(el), 1.0, 0.04);
    }
    const double atten = sky.num(i, "atten_db"), cn0 = sky.num(i, "cn0_dbhz");
    EXPECT_GT(atten, 0.03);
    EXPECT_LT(atten, 2.0);
    EXPECT_GT(cn0, 30.0);
    EXPECT_LT(cn0, 49.0);
  }
  // C/N0 and mapping against elevation: higher satellite, higher C/N0, lower mapping.
  for (std::size_t i = 0; i < sky.rows.size(); ++i) {
    for (std::size_t j = 0; j < sky.rows.size(); ++j) {
      if (sky.num(i, "el_deg") > sky.num(j, "el_deg") + 1.0) {
        ordered = ordered && sky.num(i, "cn0_dbhz") > sky.num(j, "cn0_dbhz");
        ordered = ordered && sky.num(i, "nmf_hydro") < sky.num(j, "nmf_hydro");
        ordered = ordered && sky.num(i, "atten_db") < sky.num(j, "atten_db");
      }
    }
  }
  EXPECT_TRUE(ordered);
}

TEST(SkyAtmosphere, NoKlobucharInTheHeaderUsesRtklibDefaults) {
  // brdc0010.22n without its ION ALPHA / ION BETA lines, at noon in Paris.
  std::ifstream in(nav_path("brdc0010.22n"));
  const std::string path =
      (std::filesystem::temp_directory_path() / ("gnssemu_noion_" + std::to_string(::getpid()) + ".22n")).string();
  {
    std::ofstream out(path);
    std::string line;
    while (std::getline(in, line))
      if (line.find("ION ALPHA") == std::string::npos && line.find("ION BETA") == std::string::npos) out << line << "\n";
  }
  ASSERT_FALSE(orbit::read_rinex_nav(path).klobuchar.valid);
  const CliResult r = run({"sky", "--nav", path, "--week", "2190", "--tow", "561600", "--lat", "48.8738", "--lon",
                           "2.2950", "--height", "100", "--mask", "5"});
  const CliResult with = run({"sky", "--nav", nav_path("brdc0010.22n"), "--week", "2190", "--tow", "561600",
                              "--lat", "48.8738", "--lon", "2.2950", "--height", "100", "--mask", "5"});
  std::filesystem::remove(path);
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv sky = parse_csv(r.out), sky_with = parse_csv(with.out);
  ASSERT_GE(sky.rows.size(), 4u);
  ASSERT_EQ(sky.rows.size(), sky_with.rows.size());
  for (std::size_t i = 0; i < sky.rows.size(); ++i) {
    const double az = sky.num(i, "az_deg") * kDegToRad, el = sky.num(i, "el_deg") * kDegToRad;
    EXPECT_NEAR(sky.num(i, "iono_klobuchar_m"),
                atmosphere::klobuchar_delay_l1_m(atmosphere::rtklib_default_klobuchar(), 48.8738 * kDegToRad,
                                                 2.2950 * kDegToRad, az, el, 561600.0),
                1e-4);
    EXPECT_NE(sky.cell(i, "iono_klobuchar_m"), sky_with.cell(i, "iono_klobuchar_m"));
    EXPECT_EQ(sky.cell(i, "cn0_dbhz"), sky_with.cell(i, "cn0_dbhz"));
  }
}

}  // namespace

// SPDX-License-Identifier: Apache-2.0
// gnssemu spp with several systems: TLSE 2024-01-01 (Compact RINEX, 1 Hz,
// G/R/E/C) with the IGS merged nav cut to 08-14 h; --systems errors; the
// RTKLIB ephemeris set list spp --preset rtklib selects from.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "tools/gnssemu/stations/spp.hpp"

using namespace gnssemu;
using namespace gnssemu::cli::test;

namespace {

const std::string kTlseObs = std::string(GNSSEMU_TEST_DATA) + "/obs/TLSE00FRA_R_20240011200_15M_01S_MO.crx.gz";
const std::string kTlseNav = nav_path("BRDC00IGS_R_20240010000_01D_MN_08-14h.rnx.gz");
// Header APPROX POSITION XYZ of TLSE.
const std::string kTlseStation = "4627852.5264,119640.5140,4372994.8358";

struct Summary {
  int epochs = 0;
  double mean_nsat = 0.0;
  double mean_3d_m = 0.0;
};

Summary solve(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"spp", "--obs", kTlseObs, "--nav", kTlseNav, "--mask", "10", "--station",
                                   kTlseStation};
  args.insert(args.end(), extra.begin(), extra.end());
  const CliResult r = run(args);
  EXPECT_EQ(r.status, 0) << r.err;
  const Csv csv = parse_csv(r.out);
  Summary s;
  s.epochs = static_cast<int>(csv.rows.size());
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    s.mean_nsat += std::stod(csv.cell(i, "nsat"));
    const double e = std::stod(csv.cell(i, "e_m")), n = std::stod(csv.cell(i, "n_m")), u = std::stod(csv.cell(i, "u_m"));
    s.mean_3d_m += std::sqrt(e * e + n * n + u * u);
  }
  if (s.epochs > 0) {
    s.mean_nsat /= s.epochs;
    s.mean_3d_m /= s.epochs;
  }
  return s;
}

}  // namespace

TEST(SppMultiGnss, EverySystemOfTheNavFileByDefault) {
  const Summary gps = solve({"--systems", "G"});
  const Summary all = solve({});
  const Summary grec = solve({"--systems", "G,R,E,C"});
  EXPECT_EQ(gps.epochs, 900);
  EXPECT_EQ(all.epochs, 900);
  EXPECT_EQ(grec.epochs, 900);
  // TLSE tracks about 8-9 GPS satellites above 10 deg and 30+ of four systems.
  EXPECT_GT(all.mean_nsat, gps.mean_nsat + 15.0);
  EXPECT_NEAR(all.mean_nsat, grec.mean_nsat, 1e-9);  // no QZSS in view at TLSE
  EXPECT_LT(gps.mean_3d_m, 5.0);
  EXPECT_LT(grec.mean_3d_m, 5.0);
  for (const char* one : {"R", "E", "C"}) {
    const Summary s = solve({"--systems", one});
    EXPECT_EQ(s.epochs, 900) << one;
    EXPECT_LT(s.mean_3d_m, 15.0) << one;
  }
}

TEST(SppMultiGnss, SystemsOptionErrors) {
  CliResult r = run({"spp", "--obs", kTlseObs, "--nav", kTlseNav, "--systems", "G,X"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--systems: 'G,X'"), std::string::npos) << r.err;
  r = run({"spp", "--obs", kTlseObs, "--nav", kTlseNav, "--systems", "G,S"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("SBAS"), std::string::npos) << r.err;
}

TEST(SppMultiGnss, RtklibSetListDropsAnINavSetAfterItsFNavTwin) {
  const time::GpsTime toe(2295, 129600.0);
  const auto set = [&](int number, int iode, double ttr_tow_s, int sources, double tgd_s) {
    orbit::Ephemeris e;
    e.sat = SatId(GnssSystem::kGalileo, number);
    e.toe = e.toc = toe;
    e.iode = iode;
    e.transmit_known = true;
    e.transmit_tow_s = ttr_tow_s;
    e.gal_data_sources = sources;
    e.tgd_s = tgd_s;
    return e;
  };
  const int fnav = orbit::kGalFnavE5a | orbit::kGalClockE5a, inav = orbit::kGalInavE1b | orbit::kGalClockE5b;
  // E26: F/NAV then I/NAV of IODnav 88, same transmission time: adjacent, the
  // I/NAV set goes. E11: another satellite's set between them: both stay.
  const std::vector<orbit::Ephemeris> in = {
      set(26, 87, 128000.0, inav, 1e-9),  set(26, 88, 129700.0, fnav, 2e-9), set(26, 88, 129700.0, inav, 3e-9),
      set(11, 40, 129710.0, inav, 4e-9),  set(11, 41, 129720.0, fnav, 5e-9), set(12, 7, 129721.0, inav, 6e-9),
      set(11, 41, 129722.0, inav, 7e-9)};
  const std::vector<orbit::Ephemeris> out = cli::rtklib_unique_ephemerides(in);
  ASSERT_EQ(out.size(), 6u);
  int e26_inav_88 = 0, e11_inav_41 = 0;
  for (const orbit::Ephemeris& e : out) {
    if (e.sat.number == 26 && e.iode == 88 && e.gal_data_sources == inav) ++e26_inav_88;
    if (e.sat.number == 11 && e.iode == 41 && e.gal_data_sources == inav) ++e11_inav_41;
    // Every set carries its satellite's first set's group delay (gettgd).
    if (e.sat.number == 26) {
      EXPECT_EQ(e.tgd_s, 1e-9);
    }
    if (e.sat.number == 11) {
      EXPECT_EQ(e.tgd_s, 4e-9);
    }
  }
  EXPECT_EQ(e26_inav_88, 0);
  EXPECT_EQ(e11_inav_41, 1);
}

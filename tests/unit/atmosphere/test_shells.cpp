// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/atmosphere/shells.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"

using namespace gnssemu;
using namespace gnssemu::atmosphere;

namespace {
constexpr double R = kMeanEarthRadius_m;

// Law of cosines: distance from radius r0 at elevation e to radius r (>= r0).
double exact_to_radius(double r0, double e, double r) {
  return std::sqrt(r * r - r0 * r0 * std::cos(e) * std::cos(e)) - r0 * std::sin(e);
}
std::size_t idx(ShellKind k) { return static_cast<std::size_t>(k); }
}  // namespace

TEST(ShellPath, ZenithIsThickness) {
  EXPECT_NEAR(slant_path_in_shell_m(0.0, 90 * kDegToRad, 0.0, 12e3), 12e3, 1e-6);
  EXPECT_NEAR(slant_path_in_shell_m(0.0, 90 * kDegToRad, 12e3, 50e3), 38e3, 1e-6);
  EXPECT_NEAR(slant_path_in_shell_m(5e3, 90 * kDegToRad, 0.0, 12e3), 7e3, 1e-6);   // inside
  EXPECT_EQ(slant_path_in_shell_m(12e3, 90 * kDegToRad, 0.0, 12e3), 0.0);          // at the top
  EXPECT_EQ(slant_path_in_shell_m(12e3, 30 * kDegToRad, 0.0, 12e3), 0.0);
  EXPECT_NEAR(slant_path_in_shell_m(12e3, 90 * kDegToRad, 12e3, 50e3), 38e3, 1e-6);
}

TEST(ShellPath, MatchesLawOfCosines) {
  for (double h0 : {0.0, 800.0, 11000.0})
    for (double e : {0.0, 1e-6, 0.5, 5.0, 30.0, 89.999}) {
      const double r0 = R + h0, el = e * kDegToRad;
      const double expect = exact_to_radius(r0, el, R + 50e3) - exact_to_radius(r0, el, R + 12e3);
      EXPECT_NEAR(slant_path_in_shell_m(h0, el, 12e3, 50e3), expect, 1e-6 * expect + 1e-6) << h0 << " " << e;
      EXPECT_NEAR(slant_path_in_shell_m(h0, el, 0.0, 12e3), exact_to_radius(r0, el, R + 12e3), 1e-5) << h0 << " " << e;
    }
  // Horizontal from the surface through the 0-12 km troposphere: sqrt((R+12k)^2 - R^2) = 391 km.
  EXPECT_NEAR(slant_path_in_shell_m(0.0, 0.0, 0.0, 12e3), std::sqrt(std::pow(R + 12e3, 2) - R * R), 1e-6);
}

TEST(ShellPath, NegativeElevationFromAltitude) {
  // From 12 km at -2 deg the ray dips to about 8.1 km and returns: 2 r0 sin 2 deg in the troposphere.
  const double r0 = R + 12e3;
  EXPECT_NEAR(slant_path_in_shell_m(12e3, -2 * kDegToRad, 0.0, 12e3), 2.0 * r0 * std::sin(2 * kDegToRad), 1e-4);
  // Steeper than the horizon dip: grazes the surface; finite and longer.
  const double graze = slant_path_in_shell_m(12e3, -10 * kDegToRad, 0.0, 12e3);
  EXPECT_TRUE(std::isfinite(graze));
  EXPECT_NEAR(graze, 2.0 * std::sqrt(std::pow(R + 12e3, 2) - R * R), 1e-3);
  EXPECT_EQ(slant_path_in_shell_m(NAN, 0.1, 0.0, 1.0), 0.0);
}

TEST(GasAttenuation, SpecificAttenuationAtL1) {
  // Reference §3.1: gamma_o = 0.0056 dB/km, gamma_w(7.5 g/m^3) = 0.00014 dB/km.
  EXPECT_NEAR(oxygen_specific_attenuation_db_km(1.57542), 0.0056014, 1e-6);
  EXPECT_NEAR(water_vapour_specific_attenuation_db_km(1.57542, 7.5), 0.00013859, 1e-8);
}

TEST(GasAttenuation, ZenithMatchesAnalyticChain) {
  const AtmosphereShells s(ShellsConfig{});
  const ShellAttenuation z = s.gas_attenuation(0.0, 90 * kDegToRad);
  // Closed form of the isothermal chain (Python, same constants): 0.0361329 / 0.0094439 / 4.05e-5 dB.
  EXPECT_NEAR(z.gas_db[idx(ShellKind::kTroposphere)], 0.03613293, 1e-7);
  EXPECT_NEAR(z.gas_db[idx(ShellKind::kStratosphere)], 0.00944391, 1e-7);
  EXPECT_NEAR(z.gas_db[idx(ShellKind::kMesosphere)], 4.0458e-5, 1e-8);
  EXPECT_EQ(z.gas_db[idx(ShellKind::kIonosphere)], 0.0);
  EXPECT_NEAR(z.path_m[idx(ShellKind::kIonosphere)], 940e3, 1e-3);
  EXPECT_NEAR(z.total_db, 0.0456181, 1e-6);
  // Reference §3.1 / §4.2 honest magnitudes: zenith 0.03-0.05 dB, 5 deg 0.39-0.55 dB, 10 deg 0.20-0.27 dB.
  EXPECT_GT(z.total_db, 0.03);
  EXPECT_LT(z.total_db, 0.05);
  const double a5 = s.gas_attenuation(0.0, 5 * kDegToRad).total_db;
  EXPECT_GT(a5, 0.39);
  EXPECT_LT(a5, 0.55);
  const double a10 = s.gas_attenuation(0.0, 10 * kDegToRad).total_db;
  EXPECT_GT(a10, 0.20);
  EXPECT_LT(a10, 0.27);
  // Horizontal: finite, a few dB at most.
  const double a0 = s.gas_attenuation(0.0, 0.0).total_db;
  EXPECT_GT(a0, a5);
  EXPECT_LT(a0, 5.0);
  // From 12 km: only the air above, exp(-12/8.43) of it, about a quarter.
  const double z12 = s.gas_attenuation(12e3, 90 * kDegToRad).total_db;
  EXPECT_NEAR(z12, z.gas_db[idx(ShellKind::kStratosphere)] + z.gas_db[idx(ShellKind::kMesosphere)] +
                       z.gas_db[idx(ShellKind::kThermosphere)],
              2e-6);  // water vapour above 12 km is exp(-6) of the column
}

TEST(GasAttenuation, DensityChainIsContinuous) {
  const AtmosphereShells s(ShellsConfig{});
  EXPECT_NEAR(s.dry_density_ratio(0.0), 1.0, 1e-15);
  EXPECT_NEAR(s.dry_density_ratio(8434.1), std::exp(-1.0), 1e-4);  // scale height 8.43 km at 288.15 K
  EXPECT_NEAR(s.dry_density_ratio(12e3 - 1e-6), s.dry_density_ratio(12e3), 1e-9);
  EXPECT_NEAR(s.dry_density_ratio(50e3 - 1e-6), s.dry_density_ratio(50e3), 1e-9);
}

TEST(GasAttenuation, LayersSwitchOff) {
  ShellsConfig c;
  c.shells[idx(ShellKind::kTroposphere)].enabled = false;
  const AtmosphereShells s(c);
  const ShellAttenuation z = s.gas_attenuation(0.0, 90 * kDegToRad);
  EXPECT_EQ(z.gas_db[idx(ShellKind::kTroposphere)], 0.0);
  EXPECT_NEAR(z.total_db, 0.0094439 + 4.0458e-5 + 7.8e-7 + 1.4e-10, 2e-7);
  EXPECT_NEAR(z.path_m[idx(ShellKind::kTroposphere)], 12e3, 1e-6);  // geometry still reported
}

TEST(GasAttenuation, BadConfigThrows) {
  ShellsConfig c;
  c.shells[1].top_m = 5e3;  // below its bottom: negative thickness
  EXPECT_THROW(AtmosphereShells{c}, Error);
  c = {};
  c.shells[0].temperature_k = 0.0;
  EXPECT_THROW(AtmosphereShells{c}, Error);
  c = {};
  c.shells[2].temperature_k = -10.0;
  EXPECT_THROW(AtmosphereShells{c}, Error);
  c = {};
  c.gas.water_vapour_density_g_m3 = -1.0;
  EXPECT_THROW(AtmosphereShells{c}, Error);
  c = {};
  c.gas.water_vapour_scale_height_m = 0.0;
  EXPECT_THROW(AtmosphereShells{c}, Error);
  try {
    c = {};
    c.shells[1].top_m = 5e3;
    AtmosphereShells bad(c);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("stratosphere: negative thickness"), std::string::npos) << e.what();
  }
}

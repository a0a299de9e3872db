// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/atmosphere/shells.hpp"
#include "core/common/constants.hpp"
#include "core/world/measurement/gas_table.hpp"

using namespace gnssemu;
using gnssemu::atmosphere::AtmosphereShells;
using gnssemu::atmosphere::ShellsConfig;

TEST(GasTable, AgreesWithTheQuadrature) {
  const AtmosphereShells shells(ShellsConfig{});
  for (const double h : {0.0, 100.0, 3000.0}) {
    world::GasAttenuationTable table;
    double worst_low = 0.0, worst_high = 0.0;
    for (double el_deg = -2.0; el_deg <= 90.0; el_deg += 0.0137) {
      // Below the grid (0.75 degrees) the table integrates: exact.
      const double el = el_deg * kDegToRad;
      const double exact = shells.gas_attenuation(h, el).total_db;
      const double err = std::fabs(table.total_db(shells, h, el) - exact);
      (el_deg < 2.0 ? worst_low : worst_high) = std::max(el_deg < 2.0 ? worst_low : worst_high, err);
    }
    EXPECT_LT(worst_high, 1e-5) << "height " << h;
    EXPECT_LT(worst_low, 3e-5) << "height " << h;
  }
}

TEST(GasTable, EachNodeOnceForOneHeight) {
  const AtmosphereShells shells(ShellsConfig{});
  world::GasAttenuationTable table;
  for (int pass = 0; pass < 3; ++pass)
    for (double el_deg = 0.0; el_deg <= 90.0; el_deg += 0.01) table.total_db(shells, 100.0, el_deg * kDegToRad);
  // Nodes 0.5..89.75 degrees (the loop ends below 90), and every call below 0.75 degrees.
  const long below = 75;  // 0.00, 0.01, ..., 0.74
  EXPECT_EQ(table.evaluations(), 360 + 3 * below);
  // Within the height tolerance: the same nodes.
  EXPECT_EQ(table.total_db(shells, 104.0, 0.5), table.total_db(shells, 100.0, 0.5));
  EXPECT_EQ(table.evaluations(), 360 + 3 * below);
  // Beyond it the table starts over at the new height.
  const double moved = table.total_db(shells, 110.0, 0.5);
  EXPECT_GT(table.evaluations(), 360 + 3 * below);
  EXPECT_NEAR(moved, shells.gas_attenuation(110.0, 0.5).total_db, 1e-5);
}

TEST(GasTable, OffTheGridIsTheQuadrature) {
  const AtmosphereShells shells(ShellsConfig{});
  world::GasAttenuationTable table;
  const double el = -10.0 * kDegToRad;
  EXPECT_EQ(table.total_db(shells, 100.0, el), shells.gas_attenuation(100.0, el).total_db);
  EXPECT_EQ(table.total_db(shells, NAN, 0.3), shells.gas_attenuation(NAN, 0.3).total_db);
  EXPECT_EQ(table.evaluations(), 2);
}

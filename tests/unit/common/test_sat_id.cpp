// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/common/gnss_systems.hpp"
#include "core/common/sat_id.hpp"

using namespace gnssemu;

TEST(SatId, DenseIndexCoversEverySatelliteOnce) {
  std::set<int> seen;
  for (const auto& n : kSatNumbering) {
    for (int k = n.first; k <= n.last; ++k) {
      const SatId id(n.system, k);
      ASSERT_TRUE(id.valid());
      ASSERT_GE(id.index(), 0);
      ASSERT_LT(id.index(), kNumSats);
      EXPECT_TRUE(seen.insert(id.index()).second);
      EXPECT_EQ(SatId::from_index(id.index()), id);
    }
  }
  EXPECT_EQ(static_cast<int>(seen.size()), kNumSats);
  EXPECT_EQ(kNumSats, 32 + 27 + 36 + 63 + 10 + 39);
  EXPECT_EQ(SatId::gps(1).index(), 0);  // GPS first: a GPS-only run indexes as PRN - 1
  EXPECT_EQ(SatId::gps(32).index(), 31);
}

TEST(SatId, RinexNamesAndPrns) {
  EXPECT_EQ(std::string(sat_name(SatId::gps(5)).data()), "G05");
  EXPECT_EQ(std::string(sat_name(SatId(GnssSystem::kGlonass, 12)).data()), "R12");
  EXPECT_EQ(std::string(sat_name(SatId(GnssSystem::kGalileo, 30)).data()), "E30");
  EXPECT_EQ(std::string(sat_name(SatId(GnssSystem::kBeiDou, 19)).data()), "C19");
  const auto j02 = SatId::from_prn(GnssSystem::kQzss, 194);
  ASSERT_TRUE(j02);
  EXPECT_EQ(std::string(sat_name(*j02).data()), "J02");
  EXPECT_EQ(j02->prn(), 194);
  const auto s23 = SatId::from_prn(GnssSystem::kSbas, 123);
  ASSERT_TRUE(s23);
  EXPECT_EQ(std::string(sat_name(*s23).data()), "S23");
  EXPECT_EQ(s23->prn(), 123);
  EXPECT_FALSE(SatId::from_prn(GnssSystem::kSbas, 119));
  EXPECT_FALSE(SatId::from_prn(GnssSystem::kSbas, 159));
  EXPECT_FALSE(SatId::from_prn(GnssSystem::kQzss, 5));
  EXPECT_FALSE(SatId::from_prn(GnssSystem::kGps, 33));
  EXPECT_FALSE(SatId().valid());
}

TEST(SatId, Parse) {
  EXPECT_EQ(parse_sat("G05"), SatId::gps(5));
  EXPECT_EQ(parse_sat("G5"), SatId::gps(5));
  EXPECT_EQ(parse_sat("G 5"), SatId::gps(5));
  EXPECT_EQ(parse_sat("C63"), SatId(GnssSystem::kBeiDou, 63));
  EXPECT_FALSE(parse_sat("C64"));
  EXPECT_FALSE(parse_sat("R28"));
  EXPECT_FALSE(parse_sat("S19"));
  EXPECT_FALSE(parse_sat("I01"));  // NavIC: not in the table
  EXPECT_FALSE(parse_sat("G"));
  EXPECT_FALSE(parse_sat("G1x"));
  EXPECT_FALSE(parse_sat("G001"));
}

TEST(SatId, OrderIsSystemThenNumber) {
  EXPECT_LT(SatId::gps(32), SatId(GnssSystem::kGlonass, 1));
  EXPECT_LT(SatId(GnssSystem::kBeiDou, 2), SatId(GnssSystem::kBeiDou, 10));
  EXPECT_LT(SatId(GnssSystem::kQzss, 10), SatId(GnssSystem::kSbas, 20));
}

TEST(SystemSet, ParseAndPrint) {
  const auto set = parse_systems("G,R,E,C,J");
  ASSERT_TRUE(set);
  EXPECT_EQ(set->count(), 5);
  EXPECT_FALSE(set->has(GnssSystem::kSbas));
  EXPECT_EQ(std::string(systems_text(*set).data()), "G,R,E,C,J");
  EXPECT_EQ(std::string(systems_text(*parse_systems("E, G")).data()), "G,E");
  EXPECT_FALSE(parse_systems(""));
  EXPECT_FALSE(parse_systems("G,G"));
  EXPECT_FALSE(parse_systems("G,X"));
  EXPECT_FALSE(parse_systems("G,"));
  EXPECT_FALSE(parse_systems("GR"));
  EXPECT_EQ(SystemSet::all().count(), kNumSystems);
  EXPECT_EQ(parse_systems("G,R,J,S")->intersect(*parse_systems("G,E,J")), *parse_systems("G,J"));
  EXPECT_EQ(parse_systems("G,R,J,S")->minus(*parse_systems("G,E,J")), *parse_systems("R,S"));
  EXPECT_EQ(parse_systems("G,R,J,S")->unite(*parse_systems("G,E,J")), *parse_systems("G,R,E,J,S"));
}

TEST(SystemTable, RowsAndCarriers) {
  for (std::size_t i = 0; i < kSystems.size(); ++i) EXPECT_EQ(static_cast<std::size_t>(kSystems[i].system), i);
  EXPECT_DOUBLE_EQ(l1_carrier_hz(GnssSystem::kGlonass, -7), 1598.0625e6);
  EXPECT_DOUBLE_EQ(l1_carrier_hz(GnssSystem::kGlonass, 6), 1605.375e6);
  EXPECT_DOUBLE_EQ(l1_carrier_hz(GnssSystem::kBeiDou), 1561.098e6);
  EXPECT_DOUBLE_EQ(l1_carrier_hz(GnssSystem::kGalileo), 1575.42e6);
  EXPECT_TRUE(is_beidou_geo(SatId(GnssSystem::kBeiDou, 1)));
  EXPECT_TRUE(is_beidou_geo(SatId(GnssSystem::kBeiDou, 59)));
  EXPECT_FALSE(is_beidou_geo(SatId(GnssSystem::kBeiDou, 6)));
  EXPECT_FALSE(is_beidou_geo(SatId(GnssSystem::kGps, 1)));
}

// SPDX-License-Identifier: Apache-2.0
// The rules of one event: ranges per ramp end, ramps need a duration, what
// each type requires.
#include <gtest/gtest.h>

#include "core/faults/fault_event.hpp"
#include "fault_rig.hpp"

namespace gnssemu::faults {
namespace {

using test::make_event;

TEST(FaultEvent, RampIsLinearOverTheEvent) {
  FaultEvent e = make_event(FaultType::kJammer, 10.0, 100.0);
  e.put(Param::kJsDb, Ramp{0.0, 60.0});
  EXPECT_DOUBLE_EQ(e.value(Param::kJsDb, e.fraction_at(10.0)), 0.0);
  EXPECT_DOUBLE_EQ(e.value(Param::kJsDb, e.fraction_at(60.0)), 30.0);
  EXPECT_DOUBLE_EQ(e.value(Param::kJsDb, e.fraction_at(110.0)), 60.0);
  EXPECT_TRUE(e.active_at(10.0));
  EXPECT_FALSE(e.active_at(110.0));
  EXPECT_FALSE(e.active_at(9.99));
  EXPECT_FALSE(check_event(e));
}

TEST(FaultEvent, RulesNameTheKey) {
  FaultEvent ramp = make_event(FaultType::kJammer, 0.0);
  ramp.put(Param::kJsDb, Ramp{0.0, 60.0});
  EXPECT_EQ(check_event(ramp).value().rfind("js_db: a [from, to] ramp needs a finite duration_s", 0), 0u);

  FaultEvent range = make_event(FaultType::kSatellite, 0.0);
  range.put(Param::kPrn, 33.0);
  EXPECT_EQ(check_event(range).value().rfind("prn: 33 is out of range", 0), 0u);

  FaultEvent no_prn = make_event(FaultType::kSatellite, 0.0);
  no_prn.put(Param::kBiasM, 50.0);
  EXPECT_EQ(check_event(no_prn).value(), "satellite: prn is required");

  FaultEvent both = make_event(FaultType::kJammer, 0.0);
  both.put(Param::kJsDb, 30.0);
  both.put(Param::kEirpDbw, 0.0);
  both.put(Param::kDistanceM, 100.0);
  EXPECT_TRUE(check_event(both).has_value());

  FaultEvent placed = make_event(FaultType::kJammer, 0.0);
  placed.put(Param::kEirpDbw, 0.0);
  EXPECT_EQ(check_event(placed).value(), "eirp_dbw: needs distance_m or lat_deg and lon_deg");
  placed.put(Param::kDistanceM, 100.0);
  EXPECT_FALSE(check_event(placed));

  FaultEvent wrong_type = make_event(FaultType::kOutage, 0.0);
  wrong_type.put(Param::kJsDb, 10.0);
  EXPECT_EQ(check_event(wrong_type).value().rfind("js_db: not a parameter of type outage", 0), 0u);
}

TEST(FaultEvent, DescribeSaysTheParametersNow) {
  FaultEvent e = make_event(FaultType::kJammer, 10.0, 100.0, static_cast<int>(JammerKind::kCw));
  e.put(Param::kJsDb, Ramp{0.0, 60.0});
  EXPECT_EQ(describe(e, 60.0), "kind=cw js_db=30");
  FaultEvent s = make_event(FaultType::kSatellite, 0.0);
  s.put(Param::kPrn, 8);
  s.put(Param::kUnhealthy, 1.0);
  EXPECT_EQ(describe(s, 5.0), "prn=8 unhealthy=true");
  s.put(Param::kPrn, sat_param(SatId(GnssSystem::kBeiDou, 19)));
  EXPECT_EQ(describe(s, 5.0), "prn=C19 unhealthy=true");
  EXPECT_FALSE(check_event(s));
}

TEST(FaultEvent, EveryParameterHasANameARangeAndADoc) {
  for (const ParamSpec& s : param_specs()) {
    EXPECT_FALSE(s.name.empty());
    EXPECT_FALSE(s.doc.empty()) << s.name;
    EXPECT_LE(s.range.min, s.range.max) << s.name;
    EXPECT_NE(s.types, 0) << s.name;
  }
  EXPECT_EQ(find_param(FaultType::kSpoofer, "clock_jump_us"), find_param(FaultType::kSatellite, "clock_jump_us"));
  EXPECT_EQ(find_param(FaultType::kOutage, "js_db"), nullptr);
}

}  // namespace
}  // namespace gnssemu::faults

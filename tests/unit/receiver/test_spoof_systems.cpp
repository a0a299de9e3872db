// SPDX-License-Identifier: Apache-2.0
// The spoof monitor's system test: GPS satellites whose residuals point
// elsewhere than the other systems' (a GPS-only spoofer) raise an indication.
#include <gtest/gtest.h>

#include <cmath>

#include "core/receiver/tracking/spoof_monitor.hpp"

namespace gnssemu::receiver {
namespace {

// Six used GPS and six used Galileo satellites spread over the sky; the GPS
// residuals are those of a position dx_gps_enu off (and a clock offset).
Fix fix_with(const Enu& dx_gps_enu, double gps_clock_m) {
  Fix f;
  f.type = FixType::k3D;
  f.t = time::GpsTime(2300, 100.0);
  for (int g = 0; g < 2; ++g) {
    for (int k = 0; k < 6; ++k) {
      SatInfo& s = f.sats[static_cast<std::size_t>(f.num_sats++)];
      s.sat = g == 0 ? SatId::gps(3 + k) : SatId(GnssSystem::kGalileo, 3 + k);
      s.az_rad = (60.0 * k + 25.0 * g) * kDegToRad;
      s.el_rad = (15.0 + 12.0 * k) * kDegToRad;
      s.tracked = s.used = true;
      s.cn0_dbhz = 40.0 + k;
      if (g == 0) {
        const double ce = std::cos(s.el_rad);
        const Enu u(std::sin(s.az_rad) * ce, std::cos(s.az_rad) * ce, std::sin(s.el_rad));
        s.residual_m = -u.dot(dx_gps_enu) + gps_clock_m;
      } else {
        s.residual_m = 0.3 * ((k % 3) - 1);
      }
    }
  }
  return f;
}

TEST(SpoofSystems, DisagreementIsTheDistanceBetweenTheGroups) {
  const std::optional<double> d = system_disagreement_m(fix_with(Enu(300.0, -400.0, 0.0), 80.0));
  ASSERT_TRUE(d);
  EXPECT_NEAR(*d, 500.0, 2.0);
  Fix few = fix_with(Enu(300.0, 0.0, 0.0), 0.0);
  few.sats[0].used = few.sats[1].used = false;  // 4 GPS left
  EXPECT_FALSE(system_disagreement_m(few));
}

TEST(SpoofSystems, GpsOnlySpoofingIsIndicated) {
  SpoofDetectionConfig c;
  c.uniform_std_db = 0.0;
  SpoofMonitor quiet(c), spoofed(c);
  EXPECT_EQ(quiet.update(fix_with(Enu(1.0, 1.0, 2.0), 0.5)), 1);
  EXPECT_EQ(spoofed.update(fix_with(Enu(0.0, 500.0, 0.0), 0.0)), 2);
  EXPECT_EQ(spoofed.indications(), kSpoofSystemDisagreement);
  c.system_disagreement_m = 0.0;  // off
  SpoofMonitor off(c);
  EXPECT_EQ(off.update(fix_with(Enu(0.0, 500.0, 0.0), 0.0)), 1);
}

TEST(SpoofSystems, OneGroupExcludedWholesale) {
  Fix f = fix_with(Enu(0.0, 0.0, 0.0), 0.0);
  EXPECT_FALSE(one_group_excluded(f));
  for (int i = 0; i < 3; ++i) {
    f.sats[static_cast<std::size_t>(i)].used = false;
    f.sats[static_cast<std::size_t>(i)].excluded = true;
  }
  EXPECT_TRUE(one_group_excluded(f));  // 3 of 6 GPS, no Galileo
  f.sats[6].used = false;
  f.sats[6].excluded = true;
  EXPECT_FALSE(one_group_excluded(f));  // exclusions on both sides: not one system's
  SpoofMonitor m{SpoofDetectionConfig{}};
  f.sats[6].excluded = false;
  f.sats[6].used = true;
  EXPECT_EQ(m.update(f), 2);
}

}  // namespace
}  // namespace gnssemu::receiver

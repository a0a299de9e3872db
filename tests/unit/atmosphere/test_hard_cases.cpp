// SPDX-License-Identifier: Apache-2.0
// Sweep over the hard cases (DESIGN.md §5): no NaN, no negative delay or loss, and no
// heap allocation while evaluating.
#include <gtest/gtest.h>

#include <cmath>

#include "core/atmosphere/clouds_rain.hpp"
#include "core/atmosphere/ionosphere.hpp"
#include "core/atmosphere/klobuchar.hpp"
#include "core/atmosphere/shells.hpp"
#include "core/atmosphere/troposphere.hpp"
#include "core/common/constants.hpp"
#include "tests/support/alloc_counter.hpp"

using namespace gnssemu;
using namespace gnssemu::atmosphere;

namespace {

bool ok(double v) { return std::isfinite(v) && v >= 0.0; }

struct World {
  Ionosphere iono;
  Troposphere tropo;
  AtmosphereShells shells;
  CloudsRain clouds;
};

World make_world(double vtec, bool all_off) {
  IonosphereConfig ic;
  ic.source = VtecSource::kFixed;
  ic.vtec_tecu = vtec;
  TroposphereConfig tc;
  ShellsConfig sc;
  CloudsRainConfig cc;
  cc.layer_count = 2;
  cc.layers[0] = cloud_preset("thick_fog");
  cc.layers[1] = cloud_preset("thunderstorm");
  cc.rain.rate_mm_h = 100.0;
  if (all_off) {
    ic.enabled = false;
    tc.enabled = false;
    for (Shell& s : sc.shells) s.enabled = false;
    cc.layer_count = 0;
    cc.rain.rate_mm_h = 0.0;
  }
  return World{Ionosphere(ic), Troposphere(tc), AtmosphereShells(sc), CloudsRain(cc)};
}
}  // namespace

TEST(HardCases, NoNanAnywhere) {
  const double els[] = {-90, -5, -1, 0, 1e-9, 3, 5, 10, 45, 89.999999, 90};
  const double heights[] = {-400, 0, 12000, 40000};
  const double lats[] = {-90, -45, 0, 45, 90};
  const double lons[] = {-180, 0, 180};
  const double doys[] = {1, 366, 366.99};
  const double tows[] = {0.0, 50400.0, 604799.999};
  const orbit::KlobucharParams klob = rtklib_default_klobuchar();
  const World worlds[] = {make_world(0.0, false), make_world(1000.0, false), make_world(50.0, true)};

  const long before = gnssemu::support::allocation_count();
  int n = 0;
  for (const World& w : worlds)
    for (double e : els)
      for (double h : heights)
        for (double la : lats)
          for (double lo : lons)
            for (double d : doys) {
              const double el = e * kDegToRad, lat = la * kDegToRad, lon = lo * kDegToRad;
              const double tow = tows[n % 3];
              const double az = (n * 37 % 360) * kDegToRad;
              ++n;
              ASSERT_TRUE(ok(klobuchar_delay_l1_m(klob, lat, lon, az, el, tow))) << e << " " << la << " " << lo;
              ASSERT_TRUE(ok(w.iono.slant_delay_m(lat, lon, az, el, tow, -3.0)));
              ASSERT_TRUE(ok(w.iono.slant_delay_m(lat, lon, az, el, tow, 1e6)));
              const NiellMapping m = niell_mapping(el, lat, h, d);
              ASSERT_TRUE(ok(m.hydro) && ok(m.wet)) << e << " " << h << " " << la << " " << d;
              ASSERT_TRUE(ok(w.tropo.slant_delay_m(lat, h, el, d))) << e << " " << h;
              ASSERT_TRUE(ok(standard_troposphere_correction_m(lat, h, el, d)));
              const ShellAttenuation g = w.shells.gas_attenuation(h, el);
              ASSERT_TRUE(ok(g.total_db)) << e << " " << h;
              for (double p : g.path_m) ASSERT_TRUE(ok(p));
              const CloudsRainAttenuation c = w.clouds.attenuation(h, el);
              ASSERT_TRUE(ok(c.clouds_db) && ok(c.rain_db)) << e << " " << h;
            }
  EXPECT_EQ(gnssemu::support::allocation_count() - before, 0) << "evaluation allocated";
  EXPECT_EQ(n, 3 * 11 * 4 * 5 * 3 * 3);
}

TEST(HardCases, NanInputsGiveFiniteOutputs) {
  const orbit::KlobucharParams klob = rtklib_default_klobuchar();
  EXPECT_TRUE(ok(klobuchar_delay_l1_m(klob, NAN, NAN, NAN, NAN, NAN)));
  const NiellMapping m = niell_mapping(NAN, NAN, NAN, NAN);
  EXPECT_TRUE(ok(m.hydro) && ok(m.wet));
  EXPECT_TRUE(ok(AtmosphereShells(ShellsConfig{}).gas_attenuation(NAN, 0.1).total_db));
  EXPECT_TRUE(ok(slant_path_in_shell_m(0.0, NAN, 0.0, 1e3)));
}

TEST(HardCases, ExtremesHaveSensibleMagnitudes) {
  // Everything switched off: exactly zero.
  const World off = make_world(50.0, true);
  EXPECT_EQ(off.iono.slant_delay_m(0.5, 0.5, 0, 0.1, 0), 0.0);
  EXPECT_EQ(off.tropo.slant_delay_m(0.5, 0.0, 0.1, 100), 0.0);
  EXPECT_EQ(off.shells.gas_attenuation(0.0, 0.1).total_db, 0.0);
  EXPECT_EQ(off.clouds.attenuation(0.0, 0.1).rain_db, 0.0);
  // Extreme TEC (1000 TECU) at the horizon: 1000 * 0.16237 * 3.38 = 549 m.
  const World hot = make_world(1000.0, false);
  EXPECT_NEAR(hot.iono.slant_delay_m(0, 0, 0, 0.0, 0), 1000 * 0.162370 * 3.3819, 0.5);
  // Tropo at the 1 deg floor is bounded (< 100 m) and at 90 deg equals the zenith delay.
  EXPECT_LT(hot.tropo.slant_delay_m(0.0, 0.0, 0.0, 1.0), 100.0);
  EXPECT_NEAR(hot.tropo.slant_delay_m(0.0, 12000.0, 90 * kDegToRad, 1.0), hot.tropo.zhd_m(0, 12000) + hot.tropo.zwd_m(12000),
              1e-9);
}

// SPDX-License-Identifier: Apache-2.0
// SharedSky: Taylor steps across the light time against full evaluations for
// every system, GLONASS resumed integration, horizon culling, rebuilding on
// a replaced store, one sky shared by two worlds, no allocation per epoch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/world/sky/shared_sky.hpp"
#include "core/world/sky/sky.hpp"
#include "core/world/world.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::world {
namespace {

const orbit::NavData& nav() {
  static const orbit::NavData d =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  return d;
}

// 2024-01-10 00:00 GPST.
const time::GpsTime kDay(2296, 259200.0);

SystemSet every_system() {
  return SystemSet::only(GnssSystem::kGps)
      .with(GnssSystem::kGlonass)
      .with(GnssSystem::kGalileo)
      .with(GnssSystem::kBeiDou)
      .with(GnssSystem::kQzss);
}

// The Taylor steps the world's light time (65-90 ms back from the epoch) and
// the receiver's transmit time take, against the ephemeris evaluated in full
// at the same instant: far below a millimetre for every system, GLONASS
// (RK4) and the BeiDou GEO (tilted-frame transformation) included.
TEST(SharedSky, TaylorStepsMatchFullEvaluationForEverySystem) {
  const orbit::EphemerisStore store(nav().ephemerides);
  SharedSky sky(store, every_system());
  std::array<double, kNumSystems> max_pos_m{}, max_vel_m_s{}, max_clk_s{};
  std::array<int, kNumSystems> n{};
  bool beidou_geo = false;
  for (const double h : {0.5, 1.5, 3.0, 5.0, 6.5}) {
    sky.update(kDay + h * 3600.0);
    for (const SatId sat : sky.sats()) {
      const SkyState& s = sky.state(sat);
      if (s.eph == nullptr) continue;
      ASSERT_TRUE(s.current);
      const int sys = static_cast<int>(sat.system);
      ++n[static_cast<std::size_t>(sys)];
      beidou_geo = beidou_geo || is_beidou_geo(sat);
      for (const double dt : {-0.090, -0.080, -0.067, -0.020, 0.010}) {
        const orbit::SatState a = sky.state_at(*s.eph, sky.t() + dt);
        const orbit::SatState b = orbit::sat_state(*s.eph, sky.t() + dt);
        auto& mp = max_pos_m[static_cast<std::size_t>(sys)];
        auto& mv = max_vel_m_s[static_cast<std::size_t>(sys)];
        auto& mc = max_clk_s[static_cast<std::size_t>(sys)];
        mp = std::max(mp, (a.pos_m - b.pos_m).norm());
        mv = std::max(mv, (a.vel_m_s - b.vel_m_s).norm());
        mc = std::max(mc, std::fabs(a.clk_bias_s - b.clk_bias_s));
      }
    }
  }
  EXPECT_TRUE(beidou_geo);
  for (int i = 0; i < kNumSystems; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (static_cast<GnssSystem>(i) == GnssSystem::kSbas) continue;
    EXPECT_GT(n[k], 0) << system_letter(static_cast<GnssSystem>(i));
    std::printf("%c: %3d states, max |dpos| %.2e m, |dvel| %.2e m/s, |dclk| %.2e s over <= 90 ms\n",
                system_letter(static_cast<GnssSystem>(i)), n[k], max_pos_m[k], max_vel_m_s[k], max_clk_s[k]);
    EXPECT_LT(max_pos_m[k], 1e-6);    // 1 um: far below the mm
    EXPECT_LT(max_vel_m_s[k], 1e-5);  // 0.01 mm/s: 5e-5 Hz of Doppler
    EXPECT_LT(max_clk_s[k], 1e-15);   // 0.3 um
  }
}

// Epochs between the sky's grid nodes (cubic Hermite through two full
// evaluations kSkyNodeSpacing_s apart) against the ephemeris evaluated in
// full at the epoch: every system, 10 Hz epochs off the grid.
TEST(SharedSky, EpochsBetweenNodesMatchFullEvaluationForEverySystem) {
  const orbit::EphemerisStore store(nav().ephemerides);
  SharedSky sky(store, every_system());
  std::array<double, kNumSystems> max_pos_m{}, max_vel_m_s{}, max_acc_m_s2{}, max_clk_s{}, max_drift{};
  std::array<int, kNumSystems> n{};
  const long evals0 = sky.evaluations();
  int epochs = 0;
  for (const double h : {0.5, 3.0, 6.5}) {
    for (int e = 0; e < 600; ++e, ++epochs) {
      sky.update(kDay + h * 3600.0 + 0.1 * e + 0.03);
      for (const SatId sat : sky.sats()) {
        const SkyState& s = sky.state(sat);
        if (s.eph == nullptr) continue;
        const auto k = static_cast<std::size_t>(sat.system);
        ++n[k];
        const orbit::SatState b = orbit::sat_state(*s.eph, sky.t());
        max_pos_m[k] = std::max(max_pos_m[k], (s.pos_m - b.pos_m).norm());
        max_vel_m_s[k] = std::max(max_vel_m_s[k], (s.vel_m_s - b.vel_m_s).norm());
        max_acc_m_s2[k] =
            std::max(max_acc_m_s2[k], (s.acc_m_s2 - orbit::ecef_acceleration_m_s2(*s.eph, b.pos_m, b.vel_m_s)).norm());
        max_clk_s[k] = std::max(max_clk_s[k], std::fabs(s.clk_bias_s - b.clk_bias_s));
        max_drift[k] = std::max(max_drift[k], std::fabs(s.clk_drift_s_s - b.clk_drift_s_s));
      }
    }
  }
  for (int i = 0; i < kNumSystems; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (static_cast<GnssSystem>(i) == GnssSystem::kSbas) continue;
    ASSERT_GT(n[k], 0) << system_letter(static_cast<GnssSystem>(i));
    std::printf("%c: %6d states, max |dpos| %.2e m, |dvel| %.2e m/s, |dacc| %.2e m/s2, |dclk| %.2e s, |ddrift| %.2e\n",
                system_letter(static_cast<GnssSystem>(i)), n[k], max_pos_m[k], max_vel_m_s[k], max_acc_m_s2[k],
                max_clk_s[k], max_drift[k]);
    // Keplerian systems ~0.5 um; GLONASS ~6 um (its RK4 steps' own roughness).
    EXPECT_LT(max_pos_m[k], 1e-5);      // 10 um: the carrier's noise is ~1 mm
    EXPECT_LT(max_vel_m_s[k], 1e-5);    // 5e-5 Hz of Doppler
    EXPECT_LT(max_acc_m_s2[k], 1e-6);   // over an 80 ms light time: 3e-9 m
    EXPECT_LT(max_clk_s[k], 1e-15);     // 0.3 um
    EXPECT_LT(max_drift[k], 1e-15);
  }
  // About two full evaluations per satellite per node spacing (10 Hz: 1 in 50 epochs).
  const double per_epoch = static_cast<double>(sky.evaluations() - evals0) / epochs;
  std::printf("full evaluations per epoch: %.2f for %zu satellites\n", per_epoch, sky.sats().size());
  EXPECT_LT(per_epoch, 0.05 * static_cast<double>(sky.sats().size()));
}

// Beyond the Taylor span, or for another set, the ephemeris is evaluated in full.
TEST(SharedSky, FallsBackToFullEvaluation) {
  const orbit::EphemerisStore store(nav().ephemerides);
  SharedSky sky(store, every_system());
  sky.update(kDay + 3600.0);
  const auto it = std::find_if(sky.sats().begin(), sky.sats().end(),
                               [&sky](SatId s) { return sky.state(s).eph != nullptr; });
  ASSERT_NE(it, sky.sats().end());
  const orbit::Ephemeris& eph = *sky.state(*it).eph;
  const time::GpsTime far = sky.t() + 5.0;
  EXPECT_EQ(sky.state_at(eph, far).pos_m, orbit::sat_state(eph, far).pos_m);
  const orbit::Ephemeris copy = eph;
  EXPECT_EQ(sky.state_at(copy, sky.t() - 0.07).pos_m, orbit::sat_state(copy, sky.t() - 0.07).pos_m);
}

// Resuming a GLONASS integration from its last whole step gives the state
// integrated from tb, to the last bit, forwards and backwards.
TEST(SharedSky, GlonassResumedIntegrationIsBitIdentical) {
  int checked = 0;
  for (const orbit::Ephemeris& e : nav().ephemerides) {
    if (e.sat.system != GnssSystem::kGlonass || checked >= 6) continue;
    ++checked;
    orbit::GlonassNode node;
    for (double dt = -1700.0; dt < 1700.0; dt += 37.3) {
      const orbit::SatState a = orbit::sat_state(e, e.toe + dt, node);
      const orbit::SatState b = orbit::sat_state(e, e.toe + dt);
      ASSERT_EQ(a.pos_m, b.pos_m) << dt;
      ASSERT_EQ(a.vel_m_s, b.vel_m_s) << dt;
      ASSERT_EQ(a.clk_bias_s, b.clk_bias_s);
    }
    for (double dt = 1790.0; dt > -1790.0; dt -= 0.1 * 611.0) {
      ASSERT_EQ(orbit::sat_state(e, e.toe + dt, node).pos_m, orbit::sat_state(e, e.toe + dt).pos_m) << dt;
    }
  }
  EXPECT_EQ(checked, 6);
}

// With an antenna, satellites well below its horizon are not evaluated, and
// every one above it is (the world's look angles decide, from full states).
TEST(SharedSky, CullsOnlyFarBelowTheHorizon) {
  const orbit::EphemerisStore store(nav().ephemerides);
  SharedSky sky(store, every_system());
  for (const Lla site : {Lla{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0}, Lla{-33.9 * kDegToRad, 151.2 * kDegToRad, 0.0},
                         Lla{78.9 * kDegToRad, 11.9 * kDegToRad, 50.0}, Lla{0.0, -160.0 * kDegToRad, 10000.0}}) {
    const Ecef rx = geo::ecef_from_lla(site);
    for (int k = 0; k < 40; ++k) {
      const time::GpsTime t = kDay + 3600.0 + 30.0 * k;
      sky.update(t, std::span<const Ecef>(&rx, 1));
      long evaluated = 0;
      int above = 0;
      for (const SatId sat : sky.sats()) {
        const SkyState& s = sky.state(sat);
        if (s.eph == nullptr) continue;
        evaluated += s.current;
        const SkySat full = sky_sat(*s.eph, t, rx, site, Ecef());
        if (full.el_rad > 0.0) {
          ++above;
          EXPECT_TRUE(s.current) << sat_name(sat).data() << " el " << full.el_rad / kDegToRad;
        }
      }
      EXPECT_LT(evaluated, static_cast<long>(sky.sats().size()));
      EXPECT_GT(above, 10);
    }
  }
}

// The list follows the store: a store replaced in place (as the daemon
// re-dates it) is noticed by its fingerprint; an unchanged one is not rebuilt.
TEST(SharedSky, RebuildsOnlyWhenTheStoreChanges) {
  orbit::EphemerisStore store(nav().ephemerides);
  SharedSky sky(store, every_system());
  sky.update(kDay + 3600.0);
  const long rev = sky.revision();
  const std::size_t all = sky.sats().size();
  for (int k = 1; k < 20; ++k) sky.update(kDay + 3600.0 + k);
  EXPECT_EQ(sky.revision(), rev);
  std::vector<orbit::Ephemeris> gps;
  for (const orbit::Ephemeris& e : nav().ephemerides)
    if (e.sat.system == GnssSystem::kGps) gps.push_back(e);
  store = orbit::EphemerisStore(gps);
  sky.update(kDay + 3620.0);
  EXPECT_NE(sky.revision(), rev);
  EXPECT_LT(sky.sats().size(), all);
  for (const SatId sat : sky.sats()) EXPECT_EQ(sat.system, GnssSystem::kGps);
}

// Two worlds reading one sky give what each gives with its own, and the
// epoch allocates nothing.
TEST(SharedSky, TwoWorldsShareOneSky) {
  const orbit::EphemerisStore store(nav().ephemerides);
  WorldConfig cfg;
  cfg.systems = every_system();
  World own(store, cfg), a(store, cfg), b(store, cfg);
  SharedSky sky(store, every_system());
  const Lla site{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0};
  const Ecef p0 = geo::ecef_from_lla(site);
  const Vec3 v = geo::enu_to_ecef_vector(Enu(60.0, 80.0, 0.0), site.lat_rad, site.lon_rad);
  long allocs = 0;
  for (int k = 0; k < 300; ++k) {
    const time::GpsTime t = kDay + 7200.0 + 0.1 * k;
    Truth tr;
    tr.t = t;
    tr.pos_m = Ecef(p0 + v * (0.1 * k));
    tr.vel_m_s = Ecef(v);
    tr.valid = true;
    Truth tr_b = tr;
    tr_b.pos_m = Ecef(tr.pos_m + Vec3(1.0, 0.0, 0.0));  // a second antenna a metre away
    const std::array<Ecef, 2> antennas{tr.pos_m, tr_b.pos_m};
    const long a0 = support::allocation_count();
    sky.update(t, antennas);
    const Observables& oa = a.step(sky, tr, 5.0 * kDegToRad);
    b.step(sky, tr_b, 5.0 * kDegToRad);
    const Observables& oo = own.step(t, tr, 5.0 * kDegToRad);
    if (k > 0) allocs += support::allocation_count() - a0;
    ASSERT_EQ(oa.num_sats, oo.num_sats);
    ASSERT_GT(oa.num_sats, 30);
    for (int i = 0; i < oa.num_sats; ++i) {
      ASSERT_EQ(oa.sats[i].sat, oo.sats[i].sat);
      ASSERT_EQ(oa.sats[i].pseudorange_m, oo.sats[i].pseudorange_m);
      ASSERT_EQ(oa.sats[i].el_rad, oo.sats[i].el_rad);
    }
  }
  EXPECT_EQ(allocs, 0);
}

}  // namespace
}  // namespace gnssemu::world

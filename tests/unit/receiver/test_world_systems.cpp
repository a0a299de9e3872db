// SPDX-License-Identifier: Apache-2.0
// The world per system: each satellite's signal on its own carrier (GLONASS
// by FDMA channel, BeiDou B1I), so the ionosphere delays it by 1/f^2 and its
// Doppler and phase count cycles of its own wavelength.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/common/gnss_systems.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/world/world.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver {
namespace {

using test::kSite;
using test::kToe;
using test::truth_at;

// Each GPS satellite of the nominal sky also as a BeiDou MEO (same elements)
// and, from its state at toe, as a GLONASS satellite on channel -7.
std::vector<orbit::Ephemeris> twin_sky() {
  std::vector<orbit::Ephemeris> v = test::nominal_constellation(kToe, 4);
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int prn = v[i].sat.number;
    if (prn > 20) continue;
    orbit::Ephemeris c = v[i];
    c.sat = SatId(GnssSystem::kBeiDou, 18 + prn);  // C19..C38: MEO, no GEO rule
    v.push_back(c);
    const orbit::SatState st = orbit::sat_state(v[i], kToe);
    orbit::Ephemeris r;
    r.sat = SatId(GnssSystem::kGlonass, prn);
    r.toe = r.toc = kToe;
    r.pos_m = st.pos_m;
    r.vel_m_s = st.vel_m_s;
    r.glo_channel = -7;
    v.push_back(r);
  }
  return v;
}

const world::SatObservable* find(const world::Observables& o, SatId sat) {
  for (int i = 0; i < o.num_sats; ++i)
    if (o.sats[i].sat == sat && o.sats[i].received) return &o.sats[i];
  return nullptr;
}

TEST(WorldSystems, CarrierIonosphereAndDopplerPerSatellite) {
  const orbit::EphemerisStore store(twin_sky());
  world::WorldConfig c = test::noiseless().world;
  c.systems = SystemSet::all();
  c.atmosphere.ionosphere.source = atmosphere::VtecSource::kFixed;
  world::World w(store, c);
  const Ecef pos = geo::ecef_from_lla(kSite);
  const time::GpsTime t = kToe + 60.0;
  const world::Observables& obs = w.step(t, truth_at(pos, t), 5.0 * kDegToRad);
  const double f_r = 1602.0e6 - 7.0 * 0.5625e6;
  int checked_c = 0, checked_r = 0;
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& g = obs.sats[i];
    if (g.sat.system != GnssSystem::kGps || !g.received) continue;
    EXPECT_EQ(g.carrier_hz, kL1Freq_hz);
    EXPECT_EQ(g.wavelength_m, kL1Wavelength_m);
    const double iono_g = w.path_effects(g.sat).iono_m;
    ASSERT_GT(iono_g, 0.5);
    if (const world::SatObservable* b = find(obs, SatId(GnssSystem::kBeiDou, 18 + g.sat.number))) {
      EXPECT_EQ(b->carrier_hz, 1561.098e6);
      EXPECT_NEAR(w.path_effects(b->sat).iono_m / iono_g, std::pow(kL1Freq_hz / 1561.098e6, 2), 2e-3);
      ++checked_c;
    }
    if (const world::SatObservable* r = find(obs, SatId(GnssSystem::kGlonass, g.sat.number))) {
      EXPECT_EQ(r->carrier_hz, f_r);
      EXPECT_NEAR(r->wavelength_m, kSpeedOfLight_m_s / f_r, 1e-15);
      EXPECT_NEAR(w.path_effects(r->sat).iono_m / iono_g, std::pow(kL1Freq_hz / f_r, 2), 2e-3);
      // The same range rate, counted in cycles of its own carrier.
      EXPECT_NEAR(r->doppler_hz * r->wavelength_m, g.doppler_hz * g.wavelength_m, 1.0) << g.sat.number;
      if (std::fabs(g.doppler_hz) > 1000.0) {
        EXPECT_GT(std::fabs(r->doppler_hz - g.doppler_hz), 10.0);  // not L1 cycles
      }
      ++checked_r;
    }
  }
  EXPECT_GE(checked_c, 3);
  EXPECT_GE(checked_r, 3);
}

TEST(WorldSystems, OrbitClockErrorFollowsTheSystemSisre) {
  const orbit::EphemerisStore store(twin_sky());
  world::WorldConfig c = test::noiseless().world;
  c.systems = SystemSet::all();
  c.errors.orbit_clock = {1.0, 1.0e6};  // nearly constant over the run
  world::WorldConfig off = c;
  off.errors.orbit_clock.sigma_m = 0.0;
  // The orbit/clock residual is what the pseudorange gains over the same
  // world without it; its spread over the satellites follows each system's sigma.
  double sum2_g = 0.0, sum2_r = 0.0;
  int n_g = 0, n_r = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    c.seed = off.seed = seed;
    world::World w(store, c), w0(store, off);
    const Ecef pos = geo::ecef_from_lla(kSite);
    const world::Observables& a = w.step(kToe, truth_at(pos, kToe), 5.0 * kDegToRad);
    const world::Observables& b = w0.step(kToe, truth_at(pos, kToe), 5.0 * kDegToRad);
    for (int i = 0; i < a.num_sats; ++i) {
      const world::SatObservable* o0 = find(b, a.sats[i].sat);
      if (!a.sats[i].received || o0 == nullptr) continue;
      const double d = a.sats[i].pseudorange_m - o0->pseudorange_m;
      if (a.sats[i].sat.system == GnssSystem::kGps) sum2_g += d * d, ++n_g;
      if (a.sats[i].sat.system == GnssSystem::kGlonass) sum2_r += d * d, ++n_r;
    }
  }
  ASSERT_GT(n_g, 50);
  ASSERT_GT(n_r, 50);
  const double ratio = std::sqrt(sum2_r / n_r) / std::sqrt(sum2_g / n_g);
  // GLONASS: sqrt(1.0^2 - 0.6^2 + 2.0^2) = 2.15 m against GPS's 1.0 m
  // (world::orbit_clock_process; the whole sigma scaled would be 3.33).
  EXPECT_NEAR(ratio, std::sqrt(1.0 - 0.36 + 4.0), 0.5);
}

}  // namespace
}  // namespace gnssemu::receiver

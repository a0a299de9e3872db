// SPDX-License-Identifier: Apache-2.0
// The second frequency of every system, measured as what one world changes
// over a twin that differs in one input: the ionosphere (band 2 over band 1
// = (f1 / f2)^2, GLONASS by each satellite's own channel), the broadcast
// group delays (each band's users' own, per system ICD) and the receiver's
// inter-frequency bias; carriers and wavelengths from the ICD figures.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "core/common/gnss_signals.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/world/world.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver::second_band_systems {
namespace {

using test::kSite;
using test::kToe;
using test::truth_at;

// GLONASS channel of the twin of GPS PRN prn: all of -7..+6 over PRN 1..20.
int channel_of(int prn) { return prn % 14 - 7; }

// Each GPS satellite of the nominal sky also as a Galileo and (PRN <= 20) a
// BeiDou MEO (same elements) and, from its state at toe, a GLONASS satellite
// on channel_of(prn). Group delays: tgd_s and tgd2_s as given (GLONASS: none
// in its nav data).
std::vector<orbit::Ephemeris> four_system_sky(double tgd_s, double tgd2_s) {
  std::vector<orbit::Ephemeris> gps = test::nominal_constellation(kToe, 4);
  std::vector<orbit::Ephemeris> v;
  for (orbit::Ephemeris e : gps) {
    const int prn = e.sat.number;
    e.tgd_s = tgd_s;
    e.tgd2_s = tgd2_s;
    v.push_back(e);
    orbit::Ephemeris gal = e;
    gal.sat = SatId(GnssSystem::kGalileo, prn);
    gal.gal_data_sources = orbit::kGalInavE1b | orbit::kGalInavE5b | orbit::kGalClockE5b;  // I/NAV: BGD(E1,E5b)
    v.push_back(gal);
    if (prn > 20) continue;
    orbit::Ephemeris bds = e;
    bds.sat = SatId(GnssSystem::kBeiDou, 18 + prn);  // C19..C38: MEO
    v.push_back(bds);
    const orbit::SatState st = orbit::sat_state(e, kToe);
    orbit::Ephemeris r;
    r.sat = SatId(GnssSystem::kGlonass, prn);
    r.toe = r.toc = kToe;
    r.pos_m = st.pos_m;
    r.vel_m_s = st.vel_m_s;
    r.glo_channel = channel_of(prn);
    v.push_back(r);
  }
  return v;
}

world::WorldConfig dual_band_world(double vtec_tecu) {
  world::WorldConfig c = test::noiseless().world;
  c.systems = SystemSet::all();
  c.atmosphere.ionosphere.source = atmosphere::VtecSource::kFixed;
  c.atmosphere.ionosphere.vtec_tecu = vtec_tecu;
  c.carrier.oscillator_sigma_rad = 0.0;
  c.bands = 2;
  return c;
}

// The ICD carriers, Hz (GPS IS-GPS-200 §3.3.1.1; GLONASS ICD 5.1 §3.3.1.4;
// Galileo OS SIS ICD §2.4; BDS ICD B1I/B2I §4.2), per band.
double icd_carrier_hz(GnssSystem sys, int band, int k) {
  switch (sys) {
    case GnssSystem::kGps: return band == 0 ? 1575.42e6 : 1227.60e6;
    case GnssSystem::kGlonass: return band == 0 ? 1602.0e6 + k * 0.5625e6 : 1246.0e6 + k * 0.4375e6;
    case GnssSystem::kGalileo: return band == 0 ? 1575.42e6 : 1207.14e6;
    case GnssSystem::kBeiDou: return band == 0 ? 1561.098e6 : 1207.14e6;
    default: return 0.0;
  }
}

const world::SatObservable* find(const world::Observables& o, SatId sat) {
  for (int i = 0; i < o.num_sats; ++i)
    if (o.sats[i].sat == sat && o.sats[i].received && o.sats[i].band1.received) return &o.sats[i];
  return nullptr;
}

const time::GpsTime kT = kToe + 60.0;
constexpr double kMask_rad = 5.0 * kDegToRad;

TEST(WorldSecondBandSystems, IonosphereScalesByTheCarrierRatioSquared) {
  const orbit::EphemerisStore store(four_system_sky(0.0, 0.0));
  world::World w(store, dual_band_world(40.0)), w0(store, dual_band_world(0.0));
  const Ecef pos = geo::ecef_from_lla(kSite);
  const world::Observables& a = w.step(kT, truth_at(pos, kT), kMask_rad);
  const world::Observables& z = w0.step(kT, truth_at(pos, kT), kMask_rad);
  std::map<GnssSystem, int> checked;
  std::set<int> channels;
  for (int i = 0; i < a.num_sats; ++i) {
    const world::SatObservable& o = a.sats[i];
    if (!o.received || !o.band1.received) continue;
    const world::SatObservable* o0 = find(z, o.sat);
    ASSERT_NE(o0, nullptr);
    const GnssSystem sys = o.sat.system;
    if (sys == GnssSystem::kQzss || sys == GnssSystem::kSbas) continue;
    const int k = sys == GnssSystem::kGlonass ? channel_of(o.sat.number) : 0;
    const double f1 = icd_carrier_hz(sys, 0, k), f2 = icd_carrier_hz(sys, 1, k);
    // Carriers and wavelengths per band (GLONASS: the satellite's own channel).
    EXPECT_NEAR(o.carrier_hz, f1, 1e-3) << o.sat.number;
    EXPECT_NEAR(o.band1.carrier_hz, f2, 1e-3) << o.sat.number;
    EXPECT_NEAR(o.wavelength_m, kSpeedOfLight_m_s / f1, 1e-12);
    EXPECT_NEAR(o.band1.wavelength_m, kSpeedOfLight_m_s / f2, 1e-12);
    // The same range rate in cycles of each band's carrier.
    EXPECT_NEAR(o.band1.doppler_hz * o.band1.wavelength_m, o.doppler_hz * o.wavelength_m, 1e-6);
    // Code delay of each band from the ionosphere alone, and their ratio.
    const double i1 = o.pseudorange_m - o0->pseudorange_m;
    const double i2 = o.band1.pseudorange_m - o0->band1.pseudorange_m;
    ASSERT_GT(i1, 2.0) << o.sat.number;
    EXPECT_NEAR(i1, w.path_effects(o.sat).iono_m, 1e-6);
    EXPECT_NEAR(i2 / i1, (f1 / f2) * (f1 / f2), 1e-8) << int(sys) << " " << o.sat.number;
    // The phase is advanced by as much as the code is delayed, per band.
    EXPECT_NEAR((o.carrier_phase_cycles - o0->carrier_phase_cycles) * o.wavelength_m, -i1, 1e-6);
    EXPECT_NEAR((o.band1.carrier_phase_cycles - o0->band1.carrier_phase_cycles) * o.band1.wavelength_m, -i2, 1e-6);
    ++checked[sys];
    if (sys == GnssSystem::kGlonass) channels.insert(k);
  }
  for (GnssSystem sys : {GnssSystem::kGps, GnssSystem::kGlonass, GnssSystem::kGalileo, GnssSystem::kBeiDou})
    EXPECT_GE(checked[sys], 3) << int(sys);
  // Several GLONASS channels, negative ones among them.
  EXPECT_GE(channels.size(), 3u);
  EXPECT_LT(*channels.begin(), 0);
}

TEST(WorldSecondBandSystems, EachBandCarriesItsUsersGroupDelay) {
  constexpr double kTgd_s = -7.0e-9, kTgd2_s = 4.0e-9;
  const orbit::EphemerisStore with(four_system_sky(kTgd_s, kTgd2_s)), without(four_system_sky(0.0, 0.0));
  world::World w(with, dual_band_world(20.0)), w0(without, dual_band_world(20.0));
  const Ecef pos = geo::ecef_from_lla(kSite);
  const world::Observables& a = w.step(kT, truth_at(pos, kT), kMask_rad);
  const world::Observables& z = w0.step(kT, truth_at(pos, kT), kMask_rad);
  std::map<GnssSystem, int> checked;
  for (int i = 0; i < a.num_sats; ++i) {
    const world::SatObservable& o = a.sats[i];
    if (!o.received || !o.band1.received) continue;
    const world::SatObservable* o0 = find(z, o.sat);
    ASSERT_NE(o0, nullptr);
    const double d1 = o.pseudorange_m - o0->pseudorange_m;
    const double d2 = o.band1.pseudorange_m - o0->band1.pseudorange_m;
    const double c = kSpeedOfLight_m_s;
    const double gamma_gps = std::pow(1575.42 / 1227.60, 2), gamma_gal = std::pow(1575.42 / 1207.14, 2);
    switch (o.sat.system) {
      case GnssSystem::kGps:  // IS-GPS-200 §20.3.3.3.3.2: L1 TGD, L2 gamma TGD
        EXPECT_NEAR(d1, c * kTgd_s, 1e-6);
        EXPECT_NEAR(d2, gamma_gps * c * kTgd_s, 1e-6);
        break;
      case GnssSystem::kGalileo:  // OS SIS ICD §5.1.5: E1 BGD(E1,E5b), E5b (f1/f2)^2 BGD
        EXPECT_NEAR(d1, c * kTgd_s, 1e-6);
        EXPECT_NEAR(d2, gamma_gal * c * kTgd_s, 1e-6);
        break;
      case GnssSystem::kBeiDou:  // BDS ICD B1I §5.2.4.10: B1I TGD1, B2I TGD2
        EXPECT_NEAR(d1, c * kTgd_s, 1e-6);
        EXPECT_NEAR(d2, c * kTgd2_s, 1e-6);
        break;
      case GnssSystem::kGlonass:  // no group delay in the nav data read; delta tau_n broadcast 0
        EXPECT_NEAR(d1, 0.0, 1e-6);
        EXPECT_NEAR(d2, 0.0, 1e-6);
        break;
      default: continue;
    }
    // A group delay is a clock term: the phase moves with the code.
    EXPECT_NEAR((o.band1.carrier_phase_cycles - o0->band1.carrier_phase_cycles) * o.band1.wavelength_m, d2, 1e-6);
    ++checked[o.sat.system];
  }
  for (GnssSystem sys : {GnssSystem::kGps, GnssSystem::kGlonass, GnssSystem::kGalileo, GnssSystem::kBeiDou})
    EXPECT_GE(checked[sys], 3) << int(sys);
}

TEST(WorldSecondBandSystems, ReceiverBiasDelaysTheSecondCodeOnly) {
  const orbit::EphemerisStore store(four_system_sky(0.0, 0.0));
  world::WorldConfig c = dual_band_world(20.0), c0 = c;
  c.receiver_ifb_m = 1.7;
  c0.receiver_ifb_m = 0.0;
  world::World w(store, c), w0(store, c0);
  const Ecef pos = geo::ecef_from_lla(kSite);
  const world::Observables& a = w.step(kT, truth_at(pos, kT), kMask_rad);
  const world::Observables& z = w0.step(kT, truth_at(pos, kT), kMask_rad);
  int checked = 0;
  for (int i = 0; i < a.num_sats; ++i) {
    const world::SatObservable& o = a.sats[i];
    if (!o.received || !o.band1.received) continue;
    const world::SatObservable* o0 = find(z, o.sat);
    ASSERT_NE(o0, nullptr);
    EXPECT_NEAR(o.pseudorange_m - o0->pseudorange_m, 0.0, 1e-9);
    EXPECT_NEAR(o.band1.pseudorange_m - o0->band1.pseudorange_m, 1.7, 1e-9);
    // Code-phase aligned (as a u-blox F9 reports in 1230): no phase bias, any system or channel.
    EXPECT_NEAR(o.carrier_phase_cycles - o0->carrier_phase_cycles, 0.0, 1e-9);
    EXPECT_NEAR(o.band1.carrier_phase_cycles - o0->band1.carrier_phase_cycles, 0.0, 1e-9);
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

}  // namespace
}  // namespace gnssemu::receiver::second_band_systems

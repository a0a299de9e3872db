// SPDX-License-Identifier: Apache-2.0
// SBAS: the service table, the receiver's decoding of a GEO (C/N0, time to
// the first full set of corrections, time-out, service area), and end to end
// on the 2024-01-10 IGS broadcast file with its GEOs: over Paris the fix turns
// differential once an EGNOS GEO has been decoded for 120 s, GPS satellites
// carry the corrections (the ionosphere after 300 s), and not when SBAS is off,
// not tracked, or the receiver is outside every service area.
#include <gtest/gtest.h>

#include <string>

#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/receiver/tracking/sbas_reception.hpp"
#include "core/world/sky/sbas_service.hpp"

namespace gnssemu::receiver {
namespace {

Lla deg(double lat, double lon) { return Lla{lat * kDegToRad, lon * kDegToRad, 100.0}; }

TEST(SbasService, PrnsAreasAndObliquity) {
  ASSERT_NE(world::sbas_service_of_prn(123), nullptr);
  EXPECT_EQ(world::sbas_service_of_prn(123)->name, "EGNOS");
  EXPECT_EQ(world::sbas_service_of_prn(136)->name, "EGNOS");
  EXPECT_EQ(world::sbas_service_of_prn(131)->name, "WAAS");
  EXPECT_EQ(world::sbas_service_of_prn(138)->name, "WAAS");
  EXPECT_EQ(world::sbas_service_of_prn(139), nullptr);
  EXPECT_EQ(world::sbas_service_of_prn(0), nullptr);
  EXPECT_EQ(world::sbas_service_at(deg(48.87, 2.29))->name, "EGNOS");
  EXPECT_EQ(world::sbas_service_at(deg(40.7, -74.0))->name, "WAAS");
  EXPECT_EQ(world::sbas_service_at(deg(-34.6, -58.4)), nullptr);  // Buenos Aires
  EXPECT_EQ(world::sbas_service_at(deg(0.0, -150.0)), nullptr);   // mid Pacific
  EXPECT_NEAR(world::sbas_obliquity(kPi / 2.0), 1.0, 1e-12);
  const double f5 = world::sbas_obliquity(5.0 * kDegToRad);
  EXPECT_GT(f5, 2.9);
  EXPECT_LT(f5, 3.1);
  EXPECT_FALSE(world::sbas_corrects(GnssSystem::kGlonass));
  EXPECT_TRUE(world::sbas_corrects(GnssSystem::kGps));
}

SatInfo geo(int prn, double cn0_dbhz) {
  SatInfo s;
  s.sat = *SatId::from_prn(GnssSystem::kSbas, prn);
  s.tracked = cn0_dbhz > 0.0;
  s.cn0_dbhz = cn0_dbhz;
  return s;
}

/// Seconds of 1-s epochs until r has orbit/clock corrections (-1: not within n).
int seconds_to_corrections(SbasReception& r, const SatInfo& g, const Lla* pos, int n) {
  for (int k = 0; k < n; ++k) {
    r.step(k == 0 ? 0.0 : 1.0, std::span<const SatInfo>(&g, 1), pos);
    if (r.orbit_clock()) return k;
  }
  return -1;
}

TEST(SbasReception, FirstCorrectionsAfterTheirBroadcastIntervals) {
  const Lla paris = deg(48.87, 2.29);
  SbasReception r;
  const SatInfo g = geo(123, 40.0);
  EXPECT_EQ(seconds_to_corrections(r, g, &paris, 400), static_cast<int>(kSbasFirstCorrections_s));
  EXPECT_EQ(r.service()->name, "EGNOS");
  EXPECT_EQ(r.geo_prn(), 123);
  EXPECT_FALSE(r.iono());
  for (int k = 0; k < 179; ++k) r.step(1.0, std::span<const SatInfo>(&g, 1), &paris);
  EXPECT_FALSE(r.iono());
  r.step(1.0, std::span<const SatInfo>(&g, 1), &paris);
  EXPECT_TRUE(r.iono());  // 300 s decoded
  r.reset();
  EXPECT_FALSE(r.orbit_clock());
  EXPECT_EQ(r.decoded_s(123), 0.0);
}

TEST(SbasReception, NeedsDecodableSignalPositionAndServiceArea) {
  const Lla paris = deg(48.87, 2.29), new_york = deg(40.7, -74.0);
  SbasReception weak, no_pos, wrong_area, waas;
  EXPECT_EQ(seconds_to_corrections(weak, geo(123, kSbasDecodeCn0_dbhz - 1.0), &paris, 400), -1);
  EXPECT_EQ(seconds_to_corrections(no_pos, geo(123, 40.0), nullptr, 400), -1);
  EXPECT_EQ(seconds_to_corrections(wrong_area, geo(123, 40.0), &new_york, 400), -1);  // EGNOS GEO over New York
  EXPECT_EQ(seconds_to_corrections(waas, geo(133, 40.0), &new_york, 400), 120);
  EXPECT_EQ(waas.service()->name, "WAAS");
  SbasReception not_sbas;
  SatInfo gps;
  gps.sat = SatId::gps(5);
  gps.tracked = true;
  gps.cn0_dbhz = 45.0;
  EXPECT_EQ(seconds_to_corrections(not_sbas, gps, &paris, 400), -1);
}

TEST(SbasReception, GapsWithinTheTimeOutKeepTheSetLongerOnesLoseIt) {
  const Lla paris = deg(48.87, 2.29);
  const SatInfo g = geo(136, 40.0);
  const std::span<const SatInfo> on(&g, 1), off;
  SbasReception r;
  ASSERT_EQ(seconds_to_corrections(r, g, &paris, 400), 120);
  for (int k = 0; k < static_cast<int>(kSbasTimeout_s); ++k) r.step(1.0, off, &paris);
  EXPECT_TRUE(r.orbit_clock());  // 18 s silent: still within the time-out
  r.step(1.0, off, &paris);
  EXPECT_FALSE(r.orbit_clock());
  r.step(1.0, on, &paris);
  EXPECT_FALSE(r.orbit_clock());  // the set is received again from the start
  EXPECT_EQ(r.decoded_s(136), 0.0);
}

struct SbasRun {
  int first_diff = -1;   ///< epoch of the first differential fix (-1: none)
  int first_iono = -1;   ///< epoch a used satellite first has the SBAS ionosphere
  int diff_epochs = 0;
  int corrected_non_gps = 0;  ///< used satellites of other systems flagged corrected
  bool flags_consistent = true;
  std::string service;
};

SbasRun sbas_run(const Lla& where, SystemSet systems, bool sbas, int epochs, int switch_off_at = -1) {
  static const orbit::NavData nav =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  static const orbit::EphemerisStore store(nav.ephemerides);
  pipeline::PipelineConfig c;
  c.world.systems = systems;
  c.receiver.sbas = sbas;
  pipeline::Pipeline rx(store, c);
  world::Truth truth;
  truth.valid = true;
  truth.pos_m = geo::ecef_from_lla(where);
  const time::GpsTime t0 = time::GpsTime::from_calendar({2024, 1, 10, 1, 30, 0.0});
  SbasRun r;
  for (int k = 0; k < epochs; ++k) {
    if (k == switch_off_at) rx.receiver().set_sbas(false);
    truth.t = t0 + static_cast<double>(k);
    const Fix& f = rx.step(truth.t, truth);
    bool any_corr = false;
    for (int i = 0; i < f.num_sats; ++i) {
      const SatInfo& s = f.sats[i];
      if (!s.used || !s.sbas_corr) continue;
      any_corr = true;
      if (s.sat.system != GnssSystem::kGps) ++r.corrected_non_gps;
      if (s.sbas_iono && r.first_iono < 0) r.first_iono = k;
    }
    if (f.diff_soln != any_corr || f.sbas_soln != f.diff_soln) r.flags_consistent = false;
    if (f.diff_soln && (f.ref_station_id != 0 || f.corr_age_s >= 0.0)) r.flags_consistent = false;
    if (!f.diff_soln) continue;
    ++r.diff_epochs;
    if (r.first_diff < 0) r.first_diff = k;
    if (rx.receiver().sbas().service() != nullptr) r.service = std::string(rx.receiver().sbas().service()->name);
  }
  return r;
}

const SystemSet kGpsSbas = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kSbas);

TEST(SbasReceiver, ParisGetsEgnosAfterTheFirstFullSet) {
  const SbasRun r = sbas_run(deg(48.8738, 2.2950), kGpsSbas, true, 420);
  EXPECT_TRUE(r.flags_consistent);
  EXPECT_GE(r.first_diff, static_cast<int>(kSbasFirstCorrections_s));
  EXPECT_LE(r.first_diff, static_cast<int>(kSbasFirstCorrections_s) + 60);  // plus the GEO's acquisition
  EXPECT_EQ(r.diff_epochs, 420 - r.first_diff);  // then every epoch
  EXPECT_EQ(r.first_iono - r.first_diff, static_cast<int>(kSbasFirstIono_s - kSbasFirstCorrections_s));
  EXPECT_EQ(r.service, "EGNOS");
  EXPECT_EQ(r.corrected_non_gps, 0);
}

TEST(SbasReceiver, HostTurningItOffEndsTheDifferentialFix) {
  const SbasRun late = sbas_run(deg(48.8738, 2.2950), kGpsSbas, true, 300, 250);
  EXPECT_TRUE(late.flags_consistent);
  EXPECT_GT(late.diff_epochs, 0);
  EXPECT_EQ(late.first_diff + late.diff_epochs, 250);  // none from the epoch the host turned it off
}

TEST(SbasReceiver, OffNotTrackedOrOutsideEveryAreaMeansNoCorrections) {
  EXPECT_EQ(sbas_run(deg(48.8738, 2.2950), kGpsSbas, false, 300).diff_epochs, 0);                    // [receiver] sbas = false
  EXPECT_EQ(sbas_run(deg(48.8738, 2.2950), SystemSet::only(GnssSystem::kGps), true, 300).diff_epochs, 0);  // no GEO tracked
  EXPECT_EQ(sbas_run(deg(-34.6, -58.4), kGpsSbas, true, 300).diff_epochs, 0);                        // Buenos Aires: no service
}

}  // namespace
}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
// Faults per system: a jammer hurts a satellite through the overlap of its
// spectrum with that satellite's main lobe; a spoofer forges the systems it
// is given and leaves the others authentic.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/common/gnss_systems.hpp"
#include "core/faults/fault_stage.hpp"
#include "core/faults/interference.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/signal/system_signal.hpp"

namespace gnssemu::faults {
namespace {

FaultEvent event(FaultType type, int mode = 0) { return FaultEvent::of(type, 0.0, kForever_s, static_cast<std::uint8_t>(mode)); }

// One received satellite per system of interest, all at 45 dB-Hz.
world::Observables sky() {
  world::Observables obs;
  obs.antenna_connected = true;
  const SatId sats[] = {SatId(GnssSystem::kGps, 5),     SatId(GnssSystem::kGps, 12),
                        SatId(GnssSystem::kGlonass, 3), SatId(GnssSystem::kGalileo, 11),
                        SatId(GnssSystem::kBeiDou, 19), SatId(GnssSystem::kGlonass, 9)};
  const int channels[] = {0, 0, -7, 0, 0, 6};
  for (int i = 0; i < 6; ++i) {
    world::SatObservable& o = obs.sats[static_cast<std::size_t>(obs.num_sats++)];
    o.sat = sats[i];
    o.az_rad = 0.5 * i;
    o.el_rad = 0.3 + 0.1 * i;
    o.above_mask = o.received = true;
    o.cn0_dbhz = 45.0;
    o.pseudorange_m = 2.2e7;
    o.carrier_hz = l1_carrier_hz(o.sat.system, channels[i]);
    o.wavelength_m = kSpeedOfLight_m_s / o.carrier_hz;
  }
  return obs;
}

world::Observables after(const std::vector<FaultEvent>& events) {
  FaultStage stage(FaultContext{}, events);
  world::Observables obs = sky();
  world::Truth truth;
  truth.valid = true;
  truth.pos_m = Ecef(4.2e6, 0.17e6, 4.78e6);
  stage.apply(time::GpsTime(2300, 1000.0), truth, obs);
  return obs;
}

TEST(InterferenceBands, OverlapOfALineAndOfABand) {
  const SignalBand ca{kL1Freq_hz, kCaChipRate_hz};
  EXPECT_EQ(band_overlap_fraction({kL1Freq_hz, 0.0}, ca), 1.0);
  EXPECT_EQ(band_overlap_fraction({kL1Freq_hz + 1.0e6, 0.0}, ca), 1.0);
  EXPECT_EQ(band_overlap_fraction({kL1Freq_hz + 1.1e6, 0.0}, ca), 0.0);
  EXPECT_DOUBLE_EQ(band_overlap_fraction({kL1Freq_hz, 20.0e6}, ca), 2.046e6 / 20.0e6);
  EXPECT_DOUBLE_EQ(band_overlap_fraction({kL1Freq_hz + 1.023e6, 2.046e6}, ca), 0.5);
  const SignalBand b1i{l1_carrier_hz(GnssSystem::kBeiDou), signal::system_signal(GnssSystem::kBeiDou).main_lobe_half_width_hz};
  EXPECT_EQ(band_overlap_fraction({kL1Freq_hz, 2.046e6}, b1i), 0.0);
  EXPECT_GT(band_overlap_fraction({kL1Freq_hz, 50.0e6}, b1i), 0.0);
}

TEST(InterferenceBands, DefaultBandsKeepTheCaRelation) {
  const SignalBand ca{kL1Freq_hz, kCaChipRate_hz};
  const double j_w = 1e-12;
  for (JammerKind k : {JammerKind::kWideband, JammerKind::kNarrowband, JammerKind::kCw}) {
    EXPECT_EQ(interference_density_w_hz(j_w, k, {kL1Freq_hz, default_jammer_width_hz(k)}, ca),
              interference_density_w_hz_of_w(j_w, k));
  }
  // Wider noise of the same power spreads thinner.
  EXPECT_DOUBLE_EQ(interference_density_w_hz(j_w, JammerKind::kWideband, {kL1Freq_hz, 20.46e6}, ca),
                   interference_density_w_hz_of_w(j_w, JammerKind::kWideband) / 10.0);
}

TEST(FaultSystems, NarrowbandJammerAtL1LeavesG1AndB1IAlone) {
  FaultEvent e = event(FaultType::kJammer, static_cast<int>(JammerKind::kNarrowband));
  e.put(Param::kJsDb, 40.0);
  const world::Observables obs = after({e});
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[static_cast<std::size_t>(i)];
    const bool hit = o.sat.system == GnssSystem::kGps || o.sat.system == GnssSystem::kGalileo;
    if (hit) {
      EXPECT_LT(o.cn0_dbhz, 40.0) << sat_name(o.sat).data();
    } else {
      EXPECT_EQ(o.cn0_dbhz, 45.0) << sat_name(o.sat).data();
    }
  }
}

TEST(FaultSystems, JammerOnAGlonassChannelHitsThatChannelOnly) {
  FaultEvent e = event(FaultType::kJammer, static_cast<int>(JammerKind::kCw));
  e.put(Param::kJsDb, 40.0);
  e.put(Param::kFreqMhz, l1_carrier_hz(GnssSystem::kGlonass, -7) * 1e-6);
  const world::Observables obs = after({e});
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[static_cast<std::size_t>(i)];
    if (o.sat == SatId(GnssSystem::kGlonass, 3)) {
      EXPECT_LT(o.cn0_dbhz, 40.0);
    } else {
      EXPECT_EQ(o.cn0_dbhz, 45.0) << sat_name(o.sat).data();
    }
  }
}

TEST(FaultSystems, WidebandJammerHitsEverySystemItCovers) {
  // At L1, B1I's lobe is reached from 24.6 MHz of width on, G1 channel -7's
  // from 44.3 MHz, channel +6's from 58.9 MHz.
  FaultEvent e = event(FaultType::kJammer, static_cast<int>(JammerKind::kWideband));
  e.put(Param::kJsDb, 60.0);
  e.put(Param::kBandwidthMhz, 80.0);
  const world::Observables all = after({e});
  for (int i = 0; i < all.num_sats; ++i) EXPECT_LT(all.sats[static_cast<std::size_t>(i)].cn0_dbhz, 44.0);
  e.put(Param::kBandwidthMhz, 50.0);
  const world::Observables most = after({e});
  for (int i = 0; i < most.num_sats; ++i) {
    const world::SatObservable& o = most.sats[static_cast<std::size_t>(i)];
    if (o.sat == SatId(GnssSystem::kGlonass, 9)) {
      EXPECT_EQ(o.cn0_dbhz, 45.0);  // channel +6, 1605.375 MHz
    } else {
      EXPECT_LT(o.cn0_dbhz, 44.0) << sat_name(o.sat).data();
    }
  }
}

TEST(FaultSystems, GpsOnlySpooferLeavesTheOtherSystemsAuthentic) {
  FaultEvent e = event(FaultType::kSpoofer, static_cast<int>(SpoofMode::kTakeover));
  e.put(Param::kOffsetEastM, 500.0);
  e.put(Param::kClockJumpUs, 1.0);
  const world::Observables clean = sky();
  const world::Observables obs = after({e});  // default systems: GPS
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[static_cast<std::size_t>(i)];
    const world::SatObservable& c = clean.sats[static_cast<std::size_t>(i)];
    if (o.sat.system == GnssSystem::kGps) {
      EXPECT_GT(std::fabs(o.pseudorange_m - c.pseudorange_m), 1.0);
      EXPECT_GT(o.cn0_dbhz, c.cn0_dbhz);
    } else {
      EXPECT_EQ(o.pseudorange_m, c.pseudorange_m) << sat_name(o.sat).data();
      EXPECT_EQ(o.cn0_dbhz, c.cn0_dbhz);
    }
  }
  e.put(Param::kSystems, static_cast<double>(SystemSet::all().bits()));
  const world::Observables all = after({e});
  for (int i = 0; i < all.num_sats; ++i)
    EXPECT_GT(std::fabs(all.sats[static_cast<std::size_t>(i)].pseudorange_m - 2.2e7), 1.0);
}

TEST(FaultSystems, SpooferSystemsInTheScenarioWords) {
  FaultEvent e = event(FaultType::kSpoofer);
  EXPECT_EQ(describe(e, 0.0), "mode=drag");
  e.put(Param::kSystems, static_cast<double>(SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGalileo).bits()));
  EXPECT_EQ(describe(e, 0.0), "mode=drag systems=G,E");
  EXPECT_FALSE(check_event(e));
  e.put(Param::kSystems, 0.0);
  EXPECT_TRUE(check_event(e));
}

// The whole pipeline with four systems on the IGS broadcast file: a GPS-only
// takeover moves the GPS ranges alone: the solution's fault exclusion throws
// the (fewer) GPS satellites out, and the spoof monitor's system test (the
// only criterion left on here) reports it; a spoofer of every system moves
// all ranges together and shows nothing.
int system_indications(SystemSet forged) {
  static const orbit::NavData nav =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  static const orbit::EphemerisStore store(nav.ephemerides);
  pipeline::PipelineConfig c;
  c.world.systems = SystemSet(0).with(GnssSystem::kGps).with(GnssSystem::kGlonass).with(GnssSystem::kGalileo).with(
      GnssSystem::kBeiDou);
  receiver::SpoofDetectionConfig& sd = c.receiver.spoof_detection;
  sd.cn0_jump_db = 60.0;
  sd.clock_jump_m = 3.0e8;
  sd.uniform_std_db = 0.0;
  pipeline::Pipeline rx(store, c);
  FaultEvent e = event(FaultType::kSpoofer, static_cast<int>(SpoofMode::kTakeover));
  e.start_s = 60.0;
  e.put(Param::kOffsetEastM, 400.0);
  e.put(Param::kOffsetNorthM, 300.0);
  e.put(Param::kPowerAdvantageDb, 10.0);
  e.put(Param::kSystems, static_cast<double>(forged.bits()));
  rx.set_faults(std::vector<FaultEvent>{e});
  world::Truth truth;
  truth.valid = true;
  truth.pos_m = geo::ecef_from_lla(Lla{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0});
  time::GpsTime t0;
  for (const orbit::Ephemeris& eph : nav.ephemerides)
    if (eph.sat.system == GnssSystem::kGps) t0 = eph.toe + 3600.0;  // within every system's data
  int flagged = 0;
  for (int k = 0; k < 120; ++k) {
    truth.t = t0 + static_cast<double>(k);
    const receiver::Fix& f = rx.step(truth.t, truth);
    if (k < 60) {
      EXPECT_EQ(f.spoof_det_state, 1) << k;
    } else if (f.spoof_det_state >= 2) {
      ++flagged;
    }
  }
  return flagged;
}

TEST(FaultSystems, GpsOnlySpooferDisagreesWithTheOtherSystems) {
  EXPECT_GT(system_indications(SystemSet::only(GnssSystem::kGps)), 30);
  EXPECT_EQ(system_indications(SystemSet::all()), 0);
}

}  // namespace
}  // namespace gnssemu::faults

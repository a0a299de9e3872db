// SPDX-License-Identifier: Apache-2.0
// The second frequency: a dual-band world gives each satellite's second
// signal the ionosphere scaled by (f1/f2)^2 (code delayed, phase advanced),
// the broadcast group delay of its users, the receiver's inter-frequency
// bias and the C/N0 of its minimum received power; the receiver reports
// both bands in SatId then band order, the second after its aided pull-in.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/common/gnss_signals.hpp"
#include "core/geo/geodesy.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/world/world.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver {
namespace {

using test::kSite;
using test::kToe;
using test::truth_at;

constexpr double kTgd_s = -11.0e-9;

std::vector<orbit::Ephemeris> sky_with_tgd() {
  std::vector<orbit::Ephemeris> v = test::nominal_constellation(kToe, 4);
  for (orbit::Ephemeris& e : v) e.tgd_s = kTgd_s;
  return v;
}

world::WorldConfig dual_band_world() {
  world::WorldConfig c = test::noiseless().world;
  c.atmosphere.ionosphere.source = atmosphere::VtecSource::kFixed;
  c.carrier.oscillator_sigma_rad = 0.0;
  c.bands = 2;
  return c;
}

TEST(WorldSecondBand, IonosphereGroupDelayBiasAndPower) {
  const orbit::EphemerisStore store(sky_with_tgd());
  const world::WorldConfig c = dual_band_world();
  world::World w(store, c);
  const Ecef pos = geo::ecef_from_lla(kSite);
  const time::GpsTime t = kToe + 60.0;
  const world::Observables& obs = w.step(t, truth_at(pos, t), 5.0 * kDegToRad);
  const double lambda2 = kSpeedOfLight_m_s / 1227.60e6;
  const double gamma = std::pow(77.0 / 60.0, 2);
  int checked = 0;
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[i];
    if (!o.received) continue;
    const world::SecondSignal& b = o.band1;
    ASSERT_TRUE(b.received);
    const double i1 = w.path_effects(o.sat).iono_m;
    ASSERT_GT(i1, 0.5);
    EXPECT_DOUBLE_EQ(b.carrier_hz, 1227.60e6);
    EXPECT_NEAR(b.wavelength_m, lambda2, 1e-15);
    // Code: (gamma - 1) (I1 + c TGD) more, plus the receiver's bias.
    EXPECT_NEAR(b.pseudorange_m - o.pseudorange_m,
                (gamma - 1.0) * (i1 + kSpeedOfLight_m_s * kTgd_s) + c.receiver_ifb_m, 1e-6);
    // Phase: advanced by gamma I1 below the code without the bias, up to a whole number of cycles.
    const double n2 = (b.carrier_phase_cycles * lambda2 - (b.pseudorange_m - c.receiver_ifb_m - 2.0 * gamma * i1)) / lambda2;
    EXPECT_NEAR(n2, std::round(n2), 0.02) << o.sat.number;
    EXPECT_NEAR(b.doppler_hz * lambda2, o.doppler_hz * o.wavelength_m, 1e-6);
    EXPECT_NEAR(b.cn0_dbhz - o.cn0_dbhz, -163.0 + 158.5, 1e-9);  // L2CL (half of L2C) vs L1 C/A
    EXPECT_TRUE(b.carrier_valid);
    ++checked;
  }
  EXPECT_GE(checked, 5);

  // A single-band world leaves the second signal out.
  world::WorldConfig one = c;
  one.bands = 1;
  world::World w1(store, one);
  const world::Observables& o1 = w1.step(t, truth_at(pos, t), 5.0 * kDegToRad);
  for (int i = 0; i < o1.num_sats; ++i) EXPECT_FALSE(o1.sats[i].band1.received);
}

TEST(WorldSecondBand, GroupDelaysPerSystem) {
  orbit::Ephemeris e = test::base_eph(1, kToe);
  e.tgd_s = 2.0e-9;
  e.tgd2_s = 5.0e-9;
  const double g = 1.5;
  EXPECT_DOUBLE_EQ(orbit::band1_group_delay_s(e, g), 3.0e-9);
  e.sat = SatId(GnssSystem::kGalileo, 1);
  EXPECT_DOUBLE_EQ(orbit::band1_group_delay_s(e, g), 3.0e-9);
  e.sat = SatId(GnssSystem::kBeiDou, 20);
  EXPECT_DOUBLE_EQ(orbit::band1_group_delay_s(e, g), 5.0e-9);
  e.sat = SatId(GnssSystem::kGlonass, 1);
  EXPECT_DOUBLE_EQ(orbit::band1_group_delay_s(e, g), 0.0);
  EXPECT_DOUBLE_EQ(band1_power_offset_db(GnssSystem::kGalileo), 2.0);
  EXPECT_DOUBLE_EQ(band1_power_offset_db(GnssSystem::kGlonass), -6.0);
  EXPECT_DOUBLE_EQ(band1_power_offset_db(GnssSystem::kSbas), 0.0);
}

TEST(ReceiverSecondBand, BothBandsInOrderAfterTheAidedPullIn) {
  const orbit::EphemerisStore store(sky_with_tgd());
  pipeline::PipelineConfig c = test::noiseless();
  c.receiver.bands = 2;
  pipeline::Pipeline rx(store, c);
  const Ecef pos = geo::ecef_from_lla(kSite);
  // First epoch: L1 only (the second signal is still pulled in).
  rx.step(kToe, truth_at(pos, kToe));
  const RawEpoch& first = rx.receiver().raw();
  ASSERT_GT(first.num_meas, 4);
  for (int i = 0; i < first.num_meas; ++i) EXPECT_EQ(signal_info(first.meas[i].signal).band, 0);
  for (int k = 1; k <= 8; ++k) rx.step(kToe + k, truth_at(pos, kToe + k));
  const RawEpoch& raw = rx.receiver().raw();
  int l1 = 0, l2 = 0;
  for (int i = 0; i < raw.num_meas; ++i) {
    const RawMeasurement& m = raw.meas[i];
    if (i > 0) {
      const RawMeasurement& p = raw.meas[i - 1];
      EXPECT_TRUE(p.sat < m.sat || (p.sat == m.sat && signal_info(p.signal).band < signal_info(m.signal).band));
    }
    if (m.signal == SignalId::kGpsL1CA) {
      ++l1;
      EXPECT_DOUBLE_EQ(m.lock_time_s, 8.0);
      EXPECT_TRUE(m.half_cycle_resolved);
    } else {
      ASSERT_EQ(m.signal, SignalId::kGpsL2CL);
      ++l2;
      EXPECT_DOUBLE_EQ(m.lock_time_s, 7.0);  // locked one pull-in later
      EXPECT_TRUE(m.half_cycle_resolved);    // a pilot: no half-cycle ambiguity
      EXPECT_TRUE(m.carrier_valid);
    }
  }
  EXPECT_EQ(l1, l2);
  EXPECT_GT(l2, 4);
}

}  // namespace
}  // namespace gnssemu::receiver

// SPDX-License-Identifier: Apache-2.0
// The RINEX 3.04 writers read back through the project's own readers:
// observation epochs value for value, navigation sets field for field and
// satellite positions to below a millimetre.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "core/observation/rinex_obs.hpp"
#include "core/common/constants.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/rinex/rinex_nav_writer.hpp"
#include "core/rinex/rinex_obs_writer.hpp"

namespace gnssemu::rinex {
namespace {

receiver::RawMeasurement meas(SatId sat, SignalId sig, double pr_m, double lock_s, bool half_resolved) {
  receiver::RawMeasurement m;
  m.sat = sat;
  m.signal = sig;
  m.pseudorange_m = pr_m;
  m.carrier_phase_cycles = pr_m / (kSpeedOfLight_m_s / signal_carrier_hz(sig)) + 1234.0;
  m.doppler_hz = -1234.567;
  m.cn0_dbhz = 44.25;
  m.lock_time_s = lock_s;
  m.pseudorange_valid = true;
  m.carrier_valid = true;
  m.half_cycle_resolved = half_resolved;
  return m;
}

receiver::RawEpoch epoch_at(double tow_s, double lock_s) {
  receiver::RawEpoch e;
  e.t_rx = time::GpsTime(2313, tow_s);
  e.time_valid = true;
  const SatId g5(GnssSystem::kGps, 5), r7(GnssSystem::kGlonass, 7), e11(GnssSystem::kGalileo, 11),
      c20(GnssSystem::kBeiDou, 20);
  int n = 0;
  e.meas[n++] = meas(g5, SignalId::kGpsL1CA, 21000123.456, lock_s, true);
  e.meas[n++] = meas(g5, SignalId::kGpsL2CL, 21000127.789, lock_s, true);
  e.meas[n] = meas(r7, SignalId::kGloL1OF, 19500000.001, lock_s, false);
  e.meas[n++].glonass_channel = -4;
  e.meas[n++] = meas(e11, SignalId::kGalE1C, 24000000.5, lock_s, true);
  e.meas[n++] = meas(c20, SignalId::kBdsB1I, 22000000.25, lock_s, true);
  e.meas[n++] = meas(c20, SignalId::kBdsB2I, 22000003.75, lock_s, true);
  e.num_meas = n;
  return e;
}

ObsHeaderInfo header_info(int bands) {
  ObsHeaderInfo h;
  h.marker_name = "TESTMARK";
  h.receiver_type = "U-BLOX ZED-F9P";
  h.approx_pos_m = Ecef(4201575.8, 189144.7, 4779065.2);
  h.interval_s = 1.0;
  h.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGlonass).with(GnssSystem::kGalileo).with(GnssSystem::kBeiDou);
  h.num_bands = bands;
  h.glonass_channels = {{1, 1}, {2, -4}, {3, 5}, {4, 6}, {5, 1}, {6, -4}, {7, 5}, {8, 6}, {9, -2}};
  h.leap_seconds = 18;
  return h;
}

TEST(RinexObsWriter, DualBandEpochsReadBackValueForValue) {
  std::stringstream s;
  ObsWriter w(s, header_info(2));
  w.write(epoch_at(3600.0001234, 0.0));
  w.write(epoch_at(3601.0001234, 1.0));
  w.finish();
  const observation::ObsData d = observation::read_rinex_obs(s, "written.rnx");
  EXPECT_EQ(d.header.marker_name, "TESTMARK");
  EXPECT_EQ(d.header.receiver_type, "U-BLOX ZED-F9P");
  ASSERT_TRUE(d.header.approx_pos_m);
  EXPECT_NEAR(d.header.approx_pos_m->x, 4201575.8, 1e-4);
  ASSERT_TRUE(d.header.first_obs);
  EXPECT_NEAR(*d.header.first_obs - time::GpsTime(2313, 3600.0001234), 0.0, 1e-7);
  EXPECT_EQ(d.header.types_of(GnssSystem::kGps),
            (std::vector<std::string>{"C1C", "L1C", "D1C", "S1C", "C2L", "L2L", "D2L", "S2L"}));
  EXPECT_EQ(d.header.types_of(GnssSystem::kGalileo)[4], "C7Q");
  EXPECT_EQ(d.header.types_of(GnssSystem::kBeiDou)[0], "C2I");
  EXPECT_EQ(d.header.types_of(GnssSystem::kBeiDou)[4], "C7I");
  ASSERT_EQ(d.epochs.size(), 2u);
  const receiver::RawEpoch want = epoch_at(3601.0001234, 1.0);
  for (std::size_t k = 0; k < 2; ++k) {
    const observation::ObsEpoch& ep = d.epochs[k];
    ASSERT_EQ(ep.sats.size(), 4u);
    EXPECT_NEAR(ep.t - time::GpsTime(2313, 3600.0001234 + static_cast<double>(k)), 0.0, 1e-7);
    for (int i = 0; i < want.num_meas; ++i) {
      const receiver::RawMeasurement& m = want.meas[static_cast<std::size_t>(i)];
      const observation::SatObs* so = nullptr;
      for (const observation::SatObs& x : ep.sats) {
        if (x.sat == m.sat) so = &x;
      }
      ASSERT_NE(so, nullptr);
      const std::string code(signal_info(m.signal).rinex_code, 2);
      const observation::ObsValue* c = so->get(d.header.type_index(m.sat.system, "C" + code));
      const observation::ObsValue* l = so->get(d.header.type_index(m.sat.system, "L" + code));
      const observation::ObsValue* dop = so->get(d.header.type_index(m.sat.system, "D" + code));
      ASSERT_TRUE(c && l && dop);
      EXPECT_NEAR(c->value, m.pseudorange_m, 5e-4);
      EXPECT_NEAR(l->value, m.carrier_phase_cycles, 5e-4);
      EXPECT_NEAR(dop->value, m.doppler_hz, 5e-4);
      EXPECT_EQ(c->ssi, 7);
      // New lock at the first epoch: slip bit; GLONASS's half cycle unresolved.
      const int half = m.sat.system == GnssSystem::kGlonass ? 2 : 0;
      EXPECT_EQ(l->lli, (k == 0 ? 1 : 0) | half) << m.sat.number << " epoch " << k;
    }
  }
}

TEST(RinexObsWriter, SingleBandHasOnlyTheL1Types) {
  std::stringstream s;
  ObsWriter w(s, header_info(1));
  w.write(epoch_at(100.0, 3.0));
  w.finish();
  const observation::ObsData d = observation::read_rinex_obs(s, "written.rnx");
  EXPECT_EQ(d.header.types_of(GnssSystem::kGps), (std::vector<std::string>{"C1C", "L1C", "D1C", "S1C"}));
  ASSERT_EQ(d.epochs.size(), 1u);
  EXPECT_EQ(d.epochs[0].sats.size(), 4u);
  const std::string text = s.str();
  EXPECT_NE(text.find("R02 -4 R03  5"), std::string::npos);
  EXPECT_NE(text.find("GLONASS COD/PHS/BIS"), std::string::npos);
  EXPECT_NE(text.find("G L1C  0.00000"), std::string::npos);
}

TEST(RinexObsWriter, LockIndicatorFollowsLockTimeAndHalfCycle) {
  receiver::RawMeasurement m;
  m.carrier_valid = true;
  m.half_cycle_resolved = true;
  m.lock_time_s = 5.0;
  EXPECT_EQ(loss_of_lock_indicator(m, 4.0), 0);
  EXPECT_EQ(loss_of_lock_indicator(m, 6.0), 1);  // shorter than before: a slip in between
  m.lock_time_s = 0.0;
  EXPECT_EQ(loss_of_lock_indicator(m, -1.0), 1);
  m.lock_time_s = 2.0;
  m.half_cycle_resolved = false;
  EXPECT_EQ(loss_of_lock_indicator(m, 1.0), 2);
  EXPECT_EQ(signal_strength_indicator(44.0), 7);
  EXPECT_EQ(signal_strength_indicator(60.0), 9);
  EXPECT_EQ(signal_strength_indicator(0.0), 0);
}

TEST(RinexNavWriter, MixedFileReadsBackFieldForField) {
  const orbit::NavData in =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240010000_01D_MN_08-14h.rnx.gz");
  ASSERT_GT(in.ephemerides.size(), 100u);
  std::stringstream s;
  write_nav(s, in);
  const orbit::NavData out = orbit::read_rinex_nav(s, "written.rnx");
  ASSERT_EQ(out.ephemerides.size(), in.ephemerides.size());
  EXPECT_EQ(out.klobuchar.valid, in.klobuchar.valid);
  for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(out.klobuchar.alpha[static_cast<std::size_t>(k)],
                                               in.klobuchar.alpha[static_cast<std::size_t>(k)]);
  EXPECT_EQ(out.beidou_klobuchar.valid, in.beidou_klobuchar.valid);
  EXPECT_EQ(out.galileo_nequick.valid, in.galileo_nequick.valid);
  EXPECT_EQ(out.leap_seconds, in.leap_seconds);
  int systems_seen[kNumSystems] = {};
  for (std::size_t i = 0; i < in.ephemerides.size(); ++i) {
    const orbit::Ephemeris& a = in.ephemerides[i];
    const orbit::Ephemeris& b = out.ephemerides[i];
    ASSERT_EQ(a.sat, b.sat);
    ++systems_seen[static_cast<std::size_t>(a.sat.system)];
    EXPECT_EQ(a.toe, b.toe) << i;
    EXPECT_EQ(a.toc, b.toc) << i;
    EXPECT_EQ(a.iode, b.iode) << i;
    EXPECT_EQ(a.iodc, b.iodc) << i;
    EXPECT_EQ(a.health, b.health) << i;
    EXPECT_EQ(a.glo_channel, b.glo_channel) << i;
    EXPECT_EQ(a.gal_data_sources, b.gal_data_sources) << i;
    EXPECT_EQ(a.tgd_s, b.tgd_s) << i;
    EXPECT_EQ(a.tgd2_s, b.tgd2_s) << i;
    EXPECT_EQ(a.transmit_known, b.transmit_known) << i;
    EXPECT_NEAR(a.transmit_tow_s, b.transmit_tow_s, 1e-3) << i;
    const time::GpsTime t = a.toe + 600.0;
    const orbit::SatState sa = orbit::sat_state(a, t), sb = orbit::sat_state(b, t);
    EXPECT_LT((sa.pos_m - sb.pos_m).norm(), 1e-3) << i;
    EXPECT_NEAR(sa.clk_bias_s, sb.clk_bias_s, 1e-14) << i;
  }
  for (GnssSystem sys : {GnssSystem::kGps, GnssSystem::kGlonass, GnssSystem::kGalileo, GnssSystem::kBeiDou}) {
    EXPECT_GT(systems_seen[static_cast<std::size_t>(sys)], 0) << system_name(sys);
  }
}

}  // namespace
}  // namespace gnssemu::rinex

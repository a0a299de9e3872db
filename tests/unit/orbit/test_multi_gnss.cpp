// SPDX-License-Identifier: Apache-2.0
// Per-system cases checked by hand: GLONASS (reader, RK4 step size, clock),
// BeiDou (BDT times, the GEO frame), Galileo (I/NAV selection, E1 health,
// toe < t), SBAS (polynomial), the store's per-system windows and the
// reader's per-system bookkeeping.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>

#include "core/common/constants.hpp"
#include "core/orbit/constellation.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/time/utc.hpp"
#include "orbit_test_data.hpp"

using namespace gnssemu;
using namespace gnssemu::orbit;

namespace {

const NavData& igs() {
  static const NavData d = read_rinex_nav(test::kNav + "BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  return d;
}

const Ephemeris& first_of(SatId sat) {
  for (const Ephemeris& e : igs().ephemerides)
    if (e.sat == sat) return e;
  throw std::runtime_error("no set");
}

time::GpsTime gps_cal(int y, int mo, int d, int h, int mi, double s) {
  return time::GpsTime::from_calendar({y, mo, d, h, mi, s});
}

}  // namespace

TEST(MultiGnss, SystemsInTheIgsFile) {
  std::array<int, kNumSystems> n{};
  for (const Ephemeris& e : igs().ephemerides) ++n[static_cast<std::size_t>(e.sat.system)];
  for (int k : n) EXPECT_GT(k, 0);
  EXPECT_TRUE(igs().beidou_klobuchar.valid);
  EXPECT_DOUBLE_EQ(igs().beidou_klobuchar.alpha[0], 3.8184e-08);
  EXPECT_TRUE(igs().galileo_nequick.valid);
}

// R01 2024 01 10 00 15 00 (UTC): tb = 00:15:18 GPST (18 leap seconds);
// tb index (UTC + 3 h) / 15 min = 13; -tau_n and +gamma_n as the file gives
// them; km -> m; frame time 259200 s of the UTC week = 00:00:00 UTC.
TEST(MultiGnss, GlonassRecordRinex3) {
  const Ephemeris& e = first_of(SatId(GnssSystem::kGlonass, 1));
  ASSERT_EQ(e.toe, gps_cal(2024, 1, 10, 0, 15, 18.0)) << time::calendar_text(e.toe);
  EXPECT_EQ(e.toc, e.toe);
  EXPECT_EQ(e.iode, 13);
  EXPECT_DOUBLE_EQ(e.tau_n_s, -7.418449968100E-05);
  EXPECT_DOUBLE_EQ(e.gamma_n, 9.094947017729E-13);
  EXPECT_DOUBLE_EQ(e.pos_m.x, 1.418167333984E+07);
  EXPECT_DOUBLE_EQ(e.vel_m_s.z, 2.263110160828E+03);
  EXPECT_DOUBLE_EQ(e.acc_m_s2.z, 3.725290298462E-06);
  EXPECT_EQ(e.glo_channel, 1);
  EXPECT_EQ(e.health, 0);
  ASSERT_TRUE(e.transmit_known);
  EXPECT_DOUBLE_EQ(e.transmit_tow_s, 3 * 86400.0 + 18.0);
  // Clock: -tau_n + gamma_n (t - tb), no relativistic term.
  const SatState s = sat_state(e, e.toe + 600.0);
  EXPECT_DOUBLE_EQ(s.clk_bias_s, 7.418449968100E-05 + 9.094947017729E-13 * 600.0);
  EXPECT_EQ(s.relativity_s, 0.0);
  EXPECT_DOUBLE_EQ(sat_clock_at_sv_time(e, e.toe), 7.418449968100E-05 + 9.094947017729E-13 * -7.418449968100E-05);
}

// The same two R01 sets as a RINEX 2 GLONASS file (.g, frame time in s of
// the UTC day, 12 instead of 13 digits): the same orbit.
TEST(MultiGnss, GlonassRinex2SameAsRinex3) {
  const NavData g = read_rinex_nav(test::kNav + "SYNT0100.24g");
  ASSERT_EQ(g.ephemerides.size(), 2u);
  EXPECT_EQ(g.leap_seconds.value_or(-1), 18);
  for (const Ephemeris& e2 : g.ephemerides) {
    EXPECT_EQ(e2.sat, SatId(GnssSystem::kGlonass, 1));
    const Ephemeris* e3 = nullptr;
    for (const Ephemeris& e : igs().ephemerides)
      if (e.sat == e2.sat && e.toe == e2.toe) e3 = &e;
    ASSERT_NE(e3, nullptr);
    EXPECT_EQ(e2.transmit_tow_s, e3->transmit_tow_s);
    for (double dt : {-900.0, 0.0, 900.0}) {
      const SatState a = sat_state(e2, e2.toe + dt), b = sat_state(*e3, e3->toe + dt);
      EXPECT_LT((a.pos_m - b.pos_m).norm(), 1e-3) << dt;
      EXPECT_NEAR(a.clk_bias_s, b.clk_bias_s, 1e-15);
    }
  }
}

// RK4 with the ICD force model: 60 s steps are within a millimetre of 1 s
// steps over 15 min (multi-gnss.md §3: 0.6 mm), 30 s within 0.1 mm, while
// 300 s steps are off by decimetres; integrating back lands on the start.
TEST(MultiGnss, GlonassStepSizeConvergence) {
  const Ephemeris& e = first_of(SatId(GnssSystem::kGlonass, 1));
  const time::GpsTime t = e.toe + 900.0;
  const Ecef fine = glonass_state(e, t, 1.0).pos_m;
  const double d60 = (glonass_state(e, t, 60.0).pos_m - fine).norm();
  const double d30 = (glonass_state(e, t, 30.0).pos_m - fine).norm();
  const double d300 = (glonass_state(e, t, 300.0).pos_m - fine).norm();
  std::printf("GLONASS RK4 over 900 s vs 1 s steps: 60 s %.2g m, 30 s %.2g m, 300 s %.2g m\n", d60, d30, d300);
  EXPECT_LT(d60, 1e-3);
  EXPECT_LT(d30, 1e-4);
  EXPECT_GT(d300, 1e-2);
  EXPECT_EQ(sat_state(e, t).pos_m, glonass_state(e, t, kGlonassStep_s).pos_m);
  // An orbit of radius 25 500 km (GLONASS a = 25 510 km), speed ~3.9 km/s inertial.
  EXPECT_NEAR(fine.norm(), 25.5e6, 0.1e6);
  Ephemeris back = e;
  back.toe = t;
  const SatState s = glonass_state(e, t, kGlonassStep_s);
  back.pos_m = s.pos_m;
  back.vel_m_s = s.vel_m_s;
  EXPECT_LT((glonass_state(back, e.toe, kGlonassStep_s).pos_m - e.pos_m).norm(), 1e-3);
  // A span far beyond any use is held, not run for ever.
  const SatState far = sat_state(e, e.toe + 1e12);
  EXPECT_TRUE(far.pos_m.finite());
}

// BeiDou: BDT epoch and toe + 14 s; C01 (GEO; 144.6 deg E in 2024, where
// RTKLIB puts it too) through the GEO frame: at GEO radius over the
// equator, moving only its inclined-GEO figure eight (~100 m/s); the MEO
// formulas for the same elements put it thousands of km away.
TEST(MultiGnss, BeiDouTimesAndGeoFrame) {
  const Ephemeris& e = first_of(SatId(GnssSystem::kBeiDou, 1));
  EXPECT_EQ(e.toc.tow_s() - std::floor(e.toc.tow_s() / 3600.0) * 3600.0, 14.0);  // BDT on the hour
  EXPECT_EQ(e.toe, e.toc);
  EXPECT_EQ(toe_of_week_s(e), e.toe.tow_s() - 14.0);
  ASSERT_TRUE(is_beidou_geo(e.sat));
  const SatState s0 = sat_state(e, e.toe), s1 = sat_state(e, e.toe + 3600.0);
  const double lon_deg = std::atan2(s0.pos_m.y, s0.pos_m.x) * kRadToDeg;
  EXPECT_NEAR(lon_deg, 144.6, 1.0);
  EXPECT_NEAR(s0.pos_m.norm(), 42164e3, 50e3);
  EXPECT_LT(std::fabs(s0.pos_m.z), 2000e3);
  EXPECT_LT((s1.pos_m - s0.pos_m).norm(), 400e3);
  EXPECT_LT(s0.vel_m_s.norm(), 150.0);
  // Velocity of the GEO path against a central difference.
  const SatState p = sat_state(e, e.toe + 100.5), m = sat_state(e, e.toe + 99.5);
  EXPECT_LT((sat_state(e, e.toe + 100.0).vel_m_s - (p.pos_m - m.pos_m) / 1.0).norm(), 1e-4);
  Ephemeris as_meo = e;
  as_meo.sat = SatId(GnssSystem::kBeiDou, 6);
  ASSERT_FALSE(is_beidou_geo(as_meo.sat));
  EXPECT_GT((sat_state(as_meo, e.toe).pos_m - s0.pos_m).norm(), 1000e3);
  // C59-C63 are GEOs too; C58 is not.
  EXPECT_TRUE(is_beidou_geo(SatId(GnssSystem::kBeiDou, 59)));
  EXPECT_FALSE(is_beidou_geo(SatId(GnssSystem::kBeiDou, 58)));
}

// SBAS: p + v dt + a dt^2/2 and aGf0 + aGf1 dt from t0 (S27 00:58:15).
TEST(MultiGnss, SbasPolynomial) {
  const Ephemeris& e = first_of(SatId(GnssSystem::kSbas, 27));
  ASSERT_EQ(e.toe, gps_cal(2024, 1, 10, 0, 58, 15.0));
  EXPECT_DOUBLE_EQ(e.af0_s, 2.896413207054E-07);
  EXPECT_DOUBLE_EQ(e.vel_m_s.x, -1.074999928474E+00);
  const double dt = 120.0;
  const SatState s = sat_state(e, e.toe + dt);
  EXPECT_DOUBLE_EQ(s.pos_m.x, 2.420325312000E+07 + -1.074999928474E+00 * dt + 0.5 * -2.999999851454E-04 * dt * dt);
  EXPECT_DOUBLE_EQ(s.vel_m_s.y, -2.443125009537E+00 + 1.875000016298E-04 * dt);
  EXPECT_DOUBLE_EQ(s.clk_bias_s, 2.896413207054E-07 + 8.640199666843E-11 * dt);
  EXPECT_EQ(validity_half_window_s(e), 360.0);
}

namespace {
Ephemeris gal(double toe_tow, int sources, int health = 0, double transmit = 0.0) {
  Ephemeris e = first_of(SatId(GnssSystem::kGalileo, 2));
  e.toe = time::GpsTime(2296, toe_tow);
  e.toc = e.toe;
  e.gal_data_sources = sources;
  e.health = health;
  e.transmit_tow_s = transmit;
  e.transmit_known = transmit != 0.0;
  return e;
}
}  // namespace

// Galileo: I/NAV sets only (bit 9), toe strictly before t (RTKLIB 2.4.3),
// at most 4 h old, E1-B HS/DVS decide health for the E1 user; of one toe's
// I/NAV sets the first transmitted.
TEST(MultiGnss, GalileoSelection) {
  const SatId sat(GnssSystem::kGalileo, 2);
  const EphemerisStore s(
      {gal(3000.0, 513), gal(3600.0, 258), gal(3600.0, 516, 0, 3700.0), gal(3600.0, 517, 0, 3650.0)});
  EXPECT_EQ(s.count(sat), 3u);  // the F/NAV set is not kept
  EXPECT_EQ(s.select(sat, time::GpsTime(2296, 3600.0))->toe.tow_s(), 3000.0);  // toe == t not yet
  const Ephemeris* e = s.select(sat, time::GpsTime(2296, 3601.0));
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->gal_data_sources, 517);  // transmitted at 3650, before 516's 3700
  EXPECT_EQ(s.select(sat, time::GpsTime(2296, 2999.0)), nullptr);  // nothing before
  EXPECT_NE(s.select(sat, time::GpsTime(2296, 3600.0 + 14400.0)), nullptr);
  EXPECT_EQ(s.select(sat, time::GpsTime(2296, 3600.0 + 14401.0)), nullptr);
  // Health: E1-B DVS (bit 0) or HS (bits 1-2) out; E5b's bits (6-8) do not matter.
  for (const auto& [health, usable] : {std::pair{1, false}, {2, false}, {4, false}, {0x40, true}, {0x180, true}}) {
    const EphemerisStore h({gal(3000.0, 513, health)});
    EXPECT_EQ(h.select(sat, time::GpsTime(2296, 3100.0)) != nullptr, usable) << health;
  }
}

// QZSS: bit 0 of the health does not keep the satellite out (RTKLIB masks
// it; the IGS files give 1 for every QZSS set), other bits do.
TEST(MultiGnss, QzssHealthBitZeroMasked) {
  const SatId j02(GnssSystem::kQzss, 2);
  Ephemeris e = first_of(j02);
  EXPECT_EQ(e.health, 1);
  EXPECT_NE(EphemerisStore({e}).select(j02, e.toe), nullptr);
  e.health = 3;
  EXPECT_EQ(EphemerisStore({e}).select(j02, e.toe), nullptr);
}

// The store's windows per system: GLONASS 30 min about the nearest tb,
// BeiDou 6 h, QZSS 2 h (the table's ages); GPS keeps its fit-interval rule.
TEST(MultiGnss, StoreWindowsPerSystem) {
  const EphemerisStore store(igs().ephemerides);
  for (const SatId sat : {SatId(GnssSystem::kGlonass, 1), SatId(GnssSystem::kBeiDou, 1), SatId(GnssSystem::kQzss, 2)}) {
    Ephemeris e = first_of(sat);
    e.health = 0;
    const double w = validity_half_window_s(e);
    EXPECT_EQ(w, system_info(sat.system).max_ephemeris_age_s);
    const EphemerisStore one({e});
    EXPECT_NE(one.select(sat, e.toe + w), nullptr) << sat_name(sat).data();
    EXPECT_EQ(one.select(sat, e.toe + w + 1.0), nullptr) << sat_name(sat).data();
    EXPECT_EQ(one.select(sat, e.toe - w - 1.0), nullptr) << sat_name(sat).data();
  }
  // GLONASS: the nearest tb (sets every 30 min).
  const SatId r01(GnssSystem::kGlonass, 1);
  const time::GpsTime t = gps_cal(2024, 1, 10, 0, 30, 17.0);  // 899 s after one tb, 901 s before the next
  EXPECT_EQ(store.select(r01, t)->toe, gps_cal(2024, 1, 10, 0, 15, 18.0));
  EXPECT_EQ(store.select(r01, t + 2.0)->toe, gps_cal(2024, 1, 10, 0, 45, 18.0));
  EXPECT_EQ(store.select(SatId(GnssSystem::kGps, 33), t), nullptr);  // not a valid id
}

// I (NavIC) records: skipped and counted; unknown letters are errors.
TEST(MultiGnss, UnknownSystemsSkippedAndCounted) {
  std::string text =
      "     3.04           N: GNSS NAV DATA    M: MIXED            RINEX VERSION / TYPE\n"
      "                                                            END OF HEADER\n";
  const std::string irnss_lines[] = {
      "I02 2024 01 10 00 00 00 4.565306007862E-04 1.591615728103E-11 0.000000000000E+00\n",
      "     1.000000000000E+00-2.153125000000E+02 2.960837010622E-09 1.270870789390E+00\n",
      "    -7.463991641998E-06 1.942735072225E-03 1.497194170952E-05 6.493494724274E+03\n",
      "     2.592000000000E+05-7.078051567078E-08 1.562838094660E+00 2.011656761169E-07\n",
      "     5.106289982796E-01-9.918750000000E+02-1.550898349213E+00-1.810789758416E-09\n",
      "     1.435773518950E-09 0.000000000000E+00 2.296000000000E+03                   \n",
      "     2.000000000000E+00 0.000000000000E+00-3.259629011154E-09                   \n",
      "     2.592000000000E+05                                                         \n"};
  for (const std::string& l : irnss_lines) text += l;
  std::istringstream in(text);
  const NavData d = read_rinex_nav(in, "mem.rnx");
  EXPECT_EQ(d.skipped_records, 1);
  EXPECT_TRUE(d.ephemerides.empty());
}

// Nav data without GPS: a constellation all the same.
TEST(MultiGnss, ConstellationWithoutGps) {
  NavData nav = igs();
  std::erase_if(nav.ephemerides, [](const Ephemeris& e) { return e.sat.system == GnssSystem::kGps; });
  ConstellationRequest req;
  req.start = gps_cal(2024, 1, 10, 2, 0, 0.0);
  const Constellation c = build_constellation(nav, req);
  EXPECT_EQ(c.mode, NavMode::kAsIs);
  const EphemerisStore store(c.nav.ephemerides, c.store_options());
  EXPECT_NE(store.select(SatId(GnssSystem::kGalileo, 2), req.start), nullptr);
  req.start = req.start + 30.0 * kSecondsPerDay;
  const Constellation moved = build_constellation(nav, req);
  EXPECT_EQ(moved.mode, NavMode::kRelabel);
  EXPECT_EQ(moved.shift_s, 30.0 * kSecondsPerDay);
}

// Past the data a GLONASS satellite flies on along its last set's
// trajectory, from continued sets 30 min apart: the same positions as one
// long integration, no jump where one continued set hands over to the next.
TEST(MultiGnss, GlonassContinuesPastTheData) {
  const SatId r01(GnssSystem::kGlonass, 1);
  const EphemerisStore store(igs().ephemerides, StoreOptions{true});
  const EphemerisStore plain(igs().ephemerides);
  const Ephemeris* last = nullptr;
  for (const Ephemeris& e : igs().ephemerides)
    if (e.sat == r01 && (last == nullptr || last->toe < e.toe)) last = &e;
  ASSERT_NE(last, nullptr);
  for (double dt : {2000.0, 3.0 * 3600.0 + 900.0, 26.0 * 3600.0, 72.0 * 3600.0 + 17.0}) {
    const time::GpsTime t = last->toe + dt;
    EXPECT_EQ(plain.select(r01, t), nullptr);
    const Ephemeris* e = store.select(r01, t);
    ASSERT_NE(e, nullptr);
    EXPECT_LE(std::fabs(t - e->toe), kGlonassContinuationStep_s / 2.0) << dt;
    const SatState a = sat_state(*e, t), b = glonass_state(*last, t, kGlonassStep_s);
    EXPECT_LT((a.pos_m - b.pos_m).norm(), 1e-3) << dt;
    EXPECT_NEAR(a.clk_bias_s, b.clk_bias_s, 1e-15) << dt;
  }
  // Hand-over between two continued sets (tb + 45 min: 15 min from each).
  const time::GpsTime mid = last->toe + 2700.0;
  const SatState before = sat_state(*store.select(r01, mid - 0.001), mid);
  const SatState after = sat_state(*store.select(r01, mid + 0.001), mid);
  EXPECT_NE(store.select(r01, mid - 0.001), store.select(r01, mid + 0.001));
  EXPECT_LT((before.pos_m - after.pos_m).norm(), 1e-4);
}

// RINEX 2.11 GEO navigation (H): PRN - 100, GPST epoch, km.
TEST(MultiGnss, SbasRinex2) {
  std::istringstream in(
      "     2.11           H: GEO NAV MSG DATA                     RINEX VERSION / TYPE\n"
      "                                                            END OF HEADER\n"
      "27 24  1 10  0 58 15.0 0.289641320705D-06 0.864019966684D-10 0.262695000000D+06\n"
      "    0.242032531200D+05-0.107499992847D-02-0.299999985145D-06 0.000000000000D+00\n"
      "    0.345317626400D+05-0.244312500954D-02 0.187500001630D-06 0.150000000000D+02\n"
      "   -0.110240000000D+01-0.106000006199D-02 0.000000000000D+00 0.220000000000D+03\n");
  const NavData d = read_rinex_nav(in, "mem.24h");
  ASSERT_EQ(d.ephemerides.size(), 1u);
  const Ephemeris& e = d.ephemerides.front();
  EXPECT_EQ(e.sat, SatId(GnssSystem::kSbas, 27));
  EXPECT_EQ(e.sat.prn(), 127);
  const Ephemeris& e3 = first_of(SatId(GnssSystem::kSbas, 27));
  EXPECT_EQ(e.toe, e3.toe);
  EXPECT_LT((sat_state(e, e.toe + 100.0).pos_m - sat_state(e3, e3.toe + 100.0).pos_m).norm(), 1e-3);
  EXPECT_EQ(e.iode, 220);
}

// Per-system files read together: GPS (.n) and GLONASS (.g) in one store.
TEST(MultiGnss, GpsAndGlonassFilesTogether) {
  const NavData d = read_rinex_nav_files({test::kNav + "brdc0010.22n", test::kNav + "SYNT0100.24g"});
  EXPECT_EQ(d.ephemerides.size(), 422u + 2u);
  const EphemerisStore store(d.ephemerides);
  EXPECT_EQ(store.count(SatId(GnssSystem::kGlonass, 1)), 2u);
  EXPECT_EQ(store.count(SatId::gps(1)), EphemerisStore(test::brdc().ephemerides).count(SatId::gps(1)));
  EXPECT_NE(store.select(SatId(GnssSystem::kGlonass, 1), gps_cal(2024, 1, 10, 0, 20, 0.0)), nullptr);
  EXPECT_TRUE(d.klobuchar.valid);  // from the GPS file
}

// Past the data an SBAS GEO stays where its last set's window ends (its
// polynomial's acceleration would carry it ~1000 km a day); the position
// and the clock continue at the hand-over.
TEST(MultiGnss, SbasHeldPastTheData) {
  const SatId s27(GnssSystem::kSbas, 27);
  std::vector<Ephemeris> sets;
  for (const Ephemeris& e : igs().ephemerides)
    if (e.sat == s27) sets.push_back(e);
  for (Ephemeris& e : sets) e.health = 0;  // the file flags some sets 63
  const EphemerisStore store(sets, StoreOptions{true});
  const Ephemeris* last = nullptr;
  for (const Ephemeris& e : sets)
    if (last == nullptr || last->toe < e.toe) last = &e;
  ASSERT_NE(last, nullptr);
  const time::GpsTime end = last->toe + validity_half_window_s(*last);
  const Ephemeris* held = store.select(s27, end + 1.0);
  ASSERT_NE(held, nullptr);
  ASSERT_NE(store.select(s27, end), nullptr);
  const SatState a = sat_state(*store.select(s27, end), end), b = sat_state(*held, end + 1.0);
  EXPECT_LT((a.pos_m - b.pos_m).norm(), 1e-6);
  EXPECT_NEAR(a.clk_bias_s, b.clk_bias_s, 1e-18);
  const SatState c = sat_state(*store.select(s27, end + 3.0 * kSecondsPerDay), end + 3.0 * kSecondsPerDay);
  EXPECT_EQ(c.pos_m, b.pos_m);
  EXPECT_NEAR(c.pos_m.norm(), 42164e3, 100e3);
}

TEST(NavSystems, SystemsOfTheData) {
  EXPECT_EQ(systems_of(read_rinex_nav(test::kNav + "brdc0010.22n")), SystemSet::only(GnssSystem::kGps));
  // The IGS merged file: every system; its NavIC records are skipped.
  EXPECT_EQ(systems_of(read_rinex_nav(test::kNav + "BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz")), SystemSet::all());
  EXPECT_TRUE(systems_of(NavData{}).empty());
}

// The shipped default nav data (config/nav): GPS, GLONASS, Galileo, BeiDou,
// QZSS and the SBAS GEOs, every satellite's sets covering the whole day.
TEST(NavSystems, ShippedDefaultHoldsEverySystem) {
  const NavData d = read_rinex_nav(std::string(GNSSEMU_SOURCE_DIR) + "/config/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz");
  EXPECT_EQ(systems_of(d), SystemSet::all());
  EXPECT_EQ(d.skipped_records, 0);
  const EphemerisStore store(d.ephemerides);
  std::array<int, kNumSystems> healthy{};
  const time::GpsTime noon(2296, 3 * 86400.0 + 43200.0);  // 2024-01-10 12:00 GPST
  for (int i = 0; i < kNumSats; ++i) {
    if (store.select(SatId::from_index(i), noon) != nullptr) ++healthy[static_cast<std::size_t>(SatId::from_index(i).system)];
  }
  EXPECT_GE(healthy[0], 30);  // G
  EXPECT_GE(healthy[1], 22);  // R
  EXPECT_GE(healthy[2], 22);  // E
  EXPECT_GE(healthy[3], 40);  // C
  EXPECT_GE(healthy[4], 3);   // J
  EXPECT_GE(healthy[5], 8);   // S
}

// The thinned SBAS records (tools/make_default_nav.py) leave no gap: every
// GEO healthy at 00:10 stays selectable every 30 s until 23:50.
TEST(NavSystems, ShippedDefaultSbasCoversTheDay) {
  const NavData d = read_rinex_nav(std::string(GNSSEMU_SOURCE_DIR) + "/config/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz");
  const EphemerisStore store(d.ephemerides);
  const time::GpsTime day(2296, 3 * 86400.0);  // 2024-01-10 00:00 GPST
  int geos = 0;
  for (int i = 0; i < kNumSats; ++i) {
    const SatId sat = SatId::from_index(i);
    if (sat.system != GnssSystem::kSbas || store.select(sat, day + 600.0) == nullptr) continue;
    ++geos;
    int gaps = 0;
    for (double t = 600.0; t <= 86400.0 - 600.0; t += 30.0) gaps += store.select(sat, day + t) == nullptr ? 1 : 0;
    EXPECT_EQ(gaps, 0) << sat.number;
  }
  EXPECT_GE(geos, 8);
}

// The shipped default moved to a later date serves every system at the
// start and three days on (each satellite continued past the data).
TEST(NavSystems, ShippedDefaultServesEverySystemDaysOn) {
  const NavData d = read_rinex_nav(std::string(GNSSEMU_SOURCE_DIR) + "/config/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz");
  ConstellationRequest req;
  req.mode = NavMode::kAuto;
  req.start = time::GpsTime(2446, 210808.0);  // 2026-11-24 10:33:28 GPST
  const Constellation c = build_constellation(d, req);
  EXPECT_EQ(c.mode, NavMode::kRelabel);
  EXPECT_EQ(c.shift_s, 1049.0 * kSecondsPerDay);
  const EphemerisStore store(c.nav.ephemerides, c.store_options());
  for (const double later_s : {0.0, 3.0 * kSecondsPerDay}) {
    std::array<int, kNumSystems> n{};
    for (int i = 0; i < kNumSats; ++i) {
      const SatId sat = SatId::from_index(i);
      if (store.select(sat, req.start + later_s) != nullptr) ++n[static_cast<std::size_t>(sat.system)];
    }
    EXPECT_GE(n[0], 30) << later_s;
    EXPECT_GE(n[1], 22) << later_s;
    EXPECT_GE(n[2], 22) << later_s;
    EXPECT_GE(n[3], 40) << later_s;
    EXPECT_GE(n[4], 3) << later_s;
    EXPECT_GE(n[5], 8) << later_s;  // SBAS GEOs held past the data
  }
}

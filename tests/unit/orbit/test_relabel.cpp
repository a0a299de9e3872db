// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "core/common/constants.hpp"
#include "core/orbit/almanac.hpp"
#include "core/orbit/relabel.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "orbit_test_data.hpp"

using namespace gnssemu;
using namespace gnssemu::orbit;

using test::brdc;
using test::kData;

namespace {

/// Largest position (m), velocity (m/s) and clock (s) difference between
/// eph at t and moved at t + shift over eph's 4-hour window.
struct Diff {
  double pos_m = 0.0, vel_m_s = 0.0, clk_s = 0.0;
};
Diff compare(const Ephemeris& eph, const Ephemeris& moved, double shift_s, double window_s = 7200.0) {
  Diff d;
  for (double dt = -window_s; dt <= window_s; dt += window_s / 12.0) {
    const time::GpsTime t = eph.toe + dt;
    const SatState a = sat_state(eph, t), b = sat_state(moved, t + shift_s);
    d.pos_m = std::max(d.pos_m, (a.pos_m - b.pos_m).norm());
    d.vel_m_s = std::max(d.vel_m_s, (a.vel_m_s - b.vel_m_s).norm());
    d.clk_s = std::max(d.clk_s, std::fabs(a.clk_bias_s - b.clk_bias_s));
  }
  return d;
}

}  // namespace

// The satellites stand shift_s later exactly where they stood: whole days,
// whole weeks, fractions of a day, backwards, across week boundaries.
TEST(Relabel, SameGeometryShiftLater) {
  const double day = kSecondsPerDay;
  for (const double shift : {day, 1788.0 * day, -636.0 * day, 0.5 * day + 17.25, 7.0 * day, 3.0 * 7.0 * day + 1.0,
                             -1.0, 1e8}) {
    for (const Ephemeris& e : brdc().ephemerides) {
      const Ephemeris m = relabel(e, shift);
      EXPECT_EQ(m.toe, e.toe + shift);
      EXPECT_EQ(m.toc, e.toc + shift);
      EXPECT_EQ(m.iode, e.iode);
      const Diff d = compare(e, m, shift);
      ASSERT_LT(d.pos_m, 1e-3) << "PRN " << int(e.sat.number) << " shift " << shift;
      ASSERT_LT(d.vel_m_s, 1e-6) << "PRN " << int(e.sat.number) << " shift " << shift;
      ASSERT_LT(d.clk_s, 1e-15) << "PRN " << int(e.sat.number) << " shift " << shift;
    }
  }
}

// Every system of an IGS mixed file (GLONASS RK4 and SBAS over their
// windows; BeiDou GEO and MEO; Galileo; QZSS): the same geometry shift_s later.
TEST(Relabel, EverySystemSameGeometryShiftLater) {
  const NavData nav = read_rinex_nav(test::kNav + "BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  const double day = kSecondsPerDay;
  std::array<int, kNumSystems> n{};
  for (const double shift : {day, 1788.0 * day, -636.0 * day, 0.5 * day + 17.25, 3.0 * 7.0 * day + 1.0, 1e8}) {
    for (const Ephemeris& e : nav.ephemerides) {
      const Ephemeris m = relabel(e, shift);
      EXPECT_EQ(m.toe, e.toe + shift);
      const Diff d = compare(e, m, shift, validity_half_window_s(e));
      const char* name = sat_name(e.sat).data();
      ASSERT_LT(d.pos_m, 1e-3) << name << " shift " << shift;
      ASSERT_LT(d.vel_m_s, 1e-6) << name << " shift " << shift;
      ASSERT_LT(d.clk_s, 1e-15) << name << " shift " << shift;
      ++n[static_cast<std::size_t>(e.sat.system)];
    }
  }
  for (int k : n) EXPECT_GT(k, 0);
}

// GLONASS: the ECEF state at tb is the geometry; any turn about z would
// move the satellite against the other systems (ω̇e·shift is 0.986° a day
// moved past whole turns, ~440 km at GLONASS's orbit radius; docs/models.md
// "Geometry kept", per system).
TEST(Relabel, GlonassStateVectorIsNotRotated) {
  const NavData nav = read_rinex_nav(test::kNav + "BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  for (const Ephemeris& e : nav.ephemerides) {
    if (e.sat.system != GnssSystem::kGlonass) continue;
    const Ephemeris m = relabel(e, 3.0 * kSecondsPerDay + 5.0);
    EXPECT_EQ(m.pos_m, e.pos_m);
    EXPECT_EQ(m.vel_m_s, e.vel_m_s);
    EXPECT_EQ(m.acc_m_s2, e.acc_m_s2);
    EXPECT_EQ(m.tau_n_s, e.tau_n_s);
    EXPECT_EQ(m.glo_channel, e.glo_channel);
  }
}

// Why Ω0 moves: toe/toc alone keep the geometry for whole weeks only; a
// shift by a day turns every orbit by ω̇e·86400 s ≈ 6.3 rad, thousands of km.
TEST(Relabel, ShiftingToeAloneTurnsTheOrbits) {
  const Ephemeris& e = brdc().ephemerides.front();
  for (const double shift : {kSecondsPerDay, 2.0 * kSecondsPerWeek}) {
    Ephemeris naive = e;
    naive.toe = e.toe + shift;
    naive.toc = e.toc + shift;
    const Diff d = compare(e, naive, shift);
    if (shift == kSecondsPerDay) {
      EXPECT_GT(d.pos_m, 1000e3);
    } else {
      EXPECT_LT(d.pos_m, 1e-3);  // whole weeks: toe's time of week is unchanged
    }
  }
}

TEST(Relabel, TransmissionTimeKeepsItsInstant) {
  for (const Ephemeris& e : brdc().ephemerides) {
    if (!e.transmit_known) continue;
    const Ephemeris m = relabel(e, 5.0 * kSecondsPerDay + 3.0);  // crosses into week 2191
    const double before = (time::GpsTime(e.toe.week(), 0.0) + e.transmit_tow_s) - e.toe;
    const double after = (time::GpsTime(m.toe.week(), 0.0) + m.transmit_tow_s) - m.toe;
    EXPECT_NEAR(after, before, 1e-6) << int(e.sat.number);
  }
}

TEST(Relabel, NavDataHeaderForTheNewDate) {
  const NavData m = relabel(brdc(), 1788.0 * kSecondsPerDay);
  ASSERT_EQ(m.ephemerides.size(), brdc().ephemerides.size());
  EXPECT_FALSE(m.leap_seconds.has_value());  // the new date's count is the table's
  EXPECT_EQ(m.klobuchar.alpha, brdc().klobuchar.alpha);
  ASSERT_TRUE(m.utc.valid);
  EXPECT_NEAR(time::GpsTime(m.utc.wnt, m.utc.tot_s) - time::GpsTime(brdc().utc.wnt, brdc().utc.tot_s),
              1788.0 * kSecondsPerDay, 1e-6);
}

TEST(Relabel, AlmanacLikeAnEphemeris) {
  const std::vector<AlmanacEntry> alm = read_yuma(kData + "/almanac/yuma_week862_toa319488.alm", 1886);
  for (const double shift : {kSecondsPerDay * 3900.0, -kSecondsPerDay, 0.25 * kSecondsPerDay}) {
    for (const AlmanacEntry& a : alm) {
      const AlmanacEntry m = relabel(a, shift);
      for (double dt = -86400.0; dt <= 86400.0; dt += 3600.0) {
        const SatState s0 = almanac_state(a, a.toa + dt), s1 = almanac_state(m, m.toa + dt);
        ASSERT_LT((s0.pos_m - s1.pos_m).norm(), 1e-3) << a.sat.prn() << " " << shift;
      }
    }
  }
}

// SPDX-License-Identifier: Apache-2.0
// GPS LNAV subframes from broadcast ephemerides: parity as IS-GPS-200 and
// gpsd check it, the SFRBX bit 30/31 convention, and every field decoded
// back at its ICD scale equal to the RINEX value within one LSB (the RINEX
// values were themselves quantized from these bits).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/navmsg/gps_lnav.hpp"
#include "core/protocol/navmsg/nav_bits.hpp"

namespace gnssemu::protocol::navmsg {
namespace {

const orbit::NavData& brdc() {
  static const orbit::NavData d = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  return d;
}

/// The 24 data bits of each word, concatenated (240 bits).
BitString<240> data_bits(const LnavSubframe& sf) {
  BitString<240> b;
  for (const std::uint32_t w : sf) b.put(w >> 6 & 0xFFFFFF, 24);
  return b;
}

/// gpsd's check (gpsd_interpret_subframe_raw): invert when bit 30 is set,
/// then the parity with D29* = bit 31, D30* = bit 30.
bool gpsd_parity_ok(std::uint32_t w) {
  if (w & 0x40000000u) w ^= 0x3FFFFFC0u;
  return lnav_parity(w) == (w & 0x3Fu);
}

double s(const BitString<240>& b, std::size_t at, int n, double scale) {
  return static_cast<double>(sign_extend(b.get(at, n), n)) * scale;
}
double u(const BitString<240>& b, std::size_t at, int n, double scale) { return b.get(at, n) * scale; }
/// A 32-bit field split 8 + 24 over two words starting at at.
std::uint32_t split32(const BitString<240>& b, std::size_t at) { return b.get(at, 8) << 24 | b.get(at + 8, 24); }
/// The same field as two's complement.
double signed32(const BitString<240>& b, std::size_t at) { return static_cast<double>(sign_extend(split32(b, at), 32)); }

TEST(LnavParity, PreviousWordBitsFollowTheIcdTable) {
  // D29* enters D25, D27 and D30; D30* enters D26, D28 and D29 (IS-GPS-200N Table 20-XIV).
  EXPECT_EQ(lnav_parity(0x80000000u), 0b101001u);
  EXPECT_EQ(lnav_parity(0x40000000u), 0b010110u);
  // d1 enters D25, D27, D29.
  EXPECT_EQ(lnav_parity(1u << 29), 0b101010u);
}

TEST(LnavSubframe, IdsAndPagesFollowTheFrame) {
  EXPECT_EQ(lnav_subframe_id(6.0), 1);
  EXPECT_EQ(lnav_subframe_id(30.0), 5);
  EXPECT_EQ(lnav_subframe_id(36.0), 1);
  EXPECT_EQ(lnav_subframe_id(604800.0), 5);
  EXPECT_EQ(lnav_page(24.0), 1);
  EXPECT_EQ(lnav_page(30.0 * 17 + 24.0), 18);
  EXPECT_TRUE(lnav_page_produced(30.0 * 17 + 24.0));
  EXPECT_FALSE(lnav_page_produced(30.0 * 16 + 24.0));
  EXPECT_FALSE(lnav_page_produced(30.0));
}

TEST(LnavSubframe, ParityAndWordConventionAsSfrbx) {
  const orbit::Ephemeris& eph = brdc().ephemerides.front();
  for (int id = 1; id <= 4; ++id) {
    const LnavSubframe sf = gps_lnav_subframe(eph, id, 2190, 6.0 * id + 30.0 * 17, {});
    EXPECT_EQ(sf[0] >> 22 & 0xFF, 0x8Bu);
    EXPECT_EQ(sf[0] >> 31, 0u);
    for (std::size_t w = 0; w < sf.size(); ++w) {
      SCOPED_TRACE(w);
      EXPECT_EQ(sf[w] & 0x40000000u, 0u);
      EXPECT_TRUE(gpsd_parity_ok(sf[w]));
      if (w > 0) {
        EXPECT_EQ(sf[w] >> 31, ((sf[w - 1] >> 1) ^ sf[w - 1]) & 1u);
      }
    }
    EXPECT_EQ(sf[1] & 3u, 0u);  // HOW and word 10 end in D29 = D30 = 0
    EXPECT_EQ(sf[9] & 3u, 0u);
    const BitString<240> b = data_bits(sf);
    EXPECT_EQ(b.get(24, 17), static_cast<std::uint32_t>(id + 85));  // TOW count of the next subframe
    EXPECT_EQ(b.get(24 + 19, 3), static_cast<std::uint32_t>(id));
  }
}

TEST(LnavSubframe, EveryFieldDecodesToTheEphemerisWithinOneLsb) {
  constexpr double kPi = kSemicircle_rad;
  int checked = 0;
  for (const orbit::Ephemeris& eph : brdc().ephemerides) {
    SCOPED_TRACE(eph.sat.number);
    const BitString<240> b1 = data_bits(gps_lnav_subframe(eph, 1, eph.toe.week(), 6.0, {}));
    const BitString<240> b2 = data_bits(gps_lnav_subframe(eph, 2, eph.toe.week(), 12.0, {}));
    const BitString<240> b3 = data_bits(gps_lnav_subframe(eph, 3, eph.toe.week(), 18.0, {}));
    EXPECT_EQ(static_cast<int>(b1.get(48, 10)), eph.toe.week() % 1024);
    EXPECT_EQ(static_cast<int>(b1.get(48 + 16, 6)), eph.health);
    EXPECT_EQ(static_cast<int>(b1.get(48 + 22, 2) << 8 | b1.get(168, 8)), eph.iodc);
    EXPECT_NEAR(s(b1, 160, 8, std::ldexp(1.0, -31)), eph.tgd_s, std::ldexp(1.0, -31));
    EXPECT_NEAR(u(b1, 176, 16, 16.0), eph.toc.tow_s(), 16.0);
    EXPECT_NEAR(s(b1, 192, 8, std::ldexp(1.0, -55)), eph.af2_s_s2, std::ldexp(1.0, -55));
    EXPECT_NEAR(s(b1, 200, 16, std::ldexp(1.0, -43)), eph.af1_s_s, std::ldexp(1.0, -43));
    EXPECT_NEAR(s(b1, 216, 22, std::ldexp(1.0, -31)), eph.af0_s, std::ldexp(1.0, -31));
    EXPECT_EQ(static_cast<int>(b2.get(48, 8)), eph.iode);
    EXPECT_NEAR(s(b2, 56, 16, 1.0 / 32), eph.crs_m, 1.0 / 32);
    EXPECT_NEAR(s(b2, 72, 16, std::ldexp(1.0, -43)) * kPi, eph.delta_n_rad_s, std::ldexp(kPi, -43));
    EXPECT_NEAR(signed32(b2, 88) * std::ldexp(kPi, -31), eph.m0_rad, std::ldexp(kPi, -31));
    EXPECT_NEAR(s(b2, 120, 16, std::ldexp(1.0, -29)), eph.cuc_rad, std::ldexp(1.0, -29));
    EXPECT_NEAR(split32(b2, 136) * std::ldexp(1.0, -33), eph.e, std::ldexp(1.0, -33));
    EXPECT_NEAR(s(b2, 168, 16, std::ldexp(1.0, -29)), eph.cus_rad, std::ldexp(1.0, -29));
    EXPECT_NEAR(split32(b2, 184) * std::ldexp(1.0, -19), eph.sqrt_a_sqrtm, std::ldexp(1.0, -19));
    EXPECT_NEAR(u(b2, 216, 16, 16.0), eph.toe.tow_s(), 16.0);
    EXPECT_NEAR(s(b3, 48, 16, std::ldexp(1.0, -29)), eph.cic_rad, std::ldexp(1.0, -29));
    EXPECT_NEAR(signed32(b3, 64) * std::ldexp(kPi, -31), eph.omega0_rad, std::ldexp(kPi, -31));
    EXPECT_NEAR(s(b3, 96, 16, std::ldexp(1.0, -29)), eph.cis_rad, std::ldexp(1.0, -29));
    EXPECT_NEAR(signed32(b3, 112) * std::ldexp(kPi, -31), eph.i0_rad, std::ldexp(kPi, -31));
    EXPECT_NEAR(s(b3, 144, 16, 1.0 / 32), eph.crc_m, 1.0 / 32);
    EXPECT_NEAR(signed32(b3, 160) * std::ldexp(kPi, -31), eph.omega_rad, std::ldexp(kPi, -31));
    EXPECT_NEAR(s(b3, 192, 24, std::ldexp(1.0, -43)) * kPi, eph.omega_dot_rad_s, std::ldexp(kPi, -43));
    EXPECT_EQ(static_cast<int>(b3.get(216, 8)), eph.iode);
    EXPECT_NEAR(s(b3, 224, 14, std::ldexp(1.0, -43)) * kPi, eph.idot_rad_s, std::ldexp(kPi, -43));
    // The nearest code, not merely within an LSB: RINEX carries 12 digits, an LSB of sqrt(A) is 2e-6.
    EXPECT_NEAR(split32(b2, 184) * std::ldexp(1.0, -19), eph.sqrt_a_sqrtm, 1e-11 + std::ldexp(0.5, -19));
    ++checked;
  }
  EXPECT_GT(checked, 400);
}

TEST(LnavSubframe, IonoUtcPageCarriesTheBroadcastParameters) {
  const orbit::NavData& nav = brdc();
  ASSERT_TRUE(nav.klobuchar.valid);
  LnavIonoUtc iono{&nav.klobuchar, &nav.utc, 18};
  const BitString<240> b = data_bits(gps_lnav_subframe(nav.ephemerides.front(), 4, 2190, 30.0 * 17 + 24.0, iono));
  EXPECT_EQ(b.get(48, 2), 1u);
  EXPECT_EQ(b.get(50, 6), 56u);
  EXPECT_NEAR(s(b, 56, 8, std::ldexp(1.0, -30)), nav.klobuchar.alpha[0], std::ldexp(1.0, -30));
  EXPECT_NEAR(s(b, 64, 8, std::ldexp(1.0, -27)), nav.klobuchar.alpha[1], std::ldexp(1.0, -27));
  EXPECT_NEAR(s(b, 80, 8, std::ldexp(1.0, -24)), nav.klobuchar.alpha[3], std::ldexp(1.0, -24));
  EXPECT_NEAR(s(b, 88, 8, std::ldexp(1.0, 11)), nav.klobuchar.beta[0], std::ldexp(1.0, 11));
  EXPECT_NEAR(s(b, 112, 8, std::ldexp(1.0, 16)), nav.klobuchar.beta[3], std::ldexp(1.0, 16));
  EXPECT_EQ(b.get(216 - 24, 8), 18u);  // delta t_LS
}

}  // namespace
}  // namespace gnssemu::protocol::navmsg

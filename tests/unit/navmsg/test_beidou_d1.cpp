// SPDX-License-Identifier: Apache-2.0
// BeiDou D1 subframes 1-3 from broadcast ephemerides: the BCH(15,11) code,
// the subframe grid of the BDT week, and the round trip ephemeris ->
// subframes -> decoder with every field back within its LSB.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/navmsg/beidou_d1.hpp"
#include "core/protocol/navmsg/nav_bits.hpp"
#include "beidou_test_util.hpp"

namespace gnssemu::protocol::navmsg {
namespace {

const orbit::NavData& igs_d1() {
  static const orbit::NavData d =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  return d;
}

TEST(D1Bch, IsTheCyclicCodeOfXFourPlusXPlusOne) {
  // A single data bit at X^(i+4) leaves X^(i+4) mod g(X): X^4 = X + 1, X^5 = X^2 + X, ...
  EXPECT_EQ(bch15_11_parity(0b00000000001), 0b0011u);
  EXPECT_EQ(bch15_11_parity(0b00000000010), 0b0110u);
  EXPECT_EQ(bch15_11_parity(0b00000000100), 0b1100u);
  EXPECT_EQ(bch15_11_parity(0b00000001000), 0b1011u);  // X^7 = X^3 + X + 1
  // Linear, and every codeword has weight >= 3 (single errors are corrected by the ICD decoder).
  for (std::uint32_t a = 1; a < 2048; ++a) {
    const std::uint32_t cw = a << 4 | bch15_11_parity(a);
    EXPECT_GE(__builtin_popcount(cw), 3) << a;
    EXPECT_EQ(bch15_11_parity(a ^ 0x555), bch15_11_parity(a) ^ bch15_11_parity(0x555));
  }
}

TEST(D1Subframe, IdsFollowTheBdtWeek) {
  // BDT week start = GPS tow 14 s.
  EXPECT_EQ(d1_subframe_id(time::GpsTime(2296, 14.0)), 1);
  EXPECT_EQ(d1_subframe_id(time::GpsTime(2296, 14.0 + 6.0 * 7)), 3);
}

TEST(D1Subframe, EveryFieldDecodesToTheEphemerisWithinOneLsb) {
  const orbit::NavData& nav = igs_d1();
  int checked = 0;
  for (const orbit::Ephemeris& eph : nav.ephemerides) {
    if (eph.sat.system != GnssSystem::kBeiDou || is_beidou_geo(eph.sat)) continue;
    SCOPED_TRACE(static_cast<int>(eph.sat.number));
    // A frame start 5 to 35 s after toe: GPS tow = 14 s + a multiple of 30 s.
    const double tow = std::floor((eph.toe.tow_s() - 14.0) / 30.0) * 30.0 + 14.0 + 30.0;
    const time::GpsTime t0(eph.toe.week(), tow);
    ASSERT_EQ(d1_subframe_id(t0), 1);
    std::array<D1Subframe, 3> sf{};
    for (int id = 1; id <= 3; ++id) {
      sf[static_cast<std::size_t>(id - 1)] = beidou_d1_subframe(eph, id, t0 + 6.0 * (id - 1), &nav.beidou_klobuchar);
      for (const std::uint32_t w : sf[static_cast<std::size_t>(id - 1)]) EXPECT_EQ(w >> 30, 0u);
    }
    EXPECT_EQ(sf[0][0] >> 19, 0x712u);  // preamble
    const std::optional<BeidouDecoded> d = decode_beidou_d1(sf, eph.sat.number);
    ASSERT_TRUE(d.has_value());
    test::expect_beidou_set(*d, eph, nav.beidou_klobuchar);
    EXPECT_EQ(d->week, eph.toe.week() - 1356 - (eph.toe.tow_s() < 14.0 ? 1 : 0));
    std::array<D1Subframe, 3> bad = sf;
    bad[1][4] ^= 1u << 12;  // a data bit: its half's parity fails
    EXPECT_FALSE(decode_beidou_d1(bad, eph.sat.number).has_value());
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

}  // namespace
}  // namespace gnssemu::protocol::navmsg

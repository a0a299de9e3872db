// SPDX-License-Identifier: Apache-2.0
// BeiDou D2 (GEO) subframe 1 pages 1-10 from broadcast ephemerides: the page
// grid of the BDT week, the bit positions RTKLIB's decoder reads, and the
// round trip ephemeris -> pages -> decoder with every field within its LSB.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/navmsg/beidou_d2.hpp"
#include "core/protocol/navmsg/nav_bits.hpp"
#include "beidou_test_util.hpp"
#include "core/time/beidou_time.hpp"

namespace gnssemu::protocol::navmsg {
namespace {

const orbit::NavData& igs() {
  static const orbit::NavData d =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  return d;
}

/// Bit `at` (0 = MSB of word 1) of the 300-bit subframe as transmitted.
std::uint32_t bit300(const D1Subframe& w, int at) { return w[static_cast<std::size_t>(at / 30)] >> (29 - at % 30) & 1u; }
std::uint32_t bits300(const D1Subframe& w, int at, int n) {
  std::uint32_t v = 0;
  for (int i = 0; i < n; ++i) v = v << 1 | bit300(w, at + i);
  return v;
}

TEST(D2Page, PagesFollowTheBdtWeekEveryThreeSeconds) {
  // BDT week start = GPS tow 14 s.
  EXPECT_EQ(d2_page(time::GpsTime(2296, 14.0)), 1);
  EXPECT_EQ(d2_page(time::GpsTime(2296, 17.0)), 2);
  EXPECT_EQ(d2_page(time::GpsTime(2296, 14.0 + 27.0)), 10);
  EXPECT_EQ(d2_page(time::GpsTime(2296, 14.0 + 30.0)), 1);
}

const orbit::Ephemeris& a_geo() {
  for (const orbit::Ephemeris& eph : igs().ephemerides)
    if (is_beidou_geo(eph.sat)) return eph;
  throw std::runtime_error("no GEO in the test nav");
}

TEST(D2Page, FieldsSitWhereTheTransmittedSubframePutsThem) {
  // Positions in the 300-bit subframe (30-bit words, 22 data bits then 8
  // parity in words 2-10), as BDS ICD §5.3.3 lays out page 1 and 7.
  const orbit::Ephemeris& eph = a_geo();
  const time::GpsTime t0(eph.toe.week(), std::floor((eph.toe.tow_s() - 14.0) / 30.0) * 30.0 + 44.0);
  const D1Subframe p1 = beidou_d2_page(eph, 1, t0, nullptr);
  EXPECT_EQ(bits300(p1, 0, 11), 0x712u);
  EXPECT_EQ(bits300(p1, 15, 3), 1u);                                          // FraID
  EXPECT_EQ(bits300(p1, 18, 8) << 12 | bits300(p1, 30, 12), static_cast<std::uint32_t>(
                                                                 std::lround(time::bdt_from_gps(t0).tow_s)));  // SOW
  EXPECT_EQ(bits300(p1, 42, 4), 1u);                                          // Pnum
  EXPECT_EQ(bits300(p1, 64, 13), static_cast<std::uint32_t>(time::bdt_from_gps(t0).week));
  const std::uint32_t toc = bits300(p1, 77, 5) << 12 | bits300(p1, 90, 12);
  EXPECT_DOUBLE_EQ(toc * 8.0, time::bdt_from_gps(eph.toc).tow_s);
  const D1Subframe p7 = beidou_d2_page(eph, 7, t0 + 18.0, nullptr);
  EXPECT_EQ(bits300(p7, 42, 4), 7u);
  const std::uint32_t toe = bits300(p7, 80, 2) << 15 | bits300(p7, 90, 15);
  EXPECT_DOUBLE_EQ(toe * 8.0, time::bdt_from_gps(eph.toe).tow_s);
  for (const std::uint32_t w : p7) EXPECT_EQ(w >> 30, 0u);
}

TEST(D2Page, EveryFieldDecodesToTheEphemerisWithinOneLsb) {
  const orbit::NavData& nav = igs();
  int checked = 0;
  for (const orbit::Ephemeris& eph : nav.ephemerides) {
    if (!is_beidou_geo(eph.sat)) continue;
    SCOPED_TRACE(static_cast<int>(eph.sat.number));
    const time::GpsTime t0(eph.toe.week(), std::floor((eph.toe.tow_s() - 14.0) / 30.0) * 30.0 + 44.0);
    ASSERT_EQ(d2_page(t0), 1);
    std::array<D1Subframe, kD2Pages> pages{};
    for (int p = 1; p <= kD2Pages; ++p) {
      const time::GpsTime t = t0 + kD2Frame_s * (p - 1);
      ASSERT_EQ(d2_page(t), p);
      pages[static_cast<std::size_t>(p - 1)] = beidou_d2_page(eph, p, t, &nav.beidou_klobuchar);
    }
    const std::optional<BeidouDecoded> d = decode_beidou_d2(pages, eph.sat.number);
    ASSERT_TRUE(d.has_value());
    test::expect_beidou_set(*d, eph, nav.beidou_klobuchar);
    std::array<D1Subframe, kD2Pages> bad = pages;
    bad[5][3] ^= 1u << 20;  // a data bit of page 6: its half's parity fails
    EXPECT_FALSE(decode_beidou_d2(bad, eph.sat.number).has_value());
    std::array<D1Subframe, kD2Pages> swapped = pages;
    std::swap(swapped[3], swapped[4]);  // pages out of order
    EXPECT_FALSE(decode_beidou_d2(swapped, eph.sat.number).has_value());
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

}  // namespace
}  // namespace gnssemu::protocol::navmsg

// SPDX-License-Identifier: Apache-2.0
// Galileo I/NAV word types 0-6 from broadcast ephemerides: the CRC-24Q,
// the page-pair form, and the round trip ephemeris -> page pairs ->
// decoder with every field back within its LSB.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/navmsg/galileo_inav.hpp"
#include "core/protocol/navmsg/nav_bits.hpp"

namespace gnssemu::protocol::navmsg {
namespace {

const orbit::NavData& igs_inav() {
  static const orbit::NavData d =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  return d;
}

TEST(InavCrc, IsTheRtcmCrc24q) {
  // An empty RTCM 3 frame: D3 00 00 then its CRC-24Q 47 EA 4B (rtk-raw.md §2.1).
  const std::uint8_t frame[3] = {0xD3, 0x00, 0x00};
  EXPECT_EQ(crc24q_bits(frame, 24), 0x47EA4Bu);
  // Leading zero bits do not change it (RTKLIB pads the 196 page bits with four).
  const std::uint8_t shifted[4] = {0x0D, 0x30, 0x00, 0x00};
  EXPECT_EQ(crc24q_bits(shifted, 28), 0x47EA4Bu);
}

TEST(InavWordTypes, EachEphemerisWordOncePerSubframe) {
  std::array<int, 7> seen{};
  for (int k = 1; k <= 15; ++k) {
    const int t = inav_e1b_word_type(2.0 * k + 30.0 * 100);
    if (inav_word_produced(t)) ++seen[static_cast<std::size_t>(t)];
  }
  for (int t = 1; t <= 6; ++t) EXPECT_EQ(seen[static_cast<std::size_t>(t)], 1) << t;
  EXPECT_GE(seen[0], 1);
  EXPECT_EQ(inav_e1b_word_type(2.0), 2);
}

TEST(InavSisa, IndexAndMetresAgree) {
  for (int i = 1; i <= 125; ++i) EXPECT_EQ(sisa_index(sisa_m(i)), i) << i;  // 0 m reads as "none"
  EXPECT_EQ(sisa_index(0.0), 255);
  EXPECT_EQ(sisa_index(7.0), 255);
  EXPECT_DOUBLE_EQ(sisa_m(255), 0.0);
}

TEST(InavPagePair, EveryFieldDecodesToTheEphemerisWithinOneLsb) {
  const orbit::NavData& nav = igs_inav();
  const InavIonoUtc iono{&nav.galileo_nequick, &nav.utc, 18};
  constexpr double kPi = kSemicircle_rad;
  int checked = 0;
  for (const orbit::Ephemeris& eph : nav.ephemerides) {
    if (eph.sat.system != GnssSystem::kGalileo || !(eph.gal_data_sources & orbit::kGalInavE1b)) continue;
    SCOPED_TRACE(static_cast<int>(eph.sat.number));
    const time::GpsTime t = eph.toe + 600.0;
    std::array<InavPagePair, 7> pairs{};
    for (int type = 0; type <= 6; ++type) {
      pairs[static_cast<std::size_t>(type)] = galileo_inav_page_pair(eph, type, t + 2.0 * type, iono);
      EXPECT_EQ(pairs[static_cast<std::size_t>(type)][0] >> 30, 0u);  // even part, nominal
      EXPECT_EQ(pairs[static_cast<std::size_t>(type)][4] >> 30, 2u);  // odd part, nominal
    }
    const std::optional<InavDecoded> d = decode_galileo_inav(pairs);
    ASSERT_TRUE(d.has_value());
    const orbit::Ephemeris& e = d->eph;
    EXPECT_EQ(e.sat, eph.sat);
    EXPECT_EQ(e.iode, eph.iode);
    EXPECT_EQ(e.toe, eph.toe);
    EXPECT_EQ(e.toc, eph.toc);
    EXPECT_EQ(e.health, eph.health & 0x1C7);
    EXPECT_EQ(d->wn, t.week() - 1024);
    EXPECT_EQ(d->tow_s, static_cast<int>(t.tow_s()));
    EXPECT_NEAR(e.m0_rad, eph.m0_rad, std::ldexp(kPi, -31));
    EXPECT_NEAR(e.e, eph.e, std::ldexp(1.0, -33));
    EXPECT_NEAR(e.sqrt_a_sqrtm, eph.sqrt_a_sqrtm, std::ldexp(1.0, -19));
    EXPECT_NEAR(e.omega0_rad, eph.omega0_rad, std::ldexp(kPi, -31));
    EXPECT_NEAR(e.i0_rad, eph.i0_rad, std::ldexp(kPi, -31));
    EXPECT_NEAR(e.omega_rad, eph.omega_rad, std::ldexp(kPi, -31));
    EXPECT_NEAR(e.idot_rad_s, eph.idot_rad_s, std::ldexp(kPi, -43));
    EXPECT_NEAR(e.omega_dot_rad_s, eph.omega_dot_rad_s, std::ldexp(kPi, -43));
    EXPECT_NEAR(e.delta_n_rad_s, eph.delta_n_rad_s, std::ldexp(kPi, -43));
    EXPECT_NEAR(e.cuc_rad, eph.cuc_rad, std::ldexp(1.0, -29));
    EXPECT_NEAR(e.cus_rad, eph.cus_rad, std::ldexp(1.0, -29));
    EXPECT_NEAR(e.cic_rad, eph.cic_rad, std::ldexp(1.0, -29));
    EXPECT_NEAR(e.cis_rad, eph.cis_rad, std::ldexp(1.0, -29));
    EXPECT_NEAR(e.crc_m, eph.crc_m, std::ldexp(1.0, -5));
    EXPECT_NEAR(e.crs_m, eph.crs_m, std::ldexp(1.0, -5));
    EXPECT_NEAR(e.af0_s, eph.af0_s, std::ldexp(1.0, -34));
    EXPECT_NEAR(e.af1_s_s, eph.af1_s_s, std::ldexp(1.0, -46));
    EXPECT_NEAR(e.af2_s_s2, eph.af2_s_s2, std::ldexp(1.0, -59));
    EXPECT_NEAR(e.tgd_s, eph.tgd_s, std::ldexp(1.0, -32));
    EXPECT_NEAR(e.tgd2_s, eph.tgd2_s, std::ldexp(1.0, -32));
    EXPECT_NEAR(e.sv_accuracy_m, eph.sv_accuracy_m, 1e-6);  // some files give 3.119999885559 for 3.12
    EXPECT_NEAR(d->ai[0], nav.galileo_nequick.ai[0], 0.25);
    EXPECT_NEAR(d->ai[1], nav.galileo_nequick.ai[1], std::ldexp(1.0, -8));
    EXPECT_NEAR(d->ai[2], nav.galileo_nequick.ai[2], std::ldexp(1.0, -15));
    EXPECT_EQ(d->leap_s, 18);
    // A flipped data bit fails the CRC.
    std::array<InavPagePair, 7> bad = pairs;
    bad[3][1] ^= 1u << 20;
    EXPECT_FALSE(decode_galileo_inav(bad).has_value());
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

}  // namespace
}  // namespace gnssemu::protocol::navmsg

// SPDX-License-Identifier: Apache-2.0
// GLONASS strings 1-5 from broadcast ephemerides: the Hamming check bits
// against strings a real receiver logged, the frame structure of the
// GLONASST day, and the round trip ephemeris -> strings -> decoder with
// every field back within its LSB (the RINEX values were themselves
// quantized from these bits, so they come back to the digit).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/navmsg/glonass_nav.hpp"

namespace gnssemu::protocol::navmsg {
namespace {

const orbit::NavData& igs_glonass() {
  static const orbit::NavData d =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  return d;
}

/// An 85-bit string given as 22 hex digits, right-aligned (b1 = LSB), in SFRBX words.
GlonassString from_hex(const char* hex) {
  GlonassString s{};
  for (int i = 0; i < 85; ++i) {  // i = 0: b85
    const int bit = 84 - i;        // from the LSB of the 88-bit number
    const int digit = 21 - bit / 4;
    const int v = hex[digit] <= '9' ? hex[digit] - '0' : hex[digit] - 'a' + 10;
    if ((v >> (bit % 4)) & 1) s[static_cast<std::size_t>(i / 32)] |= 0x80000000u >> (i % 32);
  }
  return s;
}

std::uint32_t check_bits(const GlonassString& s) { return s[2] >> 11 & 0xFF; }

// One frame of GLONASS slot 8 as a NovAtel OEM7 logged it (GLORAWFRAME example,
// docs.novatel.com/oem7/Content/Logs/GLORAWFRAME.htm): strings 1-15 with their check bits.
constexpr const char* kLoggedFrame[15] = {
    "010bab96ab4e821602d6a7", "021ba01b6b7e1530c4a7e3", "03800628618591fb3adfd1", "0480917120000045b0051b",
    "056c00000000238000683e", "0630002df3360b8e0c2628", "070b067dcf9697ea95be30", "08b1a2459eb21d6a02b627",
    "09fbc58921c697f6b0482d", "0ab2878224422060852340", "0b89a79bd46e97f9907a1c", "0cb30c5d35b4232100f3ce",
    "0d31290ee91698013206a7", "0eb40498ea662348843025", "0f82552595de97f8f184e8"};

TEST(GlonassHamming, MatchesTheCheckBitsOfLoggedStrings) {
  for (std::uint32_t k = 1; k <= 15; ++k) {
    SCOPED_TRACE(kLoggedFrame[k - 1]);
    const GlonassString s = from_hex(kLoggedFrame[k - 1]);
    EXPECT_EQ(s[0] >> 27, k);  // b84..b81 string number after the idle b85
    EXPECT_EQ(glonass_hamming(s), check_bits(s));
  }
}

TEST(GlonassHamming, EverySingleDataBitErrorIsDetected) {
  const GlonassString s = from_hex(kLoggedFrame[0]);
  for (int i = 1; i < 77; ++i) {  // b84 .. b9
    GlonassString e = s;
    e[static_cast<std::size_t>(i / 32)] ^= 0x80000000u >> (i % 32);
    EXPECT_NE(glonass_hamming(e), check_bits(e)) << "bit index " << i;
  }
}

TEST(GlonassStringSlot, FramesStartWithTheGlonasstDay) {
  // 2024-01-10 21:00:00 UTC = 2024-01-11 00:00:00 GLONASST = GPS week 2296, 3 d 21 h + 18 s.
  const time::GpsTime day0(2296, 3 * 86400.0 + 21 * 3600.0 + 18.0);
  GlonassStringSlot s = glonass_string_slot(day0 + 2.0, 18);
  EXPECT_EQ(s.string, 1);
  EXPECT_EQ(s.frame, 1);
  EXPECT_EQ(s.superframe, 1);
  EXPECT_DOUBLE_EQ(s.frame_start.tod_s, 0.0);
  EXPECT_EQ(s.frame_start.n4, 8);    // 2024-2027
  EXPECT_EQ(s.frame_start.nt, 11);   // 11 January of the leap year
  s = glonass_string_slot(day0 + 150.0 + 30.0 + 10.0, 18);
  EXPECT_EQ(s.string, 5);
  EXPECT_EQ(s.frame, 2);
  EXPECT_EQ(s.superframe, 2);
  EXPECT_DOUBLE_EQ(s.frame_start.tod_s, 180.0);
  s = glonass_string_slot(day0, 18);  // the last string of the day before
  EXPECT_EQ(s.string, 15);
  EXPECT_EQ(s.frame, 5);
  EXPECT_EQ(s.superframe, 576);
  EXPECT_EQ(s.frame_start.nt, 10);
}

TEST(GlonassStrings, EveryFieldDecodesToTheEphemerisWithinOneLsb) {
  int checked = 0;
  for (const orbit::Ephemeris& eph : igs_glonass().ephemerides) {
    if (eph.sat.system != GnssSystem::kGlonass) continue;
    SCOPED_TRACE(static_cast<int>(eph.sat.number));
    // The frame that starts 4 min after tb.
    const GlonassStringSlot slot0 = glonass_string_slot(eph.toe + 240.0 + 2.0, 18);
    ASSERT_EQ(slot0.string, 1);
    std::array<GlonassString, 5> strings{};
    for (int k = 1; k <= 5; ++k) {
      GlonassStringSlot slot = glonass_string_slot(eph.toe + 240.0 + 2.0 * k, 18);
      ASSERT_EQ(slot.string, k);
      strings[static_cast<std::size_t>(k - 1)] = glonass_string(eph, slot, 18);
      EXPECT_EQ(strings[static_cast<std::size_t>(k - 1)][3], static_cast<std::uint32_t>(slot.superframe << 16 | slot.frame));
    }
    const std::optional<GlonassDecoded> d = decode_glonass_strings(strings, eph.glo_channel, 18);
    ASSERT_TRUE(d.has_value());
    const orbit::Ephemeris& e = d->eph;
    EXPECT_EQ(e.sat, eph.sat);
    EXPECT_EQ(e.toe, eph.toe);
    EXPECT_EQ(e.iode, eph.iode);
    EXPECT_EQ(e.health, eph.health);
    EXPECT_EQ(e.glo_age_days, eph.glo_age_days);
    EXPECT_DOUBLE_EQ(d->tk_s, slot0.frame_start.tod_s);
    EXPECT_EQ(d->nt, slot0.frame_start.nt);
    EXPECT_EQ(d->n4, 8);
    EXPECT_EQ(d->m, 1);
    const double pos_lsb = std::ldexp(1.0, -11) * 1e3, vel_lsb = std::ldexp(1.0, -20) * 1e3,
                 acc_lsb = std::ldexp(1.0, -30) * 1e3;
    const auto near = [&](const Ecef& got, const Ecef& want, double lsb) {
      EXPECT_NEAR(got.x, want.x, lsb / 2 + 1e-9 * lsb);
      EXPECT_NEAR(got.y, want.y, lsb / 2 + 1e-9 * lsb);
      EXPECT_NEAR(got.z, want.z, lsb / 2 + 1e-9 * lsb);
    };
    near(e.pos_m, eph.pos_m, pos_lsb);
    near(e.vel_m_s, eph.vel_m_s, vel_lsb);
    near(e.acc_m_s2, eph.acc_m_s2, acc_lsb);
    EXPECT_NEAR(e.tau_n_s, eph.tau_n_s, std::ldexp(0.5, -30) + 1e-15);
    EXPECT_NEAR(e.gamma_n, eph.gamma_n, std::ldexp(0.5, -40) + 1e-18);
    // Re-encoding the decoded set gives the same bits.
    for (int k = 1; k <= 5; ++k) {
      const GlonassStringSlot slot = glonass_string_slot(eph.toe + 240.0 + 2.0 * k, 18);
      EXPECT_EQ(glonass_string(e, slot, 18), strings[static_cast<std::size_t>(k - 1)]);
    }
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(GlonassStrings, ACorruptedStringIsRejected) {
  const orbit::Ephemeris* eph = nullptr;
  for (const orbit::Ephemeris& e : igs_glonass().ephemerides) {
    if (e.sat.system == GnssSystem::kGlonass) eph = &e;
  }
  ASSERT_NE(eph, nullptr);
  std::array<GlonassString, 5> strings{};
  for (int k = 1; k <= 5; ++k) {
    strings[static_cast<std::size_t>(k - 1)] = glonass_string(*eph, glonass_string_slot(eph->toe + 2.0 * k + 240.0, 18), 18);
  }
  ASSERT_TRUE(decode_glonass_strings(strings, 0, 18).has_value());
  std::array<GlonassString, 5> bad = strings;
  bad[2][1] ^= 1u << 7;
  EXPECT_FALSE(decode_glonass_strings(bad, 0, 18).has_value());
  bad = strings;
  std::swap(bad[0], bad[1]);  // string numbers out of order
  EXPECT_FALSE(decode_glonass_strings(bad, 0, 18).has_value());
}

TEST(GlonassStrings, FtIndexFollowsTheIcdTable) {
  EXPECT_EQ(glonass_ft_index(0.0), 15);
  EXPECT_EQ(glonass_ft_index(1.0), 0);
  EXPECT_EQ(glonass_ft_index(2.2), 2);
  EXPECT_EQ(glonass_ft_index(20.0), 10);
  EXPECT_EQ(glonass_ft_index(1e4), 14);
}

}  // namespace
}  // namespace gnssemu::protocol::navmsg

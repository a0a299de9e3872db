// SPDX-License-Identifier: Apache-2.0
#pragma once
// What D1 and D2 both carry, checked the same way: a decoded BeiDou set
// against the ephemeris it was encoded from, every field within its LSB
// (BDS-SIS-ICD-B1I 3.0 §5.2.4 scales; D2 splits fields, never rescales them).
#include <gtest/gtest.h>

#include <cmath>

#include "core/orbit/nav_data.hpp"
#include "core/protocol/navmsg/beidou_d1.hpp"
#include "core/protocol/navmsg/nav_bits.hpp"

namespace gnssemu::protocol::navmsg::test {

inline void expect_beidou_set(const BeidouDecoded& d, const orbit::Ephemeris& eph,
                              const orbit::KlobucharParams& klobuchar) {
  constexpr double kPi = kSemicircle_rad;
  const orbit::Ephemeris& e = d.eph;
  EXPECT_EQ(e.toe, eph.toe);
  EXPECT_EQ(e.toc, eph.toc);
  EXPECT_EQ(e.iode, eph.iode & 0x1F);
  EXPECT_EQ(e.iodc, eph.iodc & 0x1F);
  EXPECT_EQ(e.health, eph.health & 1);
  EXPECT_NEAR(e.m0_rad, eph.m0_rad, std::ldexp(kPi, -31));
  EXPECT_NEAR(e.e, eph.e, std::ldexp(1.0, -33));
  EXPECT_NEAR(e.sqrt_a_sqrtm, eph.sqrt_a_sqrtm, std::ldexp(1.0, -19));
  EXPECT_NEAR(e.omega0_rad, eph.omega0_rad, std::ldexp(kPi, -31));
  EXPECT_NEAR(e.i0_rad, eph.i0_rad, std::ldexp(kPi, -31));
  EXPECT_NEAR(e.omega_rad, eph.omega_rad, std::ldexp(kPi, -31));
  EXPECT_NEAR(e.idot_rad_s, eph.idot_rad_s, std::ldexp(kPi, -43));
  EXPECT_NEAR(e.omega_dot_rad_s, eph.omega_dot_rad_s, std::ldexp(kPi, -43));
  EXPECT_NEAR(e.delta_n_rad_s, eph.delta_n_rad_s, std::ldexp(kPi, -43));
  EXPECT_NEAR(e.cuc_rad, eph.cuc_rad, std::ldexp(1.0, -31));
  EXPECT_NEAR(e.cus_rad, eph.cus_rad, std::ldexp(1.0, -31));
  EXPECT_NEAR(e.cic_rad, eph.cic_rad, std::ldexp(1.0, -31));
  EXPECT_NEAR(e.cis_rad, eph.cis_rad, std::ldexp(1.0, -31));
  EXPECT_NEAR(e.crc_m, eph.crc_m, std::ldexp(1.0, -6));
  EXPECT_NEAR(e.crs_m, eph.crs_m, std::ldexp(1.0, -6));
  EXPECT_NEAR(e.af0_s, eph.af0_s, std::ldexp(1.0, -33));
  EXPECT_NEAR(e.af1_s_s, eph.af1_s_s, std::ldexp(1.0, -50));
  EXPECT_NEAR(e.af2_s_s2, eph.af2_s_s2, std::ldexp(1.0, -66));
  EXPECT_NEAR(e.tgd_s, eph.tgd_s, 0.1e-9);
  EXPECT_NEAR(e.tgd2_s, eph.tgd2_s, 0.1e-9);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(d.alpha[i], klobuchar.alpha[i], std::ldexp(1.0, kKlobucharAlphaExp[i]));
    EXPECT_NEAR(d.beta[i], klobuchar.beta[i], std::ldexp(1.0, kKlobucharBetaExp[i]));
  }
}

}  // namespace gnssemu::protocol::navmsg::test

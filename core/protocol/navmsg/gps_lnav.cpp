// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/navmsg/gps_lnav.hpp"

#include <bit>
#include <cmath>

#include "core/protocol/navmsg/nav_bits.hpp"

namespace gnssemu::protocol::navmsg {

namespace {

/// Word bit of D29* (31), D30* (30) and source bit d_i (30 - i).
constexpr std::uint32_t mask_of(std::initializer_list<int> d, bool d29_star, bool d30_star) {
  std::uint32_t m = (d29_star ? 1u << 31 : 0u) | (d30_star ? 1u << 30 : 0u);
  for (int i : d) m |= 1u << (30 - i);
  return m;
}

// IS-GPS-200N Table 20-XIV: which previous-word and source bits each parity bit sums.
constexpr std::array<std::uint32_t, 6> kParityMasks{
    mask_of({1, 2, 3, 5, 6, 10, 11, 12, 13, 14, 17, 18, 20, 23}, true, false),
    mask_of({2, 3, 4, 6, 7, 11, 12, 13, 14, 15, 18, 19, 21, 24}, false, true),
    mask_of({1, 3, 4, 5, 7, 8, 12, 13, 14, 15, 16, 19, 20, 22}, true, false),
    mask_of({2, 4, 5, 6, 8, 9, 13, 14, 15, 16, 17, 20, 21, 23}, false, true),
    mask_of({1, 3, 5, 6, 7, 9, 10, 14, 15, 16, 17, 18, 21, 22, 24}, false, true),
    mask_of({3, 5, 6, 8, 9, 10, 11, 13, 15, 19, 22, 23, 24}, true, false),
};

constexpr double kSc = kSemicircle_rad;

/// Nominal URA per index, m (IS-GPS-200N §20.3.3.3.1.3); index 15: none.
constexpr std::array<double, 15> kUraMax_m{2.4, 3.4, 4.85, 6.85, 9.65, 13.65, 24.0, 48.0,
                                           96.0, 192.0, 384.0, 768.0, 1536.0, 3072.0, 6144.0};

using Data = BitString<240>;

void ephemeris_subframe(Data& b, const orbit::Ephemeris& eph, int id, int week) {
  if (id == 1) {
    b.put(static_cast<std::uint32_t>(week) & 0x3FF, 10);
    b.put(1, 2);  // codes on L2: P code
    b.put(static_cast<std::uint32_t>(ura_index(eph.sv_accuracy_m)), 4);
    b.put(static_cast<std::uint32_t>(eph.health) & 0x3F, 6);
    b.put(static_cast<std::uint32_t>(eph.iodc) >> 8 & 3, 2);
    b.skip(1 + 23 + 24 + 24 + 16);  // L2 P data flag, reserved words 4-7
    b.put(quantize_signed(eph.tgd_s, std::ldexp(1.0, -31), 8), 8);
    b.put(static_cast<std::uint32_t>(eph.iodc) & 0xFF, 8);
    b.put(quantize_unsigned(eph.toc.tow_s(), 16.0, 16), 16);
    b.put(quantize_signed(eph.af2_s_s2, std::ldexp(1.0, -55), 8), 8);
    b.put(quantize_signed(eph.af1_s_s, std::ldexp(1.0, -43), 16), 16);
    b.put(quantize_signed(eph.af0_s, std::ldexp(1.0, -31), 22), 22);
  } else if (id == 2) {
    b.put(static_cast<std::uint32_t>(eph.iode) & 0xFF, 8);
    b.put(quantize_signed(eph.crs_m, std::ldexp(1.0, -5), 16), 16);
    b.put(quantize_signed(eph.delta_n_rad_s / kSc, std::ldexp(1.0, -43), 16), 16);
    b.put(quantize_signed(eph.m0_rad / kSc, std::ldexp(1.0, -31), 32) >> 24, 8);
    b.put(quantize_signed(eph.m0_rad / kSc, std::ldexp(1.0, -31), 32) & 0xFFFFFF, 24);
    b.put(quantize_signed(eph.cuc_rad, std::ldexp(1.0, -29), 16), 16);
    b.put(quantize_unsigned(eph.e, std::ldexp(1.0, -33), 32) >> 24, 8);
    b.put(quantize_unsigned(eph.e, std::ldexp(1.0, -33), 32) & 0xFFFFFF, 24);
    b.put(quantize_signed(eph.cus_rad, std::ldexp(1.0, -29), 16), 16);
    b.put(quantize_unsigned(eph.sqrt_a_sqrtm, std::ldexp(1.0, -19), 32) >> 24, 8);
    b.put(quantize_unsigned(eph.sqrt_a_sqrtm, std::ldexp(1.0, -19), 32) & 0xFFFFFF, 24);
    b.put(quantize_unsigned(eph.toe.tow_s(), 16.0, 16), 16);
    b.put(eph.fit_interval_h > 4.0 ? 1 : 0, 1);
    b.put(0, 5);  // AODO
  } else {
    b.put(quantize_signed(eph.cic_rad, std::ldexp(1.0, -29), 16), 16);
    b.put(quantize_signed(eph.omega0_rad / kSc, std::ldexp(1.0, -31), 32) >> 24, 8);
    b.put(quantize_signed(eph.omega0_rad / kSc, std::ldexp(1.0, -31), 32) & 0xFFFFFF, 24);
    b.put(quantize_signed(eph.cis_rad, std::ldexp(1.0, -29), 16), 16);
    b.put(quantize_signed(eph.i0_rad / kSc, std::ldexp(1.0, -31), 32) >> 24, 8);
    b.put(quantize_signed(eph.i0_rad / kSc, std::ldexp(1.0, -31), 32) & 0xFFFFFF, 24);
    b.put(quantize_signed(eph.crc_m, std::ldexp(1.0, -5), 16), 16);
    b.put(quantize_signed(eph.omega_rad / kSc, std::ldexp(1.0, -31), 32) >> 24, 8);
    b.put(quantize_signed(eph.omega_rad / kSc, std::ldexp(1.0, -31), 32) & 0xFFFFFF, 24);
    b.put(quantize_signed(eph.omega_dot_rad_s / kSc, std::ldexp(1.0, -43), 24), 24);
    b.put(static_cast<std::uint32_t>(eph.iode) & 0xFF, 8);
    b.put(quantize_signed(eph.idot_rad_s / kSc, std::ldexp(1.0, -43), 14), 14);
  }
}

/// Subframe 4 page 18 (IS-GPS-200N Figure 20-1 sheet 8, §20.3.3.5.1.6-7).
void iono_utc_page(Data& b, const LnavIonoUtc& iono, int week) {
  b.put(1, 2);   // data id
  b.put(56, 6);  // SV id of page 18
  const orbit::KlobucharParams k = iono.klobuchar != nullptr ? *iono.klobuchar : orbit::KlobucharParams{};
  for (std::size_t i = 0; i < 4; ++i) b.put(quantize_signed(k.alpha[i], std::ldexp(1.0, kKlobucharAlphaExp[i]), 8), 8);
  for (std::size_t i = 0; i < 4; ++i) b.put(quantize_signed(k.beta[i], std::ldexp(1.0, kKlobucharBetaExp[i]), 8), 8);
  const orbit::UtcParams u = iono.utc != nullptr ? *iono.utc : orbit::UtcParams{};
  b.put(quantize_signed(u.a1_s_s, std::ldexp(1.0, -50), 24), 24);
  const std::uint32_t a0 = quantize_signed(u.a0_s, std::ldexp(1.0, -30), 32);
  b.put(a0 >> 8, 24);
  b.put(a0 & 0xFF, 8);
  b.put(quantize_unsigned(u.tot_s, 4096.0, 8), 8);
  const int wnt = u.valid ? u.wnt : week;
  b.put(static_cast<std::uint32_t>(wnt) & 0xFF, 8);
  b.put(static_cast<std::uint32_t>(iono.leap_seconds) & 0xFF, 8);
  b.put(static_cast<std::uint32_t>(wnt) & 0xFF, 8);  // WN_LSF: no leap second announced
  b.put(7, 8);                                         // DN
  b.put(static_cast<std::uint32_t>(iono.leap_seconds) & 0xFF, 8);
}

}  // namespace

std::uint32_t lnav_parity(std::uint32_t word) noexcept {
  std::uint32_t p = 0;
  for (const std::uint32_t m : kParityMasks) p = p << 1 | (static_cast<std::uint32_t>(std::popcount(word & m)) & 1u);
  return p;
}

int ura_index(double accuracy_m) noexcept {
  for (std::size_t i = 0; i < kUraMax_m.size(); ++i) {
    if (accuracy_m <= kUraMax_m[i]) return static_cast<int>(i);
  }
  return 15;
}

double ura_accuracy_m(int index) noexcept {
  return index >= 0 && index < static_cast<int>(kUraMax_m.size()) ? kUraMax_m[static_cast<std::size_t>(index)] : 0.0;
}

LnavSubframe gps_lnav_subframe(const orbit::Ephemeris& eph, int subframe_id, int week, double tow_end_s,
                               const LnavIonoUtc& iono) noexcept {
  Data b;
  b.put(0x8B, 8);  // TLM: preamble, message 0, integrity 0, reserved
  b.skip(16);
  b.put(static_cast<std::uint32_t>(std::lround(tow_end_s / kLnavSubframe_s)) & 0x1FFFF, 17);
  b.put(0, 2);  // alert, anti-spoof
  b.put(static_cast<std::uint32_t>(subframe_id) & 7, 3);
  b.skip(2);  // solved below
  if (subframe_id <= 3) {
    ephemeris_subframe(b, eph, subframe_id, week);
  } else {
    iono_utc_page(b, iono, week);
  }
  LnavSubframe words{};
  std::uint32_t prev = 0;  // the previous stored word: its D29, D30 give bit 31
  for (std::size_t w = 0; w < words.size(); ++w) {
    const std::uint32_t star = ((prev >> 1) ^ prev) & 1u;  // D29 xor D30
    std::uint32_t word = star << 31 | b.get(24 * w, 24) << 6;
    word |= lnav_parity(word);
    if (w == 1 || w == 9) {
      // HOW and word 10 end in two bits chosen so that D29 = D30 = 0 (IS-GPS-200N §20.3.5.2).
      for (std::uint32_t t = 0; t < 4; ++t) {
        std::uint32_t c = star << 31 | (b.get(24 * w, 22) << 2 | t) << 6;
        c |= lnav_parity(c);
        if ((c & 3u) == 0) {
          word = c;
          break;
        }
      }
    }
    words[w] = word & 0xBFFFFFFFu;  // bit 30 (D30*) is always clear
    prev = word;
  }
  return words;
}

}  // namespace gnssemu::protocol::navmsg

// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/navmsg/galileo_inav.hpp"

#include <cmath>

#include "core/protocol/navmsg/nav_bits.hpp"

namespace gnssemu::protocol::navmsg {

namespace {

using Word = BitString<128>;
using Part = BitString<128>;  // a 120-bit page part and its 8 pad bits

constexpr double kSc = kSemicircle_rad;
constexpr int kGstWeekOffset = 1024;  // GST WN = GPS week - 1024 (multi-gnss.md §1.2)

/// E1-B word type at each page pair of the subframe (see the header).
constexpr std::array<int, 15> kE1bOrder{2, 4, 6, 7, 8, 0, 0, 0, 0, 0, 1, 3, 5, 0, 0};

double sgn(const Word& w, std::size_t at, int n, double scale) noexcept {
  return static_cast<double>(sign_extend(w.get(at, n), n)) * scale;
}
double uns(const Word& w, std::size_t at, int n, double scale) noexcept { return w.get(at, n) * scale; }

std::uint32_t gst_tow(const time::GpsTime& t) noexcept { return static_cast<std::uint32_t>(std::lround(t.tow_s())) % 604800u; }
std::uint32_t gst_wn(const time::GpsTime& t) noexcept {
  return static_cast<std::uint32_t>(t.week() - kGstWeekOffset) & 0xFFF;
}

Word word_bits(const orbit::Ephemeris& eph, int type, const time::GpsTime& t, const InavIonoUtc& iono) noexcept {
  Word w;
  w.put(static_cast<std::uint32_t>(type), 6);
  const std::uint32_t iod = static_cast<std::uint32_t>(eph.iode) & 0x3FF;
  switch (type) {
    case 0:
      w.put(2, 2);  // time field: WN and TOW valid
      w.skip(88);
      w.put(gst_wn(t), 12);
      w.put(gst_tow(t), 20);
      break;
    case 1:
      w.put(iod, 10);
      w.put(quantize_unsigned(eph.toe.tow_s(), 60.0, 14), 14);
      w.put(quantize_signed(eph.m0_rad / kSc, std::ldexp(1.0, -31), 32), 32);
      w.put(quantize_unsigned(eph.e, std::ldexp(1.0, -33), 32), 32);
      w.put(quantize_unsigned(eph.sqrt_a_sqrtm, std::ldexp(1.0, -19), 32), 32);
      break;
    case 2:
      w.put(iod, 10);
      w.put(quantize_signed(eph.omega0_rad / kSc, std::ldexp(1.0, -31), 32), 32);
      w.put(quantize_signed(eph.i0_rad / kSc, std::ldexp(1.0, -31), 32), 32);
      w.put(quantize_signed(eph.omega_rad / kSc, std::ldexp(1.0, -31), 32), 32);
      w.put(quantize_signed(eph.idot_rad_s / kSc, std::ldexp(1.0, -43), 14), 14);
      break;
    case 3:
      w.put(iod, 10);
      w.put(quantize_signed(eph.omega_dot_rad_s / kSc, std::ldexp(1.0, -43), 24), 24);
      w.put(quantize_signed(eph.delta_n_rad_s / kSc, std::ldexp(1.0, -43), 16), 16);
      w.put(quantize_signed(eph.cuc_rad, std::ldexp(1.0, -29), 16), 16);
      w.put(quantize_signed(eph.cus_rad, std::ldexp(1.0, -29), 16), 16);
      w.put(quantize_signed(eph.crc_m, std::ldexp(1.0, -5), 16), 16);
      w.put(quantize_signed(eph.crs_m, std::ldexp(1.0, -5), 16), 16);
      w.put(static_cast<std::uint32_t>(sisa_index(eph.sv_accuracy_m)), 8);
      break;
    case 4:
      w.put(iod, 10);
      w.put(static_cast<std::uint32_t>(eph.sat.number) & 0x3F, 6);
      w.put(quantize_signed(eph.cic_rad, std::ldexp(1.0, -29), 16), 16);
      w.put(quantize_signed(eph.cis_rad, std::ldexp(1.0, -29), 16), 16);
      w.put(quantize_unsigned(eph.toc.tow_s(), 60.0, 14), 14);
      w.put(quantize_signed(eph.af0_s, std::ldexp(1.0, -34), 31), 31);
      w.put(quantize_signed(eph.af1_s_s, std::ldexp(1.0, -46), 21), 21);
      w.put(quantize_signed(eph.af2_s_s2, std::ldexp(1.0, -59), 6), 6);
      break;
    case 5: {
      const orbit::NequickParams n = iono.nequick != nullptr ? *iono.nequick : orbit::NequickParams{};
      w.put(quantize_unsigned(n.ai[0], 0.25, 11), 11);
      w.put(quantize_signed(n.ai[1], std::ldexp(1.0, -8), 11), 11);
      w.put(quantize_signed(n.ai[2], std::ldexp(1.0, -15), 14), 14);
      w.put(0, 5);  // storm flags of the five regions
      w.put(quantize_signed(eph.tgd2_s, std::ldexp(1.0, -32), 10), 10);  // BGD(E1,E5a)
      w.put(quantize_signed(eph.tgd_s, std::ldexp(1.0, -32), 10), 10);   // BGD(E1,E5b)
      const auto h = static_cast<std::uint32_t>(eph.health);
      w.put(h >> 7 & 3u, 2);  // E5b HS
      w.put(h >> 1 & 3u, 2);  // E1-B HS
      w.put(h >> 6 & 1u, 1);  // E5b DVS
      w.put(h & 1u, 1);       // E1-B DVS
      w.put(gst_wn(t), 12);
      w.put(gst_tow(t), 20);
      break;
    }
    case 6: {
      const orbit::UtcParams u = iono.utc != nullptr ? *iono.utc : orbit::UtcParams{};
      const int wnt = u.valid ? u.wnt : t.week();
      w.put(quantize_signed(u.a0_s, std::ldexp(1.0, -30), 32), 32);
      w.put(quantize_signed(u.a1_s_s, std::ldexp(1.0, -50), 24), 24);
      w.put(static_cast<std::uint32_t>(iono.leap_seconds) & 0xFF, 8);
      w.put(quantize_unsigned(u.tot_s, 3600.0, 8), 8);
      w.put(static_cast<std::uint32_t>(wnt - kGstWeekOffset) & 0xFF, 8);
      w.put(static_cast<std::uint32_t>(wnt - kGstWeekOffset) & 0xFF, 8);  // WN_LSF: no leap second announced
      w.put(7, 3);                                                         // DN
      w.put(static_cast<std::uint32_t>(iono.leap_seconds) & 0xFF, 8);
      w.put(gst_tow(t), 20);
      break;
    }
    default:
      break;
  }
  return w;
}

std::uint32_t crc_of(const Part& even, const Part& odd) noexcept {
  BitString<200> b;
  for (std::size_t i = 0; i < 114; ++i) b.put(even.get(i, 1), 1);
  for (std::size_t i = 0; i < 82; ++i) b.put(odd.get(i, 1), 1);
  return crc24q_bits(b.bytes().data(), 196);
}

}  // namespace

int inav_e1b_word_type(double tow_end_s) noexcept {
  const long k = static_cast<long>(std::floor((tow_end_s - kInavPagePair_s) / kInavPagePair_s + 0.5));
  return kE1bOrder[static_cast<std::size_t>(((k % 15) + 15) % 15)];
}

std::uint32_t crc24q_bits(const std::uint8_t* bytes, std::size_t n_bits) noexcept {
  std::uint32_t crc = 0;
  for (std::size_t i = 0; i < n_bits; ++i) {
    const std::uint32_t in = (bytes[i / 8] >> (7 - i % 8)) & 1u;
    const std::uint32_t top = (crc >> 23) & 1u;
    crc = (crc << 1) & 0xFFFFFF;
    if (top ^ in) crc ^= 0x864CFB;
  }
  return crc;
}

int sisa_index(double m) noexcept {
  if (!(m > 0.0) || m > 6.0 + 1e-9) return 255;
  if (m < 0.5 - 1e-9) return static_cast<int>(std::lround(m / 0.01));
  if (m < 1.0 - 1e-9) return 50 + static_cast<int>(std::lround((m - 0.5) / 0.02));
  if (m < 2.0 - 1e-9) return 75 + static_cast<int>(std::lround((m - 1.0) / 0.04));
  return 100 + static_cast<int>(std::lround((m - 2.0) / 0.16));
}

double sisa_m(int i) noexcept {
  if (i < 0 || i > 125) return 0.0;
  if (i < 50) return i * 0.01;
  if (i < 75) return 0.5 + (i - 50) * 0.02;
  if (i < 100) return 1.0 + (i - 75) * 0.04;
  return 2.0 + (i - 100) * 0.16;
}

InavPagePair galileo_inav_page_pair(const orbit::Ephemeris& eph, int type, const time::GpsTime& t_start,
                                    const InavIonoUtc& iono) {
  const Word w = word_bits(eph, type, t_start, iono);
  Part even, odd;
  even.put(0, 2);  // even part, nominal page
  for (std::size_t i = 0; i < 112; ++i) even.put(w.get(i, 1), 1);
  odd.put(2, 2);  // odd part, nominal page
  odd.put(w.get(112, 16), 16);
  odd.skip(40 + 22 + 2);  // reserved 1, SAR, spare
  odd.put(crc_of(even, odd), 24);
  InavPagePair p{};
  for (std::size_t i = 0; i < 4; ++i) {
    p[i] = even.get(32 * i, 32);
    p[i + 4] = odd.get(32 * i, 32);
  }
  return p;
}

std::optional<InavDecoded> decode_galileo_inav(const std::array<InavPagePair, 7>& pairs) {
  std::array<Word, 7> w;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    Part even, odd;
    for (std::size_t i = 0; i < 4; ++i) {
      even.put(pairs[k][i], 32);
      odd.put(pairs[k][i + 4], 32);
    }
    if (even.get(0, 2) != 0 || odd.get(0, 2) != 2 || odd.get(82, 24) != crc_of(even, odd)) return std::nullopt;
    for (std::size_t i = 0; i < 112; ++i) w[k].put(even.get(2 + i, 1), 1);
    w[k].put(odd.get(2, 16), 16);
    if (w[k].get(0, 6) != k) return std::nullopt;
  }
  const std::uint32_t iod = w[1].get(6, 10);
  for (std::size_t k = 2; k <= 4; ++k) {
    if (w[k].get(6, 10) != iod) return std::nullopt;
  }
  InavDecoded d;
  orbit::Ephemeris& e = d.eph;
  d.wn = static_cast<int>(w[0].get(96, 12));
  d.tow_s = static_cast<int>(w[0].get(108, 20));
  e.iode = static_cast<int>(iod);
  e.sat = {GnssSystem::kGalileo, static_cast<int>(w[4].get(16, 6))};
  const int week = d.wn + kGstWeekOffset;
  // toe and toc within half a week of word type 0's time.
  const auto near_week = [&](double tow) {
    double dt = tow - d.tow_s;
    int wk = week;
    if (dt > 302400.0) --wk;
    if (dt < -302400.0) ++wk;
    return time::GpsTime(wk, tow);
  };
  e.toe = near_week(uns(w[1], 16, 14, 60.0));
  e.m0_rad = sgn(w[1], 30, 32, std::ldexp(kSc, -31));
  e.e = uns(w[1], 62, 32, std::ldexp(1.0, -33));
  e.sqrt_a_sqrtm = uns(w[1], 94, 32, std::ldexp(1.0, -19));
  e.omega0_rad = sgn(w[2], 16, 32, std::ldexp(kSc, -31));
  e.i0_rad = sgn(w[2], 48, 32, std::ldexp(kSc, -31));
  e.omega_rad = sgn(w[2], 80, 32, std::ldexp(kSc, -31));
  e.idot_rad_s = sgn(w[2], 112, 14, std::ldexp(kSc, -43));
  e.omega_dot_rad_s = sgn(w[3], 16, 24, std::ldexp(kSc, -43));
  e.delta_n_rad_s = sgn(w[3], 40, 16, std::ldexp(kSc, -43));
  e.cuc_rad = sgn(w[3], 56, 16, std::ldexp(1.0, -29));
  e.cus_rad = sgn(w[3], 72, 16, std::ldexp(1.0, -29));
  e.crc_m = sgn(w[3], 88, 16, std::ldexp(1.0, -5));
  e.crs_m = sgn(w[3], 104, 16, std::ldexp(1.0, -5));
  e.sv_accuracy_m = sisa_m(static_cast<int>(w[3].get(120, 8)));
  e.cic_rad = sgn(w[4], 22, 16, std::ldexp(1.0, -29));
  e.cis_rad = sgn(w[4], 38, 16, std::ldexp(1.0, -29));
  e.toc = near_week(uns(w[4], 54, 14, 60.0));
  e.af0_s = sgn(w[4], 68, 31, std::ldexp(1.0, -34));
  e.af1_s_s = sgn(w[4], 99, 21, std::ldexp(1.0, -46));
  e.af2_s_s2 = sgn(w[4], 120, 6, std::ldexp(1.0, -59));
  d.ai = {uns(w[5], 6, 11, 0.25), sgn(w[5], 17, 11, std::ldexp(1.0, -8)), sgn(w[5], 28, 14, std::ldexp(1.0, -15))};
  e.tgd2_s = sgn(w[5], 47, 10, std::ldexp(1.0, -32));
  e.tgd_s = sgn(w[5], 57, 10, std::ldexp(1.0, -32));
  e.health = static_cast<int>(w[5].get(67, 2) << 7 | w[5].get(69, 2) << 1 | w[5].get(71, 1) << 6 | w[5].get(72, 1));
  e.gal_data_sources = orbit::kGalInavE1b | orbit::kGalClockE5b;
  d.a0_s = sgn(w[6], 6, 32, std::ldexp(1.0, -30));
  d.a1_s_s = sgn(w[6], 38, 24, std::ldexp(1.0, -50));
  d.leap_s = static_cast<int>(sign_extend(w[6].get(62, 8), 8));
  return d;
}

}  // namespace gnssemu::protocol::navmsg

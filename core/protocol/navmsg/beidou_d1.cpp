// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/navmsg/beidou_d1.hpp"

#include <cmath>

#include "core/protocol/navmsg/gps_lnav.hpp"
#include "core/protocol/navmsg/nav_bits.hpp"
#include "core/time/beidou_time.hpp"

namespace gnssemu::protocol::navmsg {

namespace {

using Info = BeidouInfo;

constexpr double kSc = kSemicircle_rad;
constexpr std::uint32_t kPreamble = 0x712;  // 11100010010 (BDS ICD §5.2.4.1)

/// The BDT week and seconds of week (whole) of a GPS time.
time::WeekTime bdt(const time::GpsTime& t) noexcept { return time::bdt_from_gps(t); }

/// Two's complement field of Info back to a value.
double sgn(const Info& b, std::size_t& at, int n, double scale) noexcept {
  const double v = static_cast<double>(sign_extend(b.get(at, n), n)) * scale;
  at += static_cast<std::size_t>(n);
  return v;
}
double uns(const Info& b, std::size_t& at, int n, double scale) noexcept {
  const double v = b.get(at, n) * scale;
  at += static_cast<std::size_t>(n);
  return v;
}
/// A field of more than 32 bits is never needed; 32-bit fields as is.
std::uint32_t raw(const Info& b, std::size_t& at, int n) noexcept {
  const std::uint32_t v = b.get(at, n);
  at += static_cast<std::size_t>(n);
  return v;
}

}  // namespace

std::uint32_t bch15_11_parity(std::uint32_t data11) noexcept {
  std::uint32_t r = 0;  // remainder of data(X) X^4 mod X^4 + X + 1
  for (int i = 10; i >= 0; --i) {
    const std::uint32_t fb = ((data11 >> i) & 1u) ^ ((r >> 3) & 1u);
    r = (r << 1) & 0xF;
    if (fb) r ^= 0x3;
  }
  return r;
}

D1Subframe beidou_words(const BeidouInfo& info) noexcept {
  D1Subframe w{};
  const std::uint32_t w1 = info.get(0, 26);
  w[0] = w1 << 4 | bch15_11_parity(w1 & 0x7FF);
  for (std::size_t k = 1; k < 10; ++k) {
    const std::uint32_t d = info.get(26 + 22 * (k - 1), 22);
    w[k] = d << 8 | bch15_11_parity(d >> 11) << 4 | bch15_11_parity(d & 0x7FF);
  }
  return w;
}

bool beidou_info(const D1Subframe& w, BeidouInfo& info) noexcept {
  if ((w[0] & 0xF) != bch15_11_parity(w[0] >> 4 & 0x7FF)) return false;
  info.put(w[0] >> 4 & 0x3FFFFFF, 26);
  for (std::size_t k = 1; k < 10; ++k) {
    const std::uint32_t d = w[k] >> 8 & 0x3FFFFF;
    if ((w[k] >> 4 & 0xF) != bch15_11_parity(d >> 11) || (w[k] & 0xF) != bch15_11_parity(d & 0x7FF)) return false;
    info.put(d, 22);
  }
  return true;
}

int d1_subframe_id(const time::GpsTime& t_start) noexcept {
  const long k = std::lround(bdt(t_start).tow_s / kD1Subframe_s);
  return static_cast<int>(k % 5) + 1;
}

D1Subframe beidou_d1_subframe(const orbit::Ephemeris& eph, int id, const time::GpsTime& t_start,
                              const orbit::KlobucharParams* klobuchar) noexcept {
  Info b;
  b.put(kPreamble, 11);
  b.skip(4);
  b.put(static_cast<std::uint32_t>(id) & 7, 3);
  b.put(static_cast<std::uint32_t>(std::lround(bdt(t_start).tow_s)) & 0xFFFFF, 20);
  const time::WeekTime toe = bdt(eph.toe);
  if (id == 1) {
    const time::WeekTime toc = bdt(eph.toc);
    b.put(static_cast<std::uint32_t>(eph.health) & 1u, 1);
    b.put(static_cast<std::uint32_t>(eph.iodc) & 0x1F, 5);
    b.put(static_cast<std::uint32_t>(ura_index(eph.sv_accuracy_m)), 4);
    b.put(static_cast<std::uint32_t>(bdt(t_start).week) & 0x1FFF, 13);
    b.put(quantize_unsigned(toc.tow_s, 8.0, 17), 17);
    b.put(quantize_signed(eph.tgd_s, 0.1e-9, 10), 10);
    b.put(quantize_signed(eph.tgd2_s, 0.1e-9, 10), 10);
    const orbit::KlobucharParams k = klobuchar != nullptr ? *klobuchar : orbit::KlobucharParams{};
    for (std::size_t i = 0; i < 4; ++i) b.put(quantize_signed(k.alpha[i], std::ldexp(1.0, kKlobucharAlphaExp[i]), 8), 8);
    for (std::size_t i = 0; i < 4; ++i) b.put(quantize_signed(k.beta[i], std::ldexp(1.0, kKlobucharBetaExp[i]), 8), 8);
    b.put(quantize_signed(eph.af2_s_s2, std::ldexp(1.0, -66), 11), 11);
    b.put(quantize_signed(eph.af0_s, std::ldexp(1.0, -33), 24), 24);
    b.put(quantize_signed(eph.af1_s_s, std::ldexp(1.0, -50), 22), 22);
    b.put(static_cast<std::uint32_t>(eph.iode) & 0x1F, 5);
  } else if (id == 2) {
    b.put(quantize_signed(eph.delta_n_rad_s / kSc, std::ldexp(1.0, -43), 16), 16);
    b.put(quantize_signed(eph.cuc_rad, std::ldexp(1.0, -31), 18), 18);
    b.put(quantize_signed(eph.m0_rad / kSc, std::ldexp(1.0, -31), 32), 32);
    b.put(quantize_unsigned(eph.e, std::ldexp(1.0, -33), 32), 32);
    b.put(quantize_signed(eph.cus_rad, std::ldexp(1.0, -31), 18), 18);
    b.put(quantize_signed(eph.crc_m, std::ldexp(1.0, -6), 18), 18);
    b.put(quantize_signed(eph.crs_m, std::ldexp(1.0, -6), 18), 18);
    b.put(quantize_unsigned(eph.sqrt_a_sqrtm, std::ldexp(1.0, -19), 32), 32);
    b.put(quantize_unsigned(toe.tow_s, 8.0, 17) >> 15, 2);
  } else {
    b.put(quantize_unsigned(toe.tow_s, 8.0, 17) & 0x7FFF, 15);
    b.put(quantize_signed(eph.i0_rad / kSc, std::ldexp(1.0, -31), 32), 32);
    b.put(quantize_signed(eph.cic_rad, std::ldexp(1.0, -31), 18), 18);
    b.put(quantize_signed(eph.omega_dot_rad_s / kSc, std::ldexp(1.0, -43), 24), 24);
    b.put(quantize_signed(eph.cis_rad, std::ldexp(1.0, -31), 18), 18);
    b.put(quantize_signed(eph.idot_rad_s / kSc, std::ldexp(1.0, -43), 14), 14);
    b.put(quantize_signed(eph.omega0_rad / kSc, std::ldexp(1.0, -31), 32), 32);
    b.put(quantize_signed(eph.omega_rad / kSc, std::ldexp(1.0, -31), 32), 32);
  }
  return beidou_words(b);
}

std::optional<BeidouDecoded> decode_beidou_d1(const std::array<D1Subframe, 3>& subframes, int prn) {
  std::array<Info, 3> b;
  std::array<std::uint32_t, 3> sow{};
  for (std::size_t k = 0; k < 3; ++k) {
    if (!beidou_info(subframes[k], b[k])) return std::nullopt;
    if (b[k].get(0, 11) != kPreamble || b[k].get(15, 3) != k + 1) return std::nullopt;
    sow[k] = b[k].get(18, 20);
    if (k > 0 && sow[k] != sow[k - 1] + 6) return std::nullopt;
  }
  BeidouDecoded d;
  orbit::Ephemeris& e = d.eph;
  e.sat = {GnssSystem::kBeiDou, prn};
  d.sow_s = static_cast<int>(sow[0]);
  std::size_t at = 38;
  e.health = static_cast<int>(raw(b[0], at, 1));
  e.iodc = static_cast<int>(raw(b[0], at, 5));
  const int urai = static_cast<int>(raw(b[0], at, 4));
  d.week = static_cast<int>(raw(b[0], at, 13));
  const double toc = uns(b[0], at, 17, 8.0);
  e.tgd_s = sgn(b[0], at, 10, 0.1e-9);
  e.tgd2_s = sgn(b[0], at, 10, 0.1e-9);
  for (std::size_t i = 0; i < 4; ++i) d.alpha[i] = sgn(b[0], at, 8, std::ldexp(1.0, kKlobucharAlphaExp[i]));
  for (std::size_t i = 0; i < 4; ++i) d.beta[i] = sgn(b[0], at, 8, std::ldexp(1.0, kKlobucharBetaExp[i]));
  e.af2_s_s2 = sgn(b[0], at, 11, std::ldexp(1.0, -66));
  e.af0_s = sgn(b[0], at, 24, std::ldexp(1.0, -33));
  e.af1_s_s = sgn(b[0], at, 22, std::ldexp(1.0, -50));
  e.iode = static_cast<int>(raw(b[0], at, 5));
  at = 38;
  e.delta_n_rad_s = sgn(b[1], at, 16, std::ldexp(kSc, -43));
  e.cuc_rad = sgn(b[1], at, 18, std::ldexp(1.0, -31));
  e.m0_rad = sgn(b[1], at, 32, std::ldexp(kSc, -31));
  e.e = uns(b[1], at, 32, std::ldexp(1.0, -33));
  e.cus_rad = sgn(b[1], at, 18, std::ldexp(1.0, -31));
  e.crc_m = sgn(b[1], at, 18, std::ldexp(1.0, -6));
  e.crs_m = sgn(b[1], at, 18, std::ldexp(1.0, -6));
  e.sqrt_a_sqrtm = uns(b[1], at, 32, std::ldexp(1.0, -19));
  const std::uint32_t toe_hi = raw(b[1], at, 2);
  at = 38;
  const double toe = static_cast<double>(toe_hi << 15 | raw(b[2], at, 15)) * 8.0;
  e.i0_rad = sgn(b[2], at, 32, std::ldexp(kSc, -31));
  e.cic_rad = sgn(b[2], at, 18, std::ldexp(1.0, -31));
  e.omega_dot_rad_s = sgn(b[2], at, 24, std::ldexp(kSc, -43));
  e.cis_rad = sgn(b[2], at, 18, std::ldexp(1.0, -31));
  e.idot_rad_s = sgn(b[2], at, 14, std::ldexp(kSc, -43));
  e.omega0_rad = sgn(b[2], at, 32, std::ldexp(kSc, -31));
  e.omega_rad = sgn(b[2], at, 32, std::ldexp(kSc, -31));
  // toe and toc in the BDT week of the subframe, or the one either side when closer.
  const auto near = [&](double tow) {
    int wk = d.week;
    if (tow - d.sow_s > 302400.0) --wk;
    if (tow - d.sow_s < -302400.0) ++wk;
    return time::gps_from_bdt({wk, tow});
  };
  e.toe = near(toe);
  e.toc = near(toc);
  e.sv_accuracy_m = ura_accuracy_m(urai);
  return d;
}

}  // namespace gnssemu::protocol::navmsg

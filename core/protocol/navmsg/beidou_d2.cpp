// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/navmsg/beidou_d2.hpp"

#include <cmath>
#include <cstdint>

#include "core/protocol/navmsg/gps_lnav.hpp"
#include "core/protocol/navmsg/nav_bits.hpp"
#include "core/time/beidou_time.hpp"

namespace gnssemu::protocol::navmsg {

namespace {

constexpr double kSc = kSemicircle_rad;
constexpr std::uint32_t kPreamble = 0x712;  // BDS ICD §5.3.2
constexpr std::size_t kPageData = 42;        // first page-specific data bit (after Pnum)

/// One field of the D2 pages: where it starts (page 1-10, data bit) and its
/// width; a field split across two pages has its MSBs on `page` and the
/// `lsb_bits` LSBs at the start of the next page's data.
struct Field {
  int page;
  std::size_t at;
  int bits;
  int lsb_bits = 0;
};

// §5.3.3.1, Figures 5-10 to 5-19 (bit positions within the data bits: 26 of
// word 1, 22 of each further word; Pnum ends at 41).
constexpr Field kSatH1{1, 42, 1}, kAodc{1, 43, 5}, kUrai{1, 48, 4}, kWeek{1, 52, 13}, kToc{1, 65, 17},
    kTgd1{1, 82, 10}, kTgd2{1, 92, 10};
constexpr Field kA0{3, 80, 24}, kA1{3, 104, 22, 18}, kA2{4, 60, 11}, kAode{4, 71, 5}, kDeltaN{4, 76, 16},
    kCuc{4, 92, 18, 4}, kM0{5, 46, 32}, kCus{5, 78, 18}, kE{5, 96, 32, 22}, kSqrtA{6, 64, 32}, kCic{6, 96, 18, 8},
    kCis{7, 50, 18}, kToe{7, 68, 17}, kI0{7, 85, 32, 11}, kCrc{8, 53, 18}, kCrs{8, 71, 18},
    kOmegaDot{8, 89, 24, 5}, kOmega0{9, 47, 32}, kOmega{9, 79, 32, 5}, kIdot{10, 47, 14};

void put(BeidouInfo& b, int page, const Field& f, std::uint32_t value) noexcept {
  const std::uint32_t v = f.bits == 32 ? value : value & ((1u << f.bits) - 1u);
  if (f.page == page) {
    b.seek(f.at);
    b.put(v >> f.lsb_bits, f.bits - f.lsb_bits);
  } else if (f.lsb_bits > 0 && f.page + 1 == page) {
    b.seek(kPageData);
    b.put(v & ((1u << f.lsb_bits) - 1u), f.lsb_bits);
  }
}

std::uint32_t get(const std::array<BeidouInfo, kD2Pages>& b, const Field& f) noexcept {
  const std::uint32_t msb = b[static_cast<std::size_t>(f.page - 1)].get(f.at, f.bits - f.lsb_bits);
  if (f.lsb_bits == 0) return msb;
  return msb << f.lsb_bits | b[static_cast<std::size_t>(f.page)].get(kPageData, f.lsb_bits);
}
double sgn(const std::array<BeidouInfo, kD2Pages>& b, const Field& f, double scale) noexcept {
  return static_cast<double>(sign_extend(get(b, f), f.bits)) * scale;
}

}  // namespace

int d2_page(const time::GpsTime& t_start) noexcept {
  const long k = std::lround(time::bdt_from_gps(t_start).tow_s / kD2Frame_s);
  return static_cast<int>(k % kD2Pages) + 1;
}

D1Subframe beidou_d2_page(const orbit::Ephemeris& eph, int page, const time::GpsTime& t_start,
                          const orbit::KlobucharParams* klobuchar) noexcept {
  const time::WeekTime t = time::bdt_from_gps(t_start);
  BeidouInfo b;
  b.put(kPreamble, 11);
  b.skip(4);
  b.put(1, 3);  // subframe 1
  b.put(static_cast<std::uint32_t>(std::lround(t.tow_s)) & 0xFFFFF, 20);
  b.put(static_cast<std::uint32_t>(page) & 0xF, 4);
  if (page == 2) {
    const orbit::KlobucharParams k = klobuchar != nullptr ? *klobuchar : orbit::KlobucharParams{};
    for (std::size_t i = 0; i < 4; ++i) b.put(quantize_signed(k.alpha[i], std::ldexp(1.0, kKlobucharAlphaExp[i]), 8), 8);
    for (std::size_t i = 0; i < 4; ++i) b.put(quantize_signed(k.beta[i], std::ldexp(1.0, kKlobucharBetaExp[i]), 8), 8);
    return beidou_words(b);
  }
  const auto u = [](double v, double scale, const Field& f) { return quantize_unsigned(v, scale, f.bits); };
  const auto s = [](double v, double scale, const Field& f) { return quantize_signed(v, scale, f.bits); };
  const auto p2 = [](int n) { return std::ldexp(1.0, n); };
  put(b, page, kSatH1, static_cast<std::uint32_t>(eph.health) & 1u);
  put(b, page, kAodc, static_cast<std::uint32_t>(eph.iodc));
  put(b, page, kUrai, static_cast<std::uint32_t>(ura_index(eph.sv_accuracy_m)));
  put(b, page, kWeek, static_cast<std::uint32_t>(t.week));
  put(b, page, kToc, u(time::bdt_from_gps(eph.toc).tow_s, 8.0, kToc));
  put(b, page, kTgd1, s(eph.tgd_s, 0.1e-9, kTgd1));
  put(b, page, kTgd2, s(eph.tgd2_s, 0.1e-9, kTgd2));
  put(b, page, kA0, s(eph.af0_s, p2(-33), kA0));
  put(b, page, kA1, s(eph.af1_s_s, p2(-50), kA1));
  put(b, page, kA2, s(eph.af2_s_s2, p2(-66), kA2));
  put(b, page, kAode, static_cast<std::uint32_t>(eph.iode));
  put(b, page, kDeltaN, s(eph.delta_n_rad_s / kSc, p2(-43), kDeltaN));
  put(b, page, kCuc, s(eph.cuc_rad, p2(-31), kCuc));
  put(b, page, kM0, s(eph.m0_rad / kSc, p2(-31), kM0));
  put(b, page, kCus, s(eph.cus_rad, p2(-31), kCus));
  put(b, page, kE, u(eph.e, p2(-33), kE));
  put(b, page, kSqrtA, u(eph.sqrt_a_sqrtm, p2(-19), kSqrtA));
  put(b, page, kCic, s(eph.cic_rad, p2(-31), kCic));
  put(b, page, kCis, s(eph.cis_rad, p2(-31), kCis));
  put(b, page, kToe, u(time::bdt_from_gps(eph.toe).tow_s, 8.0, kToe));
  put(b, page, kI0, s(eph.i0_rad / kSc, p2(-31), kI0));
  put(b, page, kCrc, s(eph.crc_m, p2(-6), kCrc));
  put(b, page, kCrs, s(eph.crs_m, p2(-6), kCrs));
  put(b, page, kOmegaDot, s(eph.omega_dot_rad_s / kSc, p2(-43), kOmegaDot));
  put(b, page, kOmega0, s(eph.omega0_rad / kSc, p2(-31), kOmega0));
  put(b, page, kOmega, s(eph.omega_rad / kSc, p2(-31), kOmega));
  put(b, page, kIdot, s(eph.idot_rad_s / kSc, p2(-43), kIdot));
  return beidou_words(b);
}

std::optional<BeidouDecoded> decode_beidou_d2(const std::array<D1Subframe, kD2Pages>& pages, int prn) {
  std::array<BeidouInfo, kD2Pages> b;
  std::uint32_t sow0 = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (!beidou_info(pages[k], b[k])) return std::nullopt;
    if (b[k].get(0, 11) != kPreamble || b[k].get(15, 3) != 1 || b[k].get(38, 4) != k + 1) return std::nullopt;
    const std::uint32_t sow = b[k].get(18, 20);
    if (k == 0) sow0 = sow;
    if (sow != sow0 + 3 * k) return std::nullopt;
  }
  BeidouDecoded d;
  orbit::Ephemeris& e = d.eph;
  e.sat = {GnssSystem::kBeiDou, prn};
  d.sow_s = static_cast<int>(sow0);
  d.week = static_cast<int>(get(b, kWeek));
  const auto p2 = [](int n) { return std::ldexp(1.0, n); };
  e.health = static_cast<int>(get(b, kSatH1));
  e.iodc = static_cast<int>(get(b, kAodc));
  e.iode = static_cast<int>(get(b, kAode));
  for (std::size_t i = 0; i < 4; ++i) {
    d.alpha[i] = static_cast<double>(sign_extend(b[1].get(kPageData + 8 * i, 8), 8)) * p2(kKlobucharAlphaExp[i]);
    d.beta[i] = static_cast<double>(sign_extend(b[1].get(kPageData + 32 + 8 * i, 8), 8)) * p2(kKlobucharBetaExp[i]);
  }
  e.tgd_s = sgn(b, kTgd1, 0.1e-9);
  e.tgd2_s = sgn(b, kTgd2, 0.1e-9);
  e.af0_s = sgn(b, kA0, p2(-33));
  e.af1_s_s = sgn(b, kA1, p2(-50));
  e.af2_s_s2 = sgn(b, kA2, p2(-66));
  e.delta_n_rad_s = sgn(b, kDeltaN, p2(-43)) * kSc;
  e.cuc_rad = sgn(b, kCuc, p2(-31));
  e.m0_rad = sgn(b, kM0, p2(-31)) * kSc;
  e.cus_rad = sgn(b, kCus, p2(-31));
  e.e = get(b, kE) * p2(-33);
  e.sqrt_a_sqrtm = get(b, kSqrtA) * p2(-19);
  e.cic_rad = sgn(b, kCic, p2(-31));
  e.cis_rad = sgn(b, kCis, p2(-31));
  e.i0_rad = sgn(b, kI0, p2(-31)) * kSc;
  e.crc_m = sgn(b, kCrc, p2(-6));
  e.crs_m = sgn(b, kCrs, p2(-6));
  e.omega_dot_rad_s = sgn(b, kOmegaDot, p2(-43)) * kSc;
  e.omega0_rad = sgn(b, kOmega0, p2(-31)) * kSc;
  e.omega_rad = sgn(b, kOmega, p2(-31)) * kSc;
  e.idot_rad_s = sgn(b, kIdot, p2(-43)) * kSc;
  const auto near = [&](double tow) {
    int wk = d.week;
    if (tow - d.sow_s > 302400.0) --wk;
    if (tow - d.sow_s < -302400.0) ++wk;
    return time::gps_from_bdt({wk, tow});
  };
  e.toe = near(get(b, kToe) * 8.0);
  e.toc = near(get(b, kToc) * 8.0);
  e.sv_accuracy_m = ura_accuracy_m(static_cast<int>(get(b, kUrai)));
  return d;
}

}  // namespace gnssemu::protocol::navmsg

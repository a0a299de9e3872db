// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/navmsg/glonass_nav.hpp"

#include <bit>
#include <cmath>

#include "core/protocol/navmsg/nav_bits.hpp"

namespace gnssemu::protocol::navmsg {

namespace {

using Bits = BitString<96>;  // b85 at index 0 .. b1 at index 84, then the pad of word 2

/// Index in Bits of ICD bit b (85..1).
constexpr std::size_t at(int b) noexcept { return static_cast<std::size_t>(85 - b); }

Bits to_bits(const GlonassString& s) noexcept {
  Bits b;
  for (int w = 0; w < 3; ++w) b.put(s[static_cast<std::size_t>(w)], 32);
  return b;
}

GlonassString to_words(const Bits& b, const GlonassStringSlot& slot) noexcept {
  return {b.get(0, 32), b.get(32, 32), b.get(64, 32) & 0xFFFFF800u,
          (static_cast<std::uint32_t>(slot.superframe) & 0xFFFF) << 16 | (static_cast<std::uint32_t>(slot.frame) & 0xFF)};
}

/// Sign-magnitude field back to a value.
double sm(std::uint32_t v, int n, double scale) noexcept {
  const double mag = static_cast<double>(v & ((1u << (n - 1)) - 1u)) * scale;
  return (v >> (n - 1)) & 1u ? -mag : mag;
}

/// FT index -> accuracy, m (ICD GLONASS Ed. 5.1 Table 4.4).
constexpr std::array<double, 15> kFt_m{1.0, 2.0, 2.5, 4.0, 5.0, 7.0, 10.0, 12.0, 14.0, 16.0, 32.0, 64.0, 128.0, 256.0, 512.0};

constexpr double kKm = 1e3;

/// One coordinate's velocity (2^-20 km/s), acceleration (2^-30 km/s^2) and position (2^-11 km) fields.
void put_axis(Bits& b, double pos_m, double vel_m_s, double acc_m_s2) noexcept {
  b.put(quantize_sign_magnitude(vel_m_s / kKm, std::ldexp(1.0, -20), 24), 24);
  b.put(quantize_sign_magnitude(acc_m_s2 / kKm, std::ldexp(1.0, -30), 5), 5);
  b.put(quantize_sign_magnitude(pos_m / kKm, std::ldexp(1.0, -11), 27), 27);
}

void get_axis(const Bits& b, double& pos_m, double& vel_m_s, double& acc_m_s2) noexcept {
  vel_m_s = sm(b.get(at(64), 24), 24, std::ldexp(1.0, -20)) * kKm;
  acc_m_s2 = sm(b.get(at(40), 5), 5, std::ldexp(1.0, -30)) * kKm;
  pos_m = sm(b.get(at(35), 27), 27, std::ldexp(1.0, -11)) * kKm;
}

}  // namespace

GlonassStringSlot glonass_string_slot(const time::GpsTime& t_end, int leap_s) {
  const time::GlonassTime g = time::glonass_from_gps(t_end - kGlonassString_s, leap_s);
  const double tod = std::min(g.tod_s, 86400.0 - kGlonassString_s);  // a leap second's repeated 02:59:60
  const int frame_of_day = static_cast<int>(std::floor(tod / kGlonassFrame_s + 1e-9));
  GlonassStringSlot s;
  s.string = static_cast<int>(std::floor((tod - frame_of_day * kGlonassFrame_s) / kGlonassString_s + 1e-9)) + 1;
  s.frame = frame_of_day % 5 + 1;
  s.superframe = frame_of_day / 5 + 1;
  s.frame_start = {g.n4, g.nt, frame_of_day * kGlonassFrame_s};
  return s;
}

std::uint32_t glonass_hamming(const GlonassString& s) noexcept {
  const Bits b = to_bits(s);
  std::uint32_t beta = 0;  // beta1 at bit 0 .. beta7 at bit 6
  std::uint32_t all = 0;   // parity of the data bits
  int pos = 2;             // Hamming position of the previous data bit
  for (int k = 9; k <= 85; ++k) {
    do ++pos;
    while (std::has_single_bit(static_cast<unsigned>(pos)));  // check-bit positions 1, 2, 4, ..., 64
    if (b.get(at(k), 1) == 0) continue;
    beta ^= static_cast<std::uint32_t>(pos);
    all ^= 1u;
  }
  beta &= 0x7F;
  const std::uint32_t beta8 = (all ^ static_cast<std::uint32_t>(std::popcount(beta))) & 1u;
  return beta8 << 7 | beta;  // b8 = beta8 ... b1 = beta1, b1 sent last
}

int glonass_ft_index(double accuracy_m) noexcept {
  if (!(accuracy_m > 0.0)) return 15;
  for (std::size_t i = 0; i < kFt_m.size(); ++i) {
    if (accuracy_m <= kFt_m[i]) return static_cast<int>(i);
  }
  return 14;
}

GlonassString glonass_string(const orbit::Ephemeris& eph, const GlonassStringSlot& slot, int leap_s) {
  const time::GlonassTime tb = time::glonass_from_gps(eph.toe, leap_s);
  const auto tb_index = static_cast<std::uint32_t>(std::lround(tb.tod_s / 900.0)) & 0x7F;
  const std::uint32_t bn = static_cast<std::uint32_t>(eph.health) & 7u;
  const std::uint32_t ln = eph.health != 0 ? 1u : 0u;
  Bits b;
  b.put(0, 1);  // b85 idle
  b.put(static_cast<std::uint32_t>(slot.string) & 0xF, 4);
  switch (slot.string) {
    case 1: {
      b.skip(2);
      b.put(0, 2);  // P1: the tb interval is not in RINEX
      const double tk = slot.frame_start.tod_s;
      const auto h = static_cast<std::uint32_t>(tk / 3600.0);
      const auto mi = static_cast<std::uint32_t>((tk - h * 3600.0) / 60.0);
      b.put(h, 5);
      b.put(mi, 6);
      b.put(tk - h * 3600.0 - mi * 60.0 >= 30.0 ? 1 : 0, 1);
      put_axis(b, eph.pos_m.x, eph.vel_m_s.x, eph.acc_m_s2.x);
      break;
    }
    case 2:
      b.put(bn, 3);
      b.put(tb_index & 1u, 1);  // P2: tb odd
      b.put(tb_index, 7);
      b.skip(5);
      put_axis(b, eph.pos_m.y, eph.vel_m_s.y, eph.acc_m_s2.y);
      break;
    case 3:
      b.put(0, 1);  // P3: almanac of four satellites in this frame
      b.put(quantize_sign_magnitude(eph.gamma_n, std::ldexp(1.0, -40), 11), 11);
      b.skip(1);
      b.put(0, 2);  // P: tau_c and tau_GPS from the ground
      b.put(ln, 1);
      put_axis(b, eph.pos_m.z, eph.vel_m_s.z, eph.acc_m_s2.z);
      break;
    case 4:
      b.put(quantize_sign_magnitude(eph.tau_n_s, std::ldexp(1.0, -30), 22), 22);
      b.put(0, 5);  // delta tau_n
      b.put(static_cast<std::uint32_t>(eph.glo_age_days) & 0x1F, 5);
      b.skip(14);
      b.put(0, 1);  // P4
      b.put(static_cast<std::uint32_t>(glonass_ft_index(eph.sv_accuracy_m)), 4);
      b.skip(3);
      b.put(static_cast<std::uint32_t>(slot.frame_start.nt) & 0x7FF, 11);
      b.put(static_cast<std::uint32_t>(eph.sat.number) & 0x1F, 5);
      b.put(1, 2);  // M: GLONASS-M
      break;
    case 5:
      b.put(static_cast<std::uint32_t>(slot.frame_start.nt) & 0x7FF, 11);  // NA: the almanac's day
      b.put(0, 32);                                                         // tau_c
      b.skip(1);
      b.put(static_cast<std::uint32_t>(slot.frame_start.n4) & 0x1F, 5);
      b.put(0, 22);  // tau_GPS
      b.put(ln, 1);
      break;
    default:
      break;
  }
  GlonassString s = to_words(b, slot);
  const std::uint32_t kx = glonass_hamming(s);
  b.seek(at(8));
  b.put(kx, 8);
  s = to_words(b, slot);
  return s;
}

std::optional<GlonassDecoded> decode_glonass_strings(const std::array<GlonassString, 5>& strings, int channel,
                                                     int leap_s) {
  std::array<Bits, 5> b;
  for (std::size_t i = 0; i < strings.size(); ++i) {
    b[i] = to_bits(strings[i]);
    if (b[i].get(at(8), 8) != glonass_hamming(strings[i]) || b[i].get(at(84), 4) != i + 1) return std::nullopt;
  }
  GlonassDecoded d;
  orbit::Ephemeris& e = d.eph;
  e.sat = {GnssSystem::kGlonass, static_cast<int>(b[3].get(at(15), 5))};
  e.glo_channel = channel;
  d.tk_s = b[0].get(at(76), 5) * 3600.0 + b[0].get(at(71), 6) * 60.0 + b[0].get(at(65), 1) * 30.0;
  get_axis(b[0], e.pos_m.x, e.vel_m_s.x, e.acc_m_s2.x);
  e.health = static_cast<int>(b[1].get(at(80), 3));
  e.iode = static_cast<int>(b[1].get(at(76), 7));
  get_axis(b[1], e.pos_m.y, e.vel_m_s.y, e.acc_m_s2.y);
  e.gamma_n = sm(b[2].get(at(79), 11), 11, std::ldexp(1.0, -40));
  get_axis(b[2], e.pos_m.z, e.vel_m_s.z, e.acc_m_s2.z);
  e.tau_n_s = sm(b[3].get(at(80), 22), 22, std::ldexp(1.0, -30));
  e.glo_age_days = static_cast<int>(b[3].get(at(53), 5));
  d.ft = static_cast<int>(b[3].get(at(33), 4));
  d.nt = static_cast<int>(b[3].get(at(26), 11));
  d.m = static_cast<int>(b[3].get(at(10), 2));
  d.n4 = static_cast<int>(b[4].get(at(36), 5));
  if (d.n4 < 1 || d.nt < 1 || d.nt > 1461) return std::nullopt;
  // tb on the day of the frame, or the day either side when closer to tk (a set across midnight).
  const time::GpsTime frame = time::gps_from_glonass({d.n4, d.nt, d.tk_s}, leap_s);
  double dt = e.iode * 900.0 - d.tk_s;
  if (dt > 43200.0) dt -= 86400.0;
  if (dt < -43200.0) dt += 86400.0;
  e.toe = frame + dt;
  e.toc = e.toe;
  e.sv_accuracy_m = d.ft < 15 ? kFt_m[static_cast<std::size_t>(d.ft)] : 0.0;
  return d;
}

}  // namespace gnssemu::protocol::navmsg

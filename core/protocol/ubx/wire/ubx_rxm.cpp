// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/wire/ubx_rxm.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "core/common/constants.hpp"
#include "core/common/gnss_systems.hpp"
#include "core/protocol/navmsg/beidou_d1.hpp"
#include "core/protocol/navmsg/beidou_d2.hpp"
#include "core/protocol/navmsg/galileo_inav.hpp"
#include "core/protocol/navmsg/glonass_nav.hpp"
#include "core/protocol/navmsg/gps_lnav.hpp"
#include "core/protocol/ubx/config/ubx_gnss.hpp"

namespace gnssemu::protocol::ubx {

namespace {

/// Nearest n with base * 2^n to sigma, in [0, 15].
std::uint8_t log2_index(double sigma, double base) noexcept {
  if (!(sigma > base)) return 0;
  const double n = std::round(std::log2(sigma / base));
  return static_cast<std::uint8_t>(std::clamp(n, 0.0, 15.0));
}

template <class T>
void put(std::uint8_t* p, const T& v) noexcept {
  std::memcpy(p, &v, sizeof v);
}

/// GLONASS freqId: channel k + 7 (0..13); 0 for other systems.
std::uint8_t freq_id(GnssSystem sys, int glonass_channel) noexcept {
  return sys == GnssSystem::kGlonass ? static_cast<std::uint8_t>(std::clamp(glonass_channel + 7, 0, 13)) : 0;
}

}  // namespace

std::uint8_t rawx_pr_stdev(double sigma_m) noexcept { return log2_index(sigma_m, 0.01); }

std::uint8_t rawx_cp_stdev(double sigma_cycles, bool valid) noexcept {
  if (!valid || !std::isfinite(sigma_cycles)) return 15;
  return static_cast<std::uint8_t>(std::clamp(std::round(sigma_cycles / 0.004), 1.0, 14.0));
}

std::uint8_t rawx_do_stdev(double sigma_hz) noexcept { return log2_index(sigma_hz, 0.002); }

std::size_t rxm_rawx(const receiver::RawEpoch& raw, Generation g, std::string& out) {
  if (!raw.time_valid) return 0;
  const int n = std::clamp(raw.num_meas, 0, kRawxMaxMeas);
  std::array<std::uint8_t, kRawxHeaderBytes + kRawxMeasBytes * receiver::kMaxRawMeasurements> payload{};
  const int n_fit = std::min<int>(n, receiver::kMaxRawMeasurements);
  std::uint8_t* p = payload.data();
  put(p, raw.t_rx.tow_s());
  put(p + 8, static_cast<std::uint16_t>(raw.t_rx.week()));
  put(p + 10, static_cast<std::int8_t>(raw.leap_seconds));
  p[11] = static_cast<std::uint8_t>(n_fit);
  p[12] = static_cast<std::uint8_t>((raw.leap_seconds_valid ? 1 : 0) | (raw.clock_reset ? 2 : 0));
  p[13] = 1;  // version 1: sigId is meaningful (RTKLIB ignores it for version 0)
  for (int i = 0; i < n_fit; ++i) {
    const receiver::RawMeasurement& m = raw.meas[static_cast<std::size_t>(i)];
    std::uint8_t* q = payload.data() + kRawxHeaderBytes + kRawxMeasBytes * static_cast<std::size_t>(i);
    put(q, m.pseudorange_m);
    // u-blox reports a BeiDou GEO's phase half a cycle behind the MEOs' convention:
    // RTKLIB's decode_rxmrawx adds 0.5 to it ("half-cycle shift correction for
    // BDS GEO"), so the chip's cpMes carries -0.5 and a converted RINEX gets
    // the phase back. MSM (RTCM) carries the phase itself.
    const double cp_shift_cycles = is_beidou_geo(m.sat) ? -0.5 : 0.0;
    put(q + 8, m.carrier_valid ? m.carrier_phase_cycles + cp_shift_cycles : 0.0);
    put(q + 16, static_cast<float>(m.doppler_hz));
    q[20] = system_info(m.sat.system).ubx_gnss_id;
    q[21] = ubx_sv_id(m.sat);
    std::uint8_t sig = 0;
    if (g != Generation::kM8) {
      sig = signal_info(m.signal).ubx_sig_id;
      if (is_beidou_geo(m.sat)) ++sig;  // B1I/B2I D2 on GEOs
    }
    q[22] = sig;
    q[23] = freq_id(m.sat.system, m.glonass_channel);
    const double lock_ms = std::isfinite(m.lock_time_s) ? std::clamp(m.lock_time_s * 1e3, 0.0, 64500.0) : 0.0;
    put(q + 24, static_cast<std::uint16_t>(m.carrier_valid ? lock_ms : 0.0));
    q[26] = static_cast<std::uint8_t>(std::isfinite(m.cn0_dbhz) ? std::clamp(std::round(m.cn0_dbhz), 0.0, 255.0) : 0.0);
    q[27] = rawx_pr_stdev(m.pseudorange_sigma_m);
    q[28] = rawx_cp_stdev(m.carrier_sigma_cycles, m.carrier_valid);
    q[29] = rawx_do_stdev(m.doppler_sigma_hz);
    q[30] = static_cast<std::uint8_t>((m.pseudorange_valid ? 1 : 0) | (m.carrier_valid ? 2 : 0) |
                                      (m.carrier_valid && m.half_cycle_resolved ? 4 : 0) |
                                      (m.carrier_valid && m.half_cycle_subtracted ? 8 : 0));
  }
  return append_frame(out, msg::kRxmRawx,
                      {payload.data(), kRawxHeaderBytes + kRawxMeasBytes * static_cast<std::size_t>(n_fit)});
}

std::size_t rxm_sfrbx(SatId sat, int glonass_channel, std::span<const std::uint32_t> words, Generation g,
                      std::string& out) {
  std::array<std::uint8_t, 8 + 4 * 10> payload{};
  const std::size_t n = std::min<std::size_t>(words.size(), 10);
  payload[0] = system_info(sat.system).ubx_gnss_id;
  payload[1] = ubx_sv_id(sat);
  if (g != Generation::kM8) {
    // The signal the data came on: Galileo I/NAV on E1-B (sigId 1), BeiDou GEO D2 (1).
    if (sat.system == GnssSystem::kGalileo || is_beidou_geo(sat)) payload[2] = 1;
  }
  payload[3] = freq_id(sat.system, glonass_channel);
  payload[4] = static_cast<std::uint8_t>(n);
  payload[6] = 2;  // version
  for (std::size_t i = 0; i < n; ++i) put(payload.data() + 8 + 4 * i, words[i]);
  return append_frame(out, msg::kRxmSfrbx, {payload.data(), 8 + 4 * n});
}

namespace {

/// The SFRBX units of a satellite's L1-band message: their period, s, the
/// offset of their ends from GPS time's week start, s, and their length, s
/// (the time the satellite must be tracked through); 0: none produced.
struct UnitGrid {
  double unit_s = 0.0;
  double offset_s = 0.0;
  double length_s = 0.0;
};

UnitGrid unit_grid(SatId sat, int leap_s) noexcept {
  if (is_beidou_geo(sat)) {
    // D2 subframe 1 (the ephemeris pages) only: 0.6 s at the start of each
    // 3-s frame of the BDT week (GPST - 14 s), so it ends 2.6 s into GPST's 3-s grid.
    return {navmsg::kD2Frame_s, 2.0 + navmsg::kD2Subframe_s, navmsg::kD2Subframe_s};
  }
  switch (sat.system) {
    case GnssSystem::kGps:
    case GnssSystem::kQzss:
      return {navmsg::kLnavSubframe_s, 0.0, navmsg::kLnavSubframe_s};
    case GnssSystem::kGalileo:
      return {navmsg::kInavPagePair_s, 0.0, navmsg::kInavPagePair_s};
    case GnssSystem::kBeiDou:
      // Subframes start on the 6-s grid of the BDT week: GPST - 14 s.
      return {navmsg::kD1Subframe_s, 2.0, navmsg::kD1Subframe_s};
    case GnssSystem::kGlonass:
      // Strings start on the even seconds of the GLONASST day: GPST - leap + 3 h.
      return {navmsg::kGlonassString_s, static_cast<double>(((leap_s % 2) + 2) % 2), navmsg::kGlonassString_s};
    default:
      return {};
  }
}

/// Encode the unit of m's satellite ending at t_end (a GPS time on the grid); false: none.
bool encode_unit(const RawSource& src, const receiver::RawMeasurement& m, const time::GpsTime& t_end, Generation g,
                 std::string& out) {
  if (m.sat.system == GnssSystem::kGlonass) {
    const navmsg::GlonassStringSlot slot = navmsg::glonass_string_slot(t_end, src.iono.leap_seconds);
    if (slot.string > navmsg::kGlonassStringsProduced) return false;
    // A satellite changes sets at frame boundaries only: the set of the frame's start.
    const time::GpsTime frame_start = t_end - navmsg::kGlonassString_s * slot.string;
    const orbit::Ephemeris* eph = src.ephemerides->select(m.sat, frame_start);
    if (eph == nullptr) return false;
    const navmsg::GlonassString s = navmsg::glonass_string(*eph, slot, src.iono.leap_seconds);
    rxm_sfrbx(m.sat, m.glonass_channel, s, g, out);
    return true;
  }
  if (m.sat.system == GnssSystem::kGalileo) {
    // GST = GPST: week and TOW as GPS time's.
    const double tow_end = t_end - time::GpsTime((t_end - navmsg::kInavPagePair_s).week(), 0.0);
    const int type = navmsg::inav_e1b_word_type(tow_end);
    if (!navmsg::inav_word_produced(type)) return false;
    // One set per subframe: the set of the subframe's start.
    const double into_subframe = std::fmod(tow_end - navmsg::kInavPagePair_s, navmsg::kInavSubframe_s);
    const orbit::Ephemeris* eph =
        src.ephemerides->select(m.sat, t_end - navmsg::kInavPagePair_s - into_subframe);
    if (eph == nullptr) return false;
    const navmsg::InavPagePair p = navmsg::galileo_inav_page_pair(
        *eph, type, t_end - navmsg::kInavPagePair_s,
        {src.galileo_nequick, src.iono.utc, src.iono.leap_seconds});
    // Nine words, as a real ZED-F9P (HPG 1.12) sends them (rtk-raw.md §1.3), the
    // ninth 0: RTKLIB 2.4.3 takes no Galileo page from fewer than 44 payload bytes.
    std::array<std::uint32_t, 9> words{};
    std::copy(p.begin(), p.end(), words.begin());
    rxm_sfrbx(m.sat, 0, words, g, out);
    return true;
  }
  if (m.sat.system == GnssSystem::kBeiDou) {
    if (is_beidou_geo(m.sat)) {
      const time::GpsTime start = t_end - navmsg::kD2Subframe_s;
      const int page = navmsg::d2_page(start);
      // Pages 1-10 carry one set: the set at page 1's frame.
      const orbit::Ephemeris* eph = src.ephemerides->select(m.sat, start - navmsg::kD2Frame_s * (page - 1));
      if (eph == nullptr) return false;
      rxm_sfrbx(m.sat, 0, navmsg::beidou_d2_page(*eph, page, start, src.beidou_klobuchar), g, out);
      return true;
    }
    const time::GpsTime start = t_end - navmsg::kD1Subframe_s;
    const int id = navmsg::d1_subframe_id(start);
    if (id > 3) return false;  // almanac
    // Subframes 1-3 of a frame carry one set: the set of the frame's start.
    const orbit::Ephemeris* eph = src.ephemerides->select(m.sat, start - navmsg::kD1Subframe_s * (id - 1));
    if (eph == nullptr) return false;
    rxm_sfrbx(m.sat, 0, navmsg::beidou_d1_subframe(*eph, id, start, src.beidou_klobuchar), g, out);
    return true;
  }
  const orbit::Ephemeris* eph = src.ephemerides->select(m.sat, t_end - 1.0);
  if (eph == nullptr) return false;
  switch (m.sat.system) {
    case GnssSystem::kGps:
    case GnssSystem::kQzss: {
      // The subframe that ends at a week's start belongs to the week before.
      const time::GpsTime start = t_end - navmsg::kLnavSubframe_s;
      const double tow_end = t_end - time::GpsTime(start.week(), 0.0);
      if (!navmsg::lnav_page_produced(tow_end)) return false;
      const navmsg::LnavSubframe sf =
          navmsg::gps_lnav_subframe(*eph, navmsg::lnav_subframe_id(tow_end), start.week(), tow_end, src.iono);
      rxm_sfrbx(m.sat, 0, sf, g, out);
      return true;
    }
    default:
      return false;
  }
}

}  // namespace

int rxm_sfrbx_due(const RawSource& src, double period_s, Generation g, MessageList& out) {
  if (src.epoch == nullptr || src.ephemerides == nullptr || !src.epoch->time_valid) return 0;
  int added = 0;
  const receiver::RawEpoch& raw = *src.epoch;
  for (int i = 0; i < raw.num_meas; ++i) {
    const receiver::RawMeasurement& m = raw.meas[static_cast<std::size_t>(i)];
    if (signal_info(m.signal).band != 0 || !m.pseudorange_valid || !std::isfinite(m.pseudorange_m)) continue;
    const UnitGrid grid = unit_grid(m.sat, src.iono.leap_seconds);
    if (grid.unit_s == 0.0) continue;
    // Transmit time now and at the previous epoch, on the unit grid of the week.
    const time::GpsTime tx = raw.t_rx - m.pseudorange_m / kSpeedOfLight_m_s;
    const time::GpsTime week_start(tx.week(), 0.0);
    const double units = std::floor((tx - week_start - grid.offset_s) / grid.unit_s);
    const time::GpsTime t_end = week_start + (grid.offset_s + units * grid.unit_s);
    if (!(tx - t_end < period_s)) continue;            // no unit ended within this epoch
    if (!(m.lock_time_s + 1e-6 >= grid.length_s)) continue;  // not tracked through the whole unit
    if (encode_unit(src, m, t_end, g, out.buffer())) {
      out.close("RXM-SFRBX", Protocol::kUbx);
      ++added;
    }
  }
  return added;
}

}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
// UBX output of the other systems: NAV-SIG (M9), NAV-TIMEGLO, NAV-TIMEGAL,
// NAV-TIMEBDS, MON-HW2 and MON-GNSS. Time-scale relations: shared/reference/
// multi-gnss.md §1.2; field layouts: UBX-13003221 (M8) and the M9 interface
// description; checked against pygpsdata-MIXED.log (docs/ubx.md §Multi-GNSS).
#include <cstring>

#include "core/common/gnss_signals.hpp"
#include "core/common/gnss_systems.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/protocol/ubx/wire/ubx_encoder_detail.hpp"
#include "core/protocol/ubx/device/ubx_front_end.hpp"
#include "core/protocol/ubx/config/ubx_gnss.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"

namespace gnssemu::protocol::ubx {

namespace {

using namespace detail;

constexpr std::int64_t kNsPerS = 1000000000;
constexpr std::int64_t kSecondsPerWeek = 604800;
constexpr std::int64_t kSecondsPerDay = 86400;
constexpr int kGstWeekOffset = 1024;   // GST week 0 = GPS week 1024 (1999-08-22)
constexpr int kBdtWeekOffset = 1356;   // BDT week 0 = GPS week 1356 (2006-01-01)
constexpr int kBdtMinusGpstS = -14;    // BDT = GPST - 14 s
constexpr int kGlonasstMinusUtcS = 10800;  // GLONASST = UTC(SU) + 3 h
constexpr int kFirstGlonassPeriodYear = 1996;  // N4 = 1: 1996-1999 (ICD GLONASS 5.1)
constexpr std::uint8_t kCfgSourceFlash = 102;  // MON-HW2 cfgSource: flash image (a NEO-M8N has flash)

/// A time as whole seconds (rounded to the nearest) and the rest in ns.
struct WholeAndFraction {
  std::int64_t s = 0;
  std::int32_t frac_ns = 0;
};
WholeAndFraction split_ns(std::int64_t ns) noexcept {
  std::int64_t s = (ns + kNsPerS / 2) / kNsPerS;
  if (ns + kNsPerS / 2 < 0 && (ns + kNsPerS / 2) % kNsPerS != 0) --s;  // floor
  return {s, static_cast<std::int32_t>(ns - s * kNsPerS)};
}

/// Nanoseconds since the GPS epoch (1980-01-06 00:00:00 GPST) of the epoch, at the ns.
std::int64_t gps_ns(const Common& c) noexcept {
  return (static_cast<std::int64_t>(c.week) * kSecondsPerWeek * 1000 + c.itow) * 1000000 + c.ftow_ns;
}

struct NavTimeSowParts {
  std::int64_t week = 0;
  WholeAndFraction tow;
};

/// Week and time of week (whole s + ns) of a system whose time is GPST + offset_s with
/// weeks counted from GPS week week_offset.
NavTimeSowParts sow_of(const Common& c, int offset_s, int week_offset) noexcept {
  const WholeAndFraction t = split_ns(gps_ns(c) + static_cast<std::int64_t>(offset_s) * kNsPerS);
  NavTimeSowParts p;
  p.week = t.s / kSecondsPerWeek;
  p.tow = {t.s - p.week * kSecondsPerWeek, t.frac_ns};
  if (p.tow.s < 0) {
    p.tow.s += kSecondsPerWeek;
    --p.week;
  }
  p.week -= week_offset;
  return p;
}

std::size_t time_sow(MsgId id, const Fix& fix, int offset_s, int week_offset, int leap_s, std::string& out) {
  const Common c = derive(fix);
  wire::NavTimeSow m{};
  m.iTOW = c.itow;
  m.tAcc = c.has_time ? to_acc<std::uint32_t>(fix.time_acc_s * 1e9) : 0xFFFFFFFF;
  if (c.has_time) {
    const NavTimeSowParts p = sow_of(c, offset_s, week_offset);
    m.sow = static_cast<std::uint32_t>(p.tow.s);
    m.fSow = p.tow.frac_ns;
    m.week = static_cast<std::int16_t>(std::clamp<std::int64_t>(p.week, 0, 32767));
    m.leapS = static_cast<std::int8_t>(std::clamp(leap_s, -128, 127));
    m.valid = p.week >= 0 ? 0x07 : 0x05;  // towValid, weekValid (not before the system's week 0), leapSValid
  }
  return append_message(out, id, m);
}

}  // namespace

std::size_t UbxEncoder::nav_timegal(const Fix& fix, std::string& out) const {
  return time_sow(msg::kNavTimegal, fix, 0, kGstWeekOffset, fix.leap_seconds, out);
}

std::size_t UbxEncoder::nav_timebds(const Fix& fix, std::string& out) const {
  return time_sow(msg::kNavTimebds, fix, kBdtMinusGpstS, kBdtWeekOffset, fix.leap_seconds + kBdtMinusGpstS, out);
}

std::size_t UbxEncoder::nav_timeglo(const Fix& fix, std::string& out) const {
  const Common c = derive(fix);
  wire::NavTimeglo m{};
  m.iTOW = c.itow;
  m.tAcc = c.has_time ? to_acc<std::uint32_t>(fix.time_acc_s * 1e9) : 0xFFFFFFFF;
  if (c.has_time) {
    const std::int64_t glo_ns =
        gps_ns(c) + static_cast<std::int64_t>(kGlonasstMinusUtcS - fix.leap_seconds) * kNsPerS;
    const WholeAndFraction t = split_ns(glo_ns);
    std::int64_t days = t.s / kSecondsPerDay;
    std::int64_t tod = t.s - days * kSecondsPerDay;
    if (tod < 0) {
      tod += kSecondsPerDay;
      --days;
    }
    int year = 0, month = 0, day = 0;
    const std::int64_t day_number = time::days_from_civil(1980, 1, 6) + days;
    time::civil_from_days(day_number, year, month, day);
    const int period = (year - kFirstGlonassPeriodYear) / 4;
    m.TOD = static_cast<std::uint32_t>(tod);
    m.fTOD = t.frac_ns;
    m.Nt = static_cast<std::uint16_t>(day_number - time::days_from_civil(kFirstGlonassPeriodYear + 4 * period, 1, 1) + 1);
    m.N4 = static_cast<std::uint8_t>(std::clamp(period + 1, 0, 255));
    m.valid = year >= kFirstGlonassPeriodYear ? 0x03 : 0x01;  // todValid, dateValid
  }
  return append_message(out, msg::kNavTimeglo, m);
}

std::size_t UbxEncoder::nav_sig(const Fix& fix, std::string& out) const {
  const Common c = derive(fix);
  std::uint8_t buf[sizeof(wire::NavSigHeader) + kNumBands * kMaxSatsInView * sizeof(wire::NavSigSig)];
  wire::NavSigHeader h{};
  h.iTOW = c.itow;
  std::size_t len = sizeof h;
  const int bands = is_dual_band(config_.generation) ? kNumBands : 1;
  for_each_in_ubx_order(fix, [&](const SatInfo& s) {
    for (int band = 0; band < bands; ++band) {
      const std::optional<SignalId> sig = signal_of(s.sat.system, band);
      if (!sig) continue;  // SBAS: L1 only
      wire::NavSigSig g{};
      g.gnssId = system_info(s.sat.system).ubx_gnss_id;
      g.svId = ubx_sv_id(s.sat);
      // BeiDou GEOs send D2 (sigId + 1; F9T log C62).
      g.sigId = static_cast<std::uint8_t>(signal_info(*sig).ubx_sig_id + (is_beidou_geo(s.sat) ? 1 : 0));
      g.freqId = s.sat.system == GnssSystem::kGlonass
                     ? static_cast<std::uint8_t>(std::clamp(s.glonass_channel, kGlonassMinChannel, kGlonassMaxChannel) + 7)
                     : 0;
      // The second band reports the satellite's state until the Fix carries its own per band.
      const bool used = s.used && c.has_fix;
      g.prRes = used ? to_int<std::int16_t>(s.residual_m * 10.0) : 0;
      g.cno = cno_u1(s);
      g.qualityInd = quality_ind(s);
      // corrSource 1 SBAS for a satellite the SBAS corrected, 4 RTCM 3 OSR when
      // the solution is differential from RTCM; ionoModel 2 SBAS grid where it
      // gave the delay, else 1 broadcast Klobuchar (GPS) on a single-frequency solution.
      const bool corrected = used && (s.sbas_corr || (fix.diff_soln && !fix.sbas_soln));
      g.corrSource = !corrected ? 0 : s.sbas_corr ? 1 : 4;
      g.ionoModel = !used ? 0 : s.sbas_iono ? 2 : 1;
      std::uint16_t flags = s.healthy ? 1 : 2;
      if (s.smoothed) flags |= 1u << 2;
      if (used) flags |= 1u << 3 | 1u << 5;  // prUsed, doUsed (real logs: 0x29 for a used signal)
      // Corrected code (b6 prCorrUsed); a carrier solution also uses and corrects the carrier (b4 crUsed, b7 crCorrUsed).
      if (corrected) flags |= 1u << 6;
      if (used && fix.carr_soln != receiver::CarrierSolution::kNone) flags |= 1u << 4 | 1u << 7;
      g.sigFlags = flags;
      std::memcpy(buf + len, &g, sizeof g);
      len += sizeof g;
      ++h.numSigs;
    }
  });
  std::memcpy(buf, &h, sizeof h);
  return append_frame(out, msg::kNavSig, {buf, len});
}

std::size_t UbxEncoder::mon_hw2(const Fix& fix, const EpochInfo& info, std::string& out) const {
  const FrontEnd f = front_end(fix, info);
  wire::MonHw2 m{};
  m.ofsI = m.ofsQ = 0;  // a balanced front end
  m.magI = m.magQ = f.mag_iq;
  m.cfgSource = kCfgSourceFlash;
  return append_message(out, msg::kMonHw2, m);
}

std::size_t UbxEncoder::mon_gnss(Generation g, SystemSet enabled, std::string& out) {
  const GnssCapabilities& cap = gnss_capabilities(g);
  wire::MonGnss m{};
  m.version = 0x01;
  m.supported = mon_gnss_bits(cap.supported);
  m.defaultGnss = mon_gnss_bits(cap.defaults);
  m.enabled = mon_gnss_bits(enabled);
  m.simultaneous = cap.max_major;
  return append_message(out, msg::kMonGnss, m);
}

}  // namespace gnssemu::protocol::ubx

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Conversions and per-epoch values every UBX encoder derives from a Fix
// (ubx_encoder.cpp, ubx_encoder_gnss.cpp): rounding and clamping to wire
// fields, and the GPS time, UTC and fix state of the epoch.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/common/constants.hpp"
#include "core/common/gnss_systems.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::protocol::ubx::detail {

using receiver::Fix;
using receiver::FixType;
using receiver::SatInfo;

inline constexpr std::int64_t kMsPerWeek = 604800000;
inline constexpr std::int64_t kMsPerDay = 86400000;

// Rounded, clamped conversions: out-of-range and NaN never reach the wire.
template <class Int>
inline Int to_int(double v) noexcept {
  if (!std::isfinite(v)) return 0;
  const double lo = static_cast<double>(std::numeric_limits<Int>::min());
  const double hi = static_cast<double>(std::numeric_limits<Int>::max());
  return static_cast<Int>(std::llround(std::clamp(v, lo, hi)));
}
/// Unsigned accuracy field: NaN or negative -> max (unknown = huge).
template <class UInt>
inline UInt to_acc(double v) noexcept {
  const double hi = static_cast<double>(std::numeric_limits<UInt>::max());
  if (!std::isfinite(v) || v < 0.0 || v >= hi) return std::numeric_limits<UInt>::max();
  return static_cast<UInt>(std::llround(v));
}
inline std::uint16_t dop_u2(double dop, bool has_fix) noexcept {
  if (!has_fix || !std::isfinite(dop) || dop < 0.0) return 9999;
  return to_int<std::uint16_t>(std::min(dop, 99.99) * 100.0);
}
inline double deg0_360(double rad) noexcept {
  if (!std::isfinite(rad)) return 0.0;
  double deg = std::fmod(rad * kRadToDeg, 360.0);
  if (deg < 0.0) deg += 360.0;
  return deg;
}

/// What every message derives from the Fix, computed once per message.
struct Common {
  bool has_time = false;
  bool has_fix = false;   ///< a position to report (a GNSS fix or dead reckoning)
  bool fix_ok = false;    ///< a GNSS fix: gnssFixOK / gpsFixOk (not set for dead reckoning only)
  bool diff_soln = false; ///< a fix with differential corrections (SBAS, RTCM): diffSoln
  std::uint8_t fix_type = 0;
  std::uint32_t itow = 0;    // ms
  std::int32_t ftow_ns = 0;  // tow - iTOW, ns
  std::int16_t week = 0;
  // UTC
  int year = 1980, month = 1, day = 6, hour = 0, minute = 0, second = 0;
  std::int32_t nano = 0;
  double lat_deg = 0.0, lon_deg = 0.0, height_m = 0.0, hmsl_m = 0.0;
  double vel_n = 0.0, vel_e = 0.0, vel_d = 0.0, speed_2d = 0.0, speed_3d = 0.0;
  double course_deg = 0.0, course_acc_deg = 180.0;
  std::uint8_t num_sv = 0;
};

inline bool has_time(const Fix& fix) noexcept { return fix.time_valid && std::isfinite(fix.t.tow_s()); }

/// A position to report (a GNSS fix or dead reckoning).
inline bool has_fix(const Fix& fix) noexcept {
  return fix.type != FixType::kNone && has_time(fix) && std::isfinite(fix.lla.lat_rad) &&
         std::isfinite(fix.lla.lon_rad) && std::isfinite(fix.lla.height_m);
}

inline Common derive(const Fix& fix, FixOverride reported = std::nullopt) noexcept {
  Common c;
  c.has_time = has_time(fix);
  c.has_fix = has_fix(fix);
  c.diff_soln = c.has_fix && fix.diff_soln;
  // iTOW is the epoch rounded to the ms; carry into the week.
  std::int64_t week = fix.t.week();
  std::int64_t ms = std::llround(fix.t.tow_s() * 1000.0);
  c.ftow_ns = to_int<std::int32_t>((fix.t.tow_s() - static_cast<double>(ms) * 1e-3) * 1e9);
  if (ms >= kMsPerWeek) {
    ms -= kMsPerWeek;
    ++week;
  }
  c.itow = static_cast<std::uint32_t>(std::max<std::int64_t>(ms, 0));
  c.week = static_cast<std::int16_t>(std::clamp<std::int64_t>(week, 0, 32767));
  if (c.has_time) {
    // UTC = GPS - leap seconds, split at the ms: sec is floored, nano carries the rest.
    // An inserted leap second is 23:59:60 (u-blox NAV-PVT/NAV-TIMEUTC sec 0..60):
    // counted from 23:59:59 with the new count.
    const int leap_s = fix.leap_seconds + (fix.in_leap_second ? 1 : 0);
    const std::int64_t gps_ms = week * kMsPerWeek + ms - static_cast<std::int64_t>(leap_s) * 1000;
    const std::int64_t day0 = time::days_from_civil(1980, 1, 6);
    std::int64_t days = gps_ms / kMsPerDay;
    std::int64_t ms_of_day = gps_ms % kMsPerDay;
    if (ms_of_day < 0) {
      ms_of_day += kMsPerDay;
      --days;
    }
    time::civil_from_days(day0 + days, c.year, c.month, c.day);
    c.hour = static_cast<int>(ms_of_day / 3600000);
    c.minute = static_cast<int>(ms_of_day / 60000 % 60);
    c.second = static_cast<int>(ms_of_day / 1000 % 60);
    if (fix.in_leap_second && c.hour == 23 && c.minute == 59 && c.second == 59) c.second = 60;
    c.nano = static_cast<std::int32_t>(ms_of_day % 1000) * 1000000 + c.ftow_ns;
  }
  c.fix_ok = reports_fix_ok(fix, reported);
  if (c.has_fix) {
    c.fix_type = fix.type == FixType::k2D ? 2 : fix.type == FixType::kDeadReckoning ? 1 : 3;
    c.lat_deg = std::clamp(fix.lla.lat_rad * kRadToDeg, -90.0, 90.0);
    c.lon_deg = std::remainder(fix.lla.lon_rad * kRadToDeg, 360.0);
    c.height_m = fix.lla.height_m;
    c.hmsl_m = fix.lla.height_m - (std::isfinite(fix.geoid_sep_m) ? fix.geoid_sep_m : 0.0);
    if (fix.vel_enu_m_s.finite()) {
      c.vel_e = fix.vel_enu_m_s.x;
      c.vel_n = fix.vel_enu_m_s.y;
      c.vel_d = -fix.vel_enu_m_s.z;
    }
    c.speed_2d = std::isfinite(fix.speed_m_s) ? std::fabs(fix.speed_m_s) : std::hypot(c.vel_n, c.vel_e);
    c.speed_3d = std::sqrt(c.speed_2d * c.speed_2d + c.vel_d * c.vel_d);
    c.course_deg = deg0_360(fix.course_rad);
    // Heading accuracy from the speed accuracy: one sigma of speed error
    // across the track turns the course by sAcc / gSpeed rad (linearised),
    // capped at 180 deg, which is what a standing or crawling receiver gets
    // (a u-blox reports a large headAcc when not moving). atan2 would stop
    // at 90 deg, an accuracy the course does not have at zero speed.
    const double sacc = std::isfinite(fix.speed_acc_m_s) ? std::max(fix.speed_acc_m_s, 0.0) : 1e9;
    const double ratio = c.speed_2d > 0.0 ? sacc / c.speed_2d : std::numeric_limits<double>::infinity();
    c.course_acc_deg = std::min(180.0, ratio * kRadToDeg);
    c.num_sv = static_cast<std::uint8_t>(std::clamp(fix.num_used, 0, 255));
  }
  if (reported) c.fix_type = static_cast<std::uint8_t>(*reported);
  return c;
}

inline std::uint8_t nav_flags(const Common& c) noexcept {
  // b0 gpsFixOk, b1 diffSoln, b2 wknSet, b3 towSet (NAV-STATUS and NAV-SOL share these).
  return static_cast<std::uint8_t>((c.fix_ok ? 0x01 : 0) | (c.diff_soln ? 0x02 : 0) | (c.has_time ? 0x0C : 0));
}

/// NAV-SAT qualityInd: 7 code+carrier locked, 4 code locked, 1 searching, 0 idle.
/// A tracked satellite at >= 30 dB-Hz is reported carrier-locked, as real M8
/// logs show for strong signals (docs/ubx.md).
inline std::uint8_t quality_ind(const SatInfo& s) noexcept {
  if (s.tracked && s.cn0_dbhz > 0.0) return s.cn0_dbhz >= 30.0 ? 7 : 4;
  if (s.above_mask && s.healthy) return 1;
  return 0;
}

inline std::uint8_t cno_u1(const SatInfo& s) noexcept {
  if (!s.tracked || !std::isfinite(s.cn0_dbhz)) return 0;
  return to_int<std::uint8_t>(std::clamp(s.cn0_dbhz, 0.0, 99.0));
}

inline std::int8_t elev_i1(const SatInfo& s) noexcept {
  return to_int<std::int8_t>(std::clamp(s.el_rad * kRadToDeg, -90.0, 90.0));
}
inline std::int16_t azim_i2(const SatInfo& s) noexcept {
  const int a = to_int<std::int16_t>(deg0_360(s.az_rad));
  return static_cast<std::int16_t>(a >= 360 ? 0 : a);
}

inline int num_sats(const Fix& fix) noexcept {
  return std::clamp(fix.num_sats, 0, static_cast<int>(fix.sats.size()));
}

/// Calls f(sat) for fix.sats[0..num_sats) in u-blox's order: by gnssId
/// (GPS, SBAS, Galileo, BeiDou, QZSS, GLONASS), then by number, as NAV-SAT
/// and NAV-SVINFO list them in real logs (pyubx2 pygpsdata-MIXED.log).
template <class F>
void for_each_in_ubx_order(const Fix& fix, F&& f) {
  const int n = num_sats(fix);
  for (std::uint8_t gnss_id = 0; gnss_id <= 7; ++gnss_id) {
    for (int i = 0; i < n; ++i) {
      const SatInfo& s = fix.sats[static_cast<std::size_t>(i)];
      if (s.sat.valid() && system_info(s.sat.system).ubx_gnss_id == gnss_id) f(s);
    }
  }
}

}  // namespace gnssemu::protocol::ubx::detail

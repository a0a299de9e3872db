// SPDX-License-Identifier: Apache-2.0
#pragma once
// GLONASS time (GLONASST) = UTC(SU) + 3 h: it has UTC's leap seconds
// (multi-gnss.md §1.2). The navigation message counts days, not weeks: N4
// is the four-year interval since 1996 (1 = 1996-1999), NT the day within
// it (1..1461, day 1 = 1 January of the leap year), tod the seconds of the
// GLONASST day (ICD GLONASS Ed. 5.1 §4.4, strings 4 and 5). UTC(SU) is taken
// as UTC (their difference is broadcast, below a microsecond: not modelled).
#include <optional>

#include "core/time/gps_time.hpp"

namespace gnssemu::time {

/// UTC(SU) + 3 h: GLONASST - UTC, s.
inline constexpr double kGlonasstMinusUtc_s = 10800.0;
/// First year of four-year interval N4 = 1.
inline constexpr int kGlonassFirstCycleYear = 1996;

struct GlonassTime {
  int n4 = 1;          ///< four-year interval, 1 = 1996..1999
  int nt = 1;          ///< day within the interval, 1..1461
  double tod_s = 0.0;  ///< seconds of the GLONASST day, [0, 86400); up to 86401 in a leap second
};

/// GLONASST of a GPS instant. leap_s: GPS - UTC (empty: the built-in table,
/// which also places an inserted leap second: UTC 23:59:60.x is 02:59:60.x
/// GLONASST, tod 10800.x, the same tod as the second after it).
GlonassTime glonass_from_gps(const GpsTime& t, std::optional<int> leap_s = std::nullopt);
/// GPS instant of a GLONASST; throws gnssemu::Error for nt outside 1..1461,
/// n4 < 1 or tod outside [0, 86401).
GpsTime gps_from_glonass(const GlonassTime& g, std::optional<int> leap_s = std::nullopt);
/// GLONASST calendar (UTC calendar + 3 h) of a GPS instant.
CalendarTime glonass_calendar(const GpsTime& t, std::optional<int> leap_s = std::nullopt);

}  // namespace gnssemu::time

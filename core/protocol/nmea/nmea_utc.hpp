// SPDX-License-Identifier: Apache-2.0
#pragma once
// UTC of an epoch as NMEA prints it: hhmmss.ss and the date, rounded to
// 0.01 s with the carry taken through seconds, minutes, hours and the date.
#include <cstdint>

#include "core/time/gps_time.hpp"

namespace gnssemu::protocol::nmea {

struct UtcStamp {
  int year = 1980;
  int month = 1;       ///< 1..12
  int day = 6;         ///< 1..31
  int hour = 0;        ///< 0..23
  int minute = 0;      ///< 0..59
  int second = 0;      ///< 0..59; 60 in an inserted leap second
  int centisecond = 0; ///< 0..99
};

/// UTC of GPS instant t rounded to the nearest 0.01 s (half up), using
/// leap_seconds = GPS - UTC, s. 23:59:59.996 becomes 00:00:00.00 of the next day.
/// in_leap_second: t is in an inserted leap second (leap_seconds = old count);
/// printed as 23:59:60.xx, and 23:59:60.996 becomes 00:00:00.00.
UtcStamp utc_stamp(const time::GpsTime& t, int leap_seconds, bool in_leap_second = false) noexcept;

}  // namespace gnssemu::protocol::nmea

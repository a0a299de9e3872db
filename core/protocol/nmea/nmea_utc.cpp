// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/nmea/nmea_utc.hpp"

#include <cmath>

#include "core/time/utc.hpp"

namespace gnssemu::protocol::nmea {

UtcStamp utc_stamp(const time::GpsTime& t, int leap_seconds, bool in_leap_second) noexcept {
  constexpr int64_t kCentisPerDay = 8640000;
  if (in_leap_second) {
    // 23:59:60.xx; counted from 23:59:59 with the new count (ITU-R TF.460-6).
    const time::CalendarTime c = time::gps_to_utc(t, leap_seconds + 1);
    const int64_t centis = std::llround((c.second - 59.0) * 100.0);
    if (c.hour == 23 && c.minute == 59 && centis >= 0 && centis < 100) {
      UtcStamp u;
      u.year = c.year;
      u.month = c.month;
      u.day = c.day;
      u.hour = 23;
      u.minute = 59;
      u.second = 60;
      u.centisecond = static_cast<int>(centis);
      return u;
    }
    leap_seconds += 1;  // rounds up to the next day's 00:00:00.00
  }
  const time::CalendarTime c = time::gps_to_utc(t, leap_seconds);
  int64_t cs = static_cast<int64_t>(c.hour) * 360000 + static_cast<int64_t>(c.minute) * 6000 +
               static_cast<int64_t>(std::llround(c.second * 100.0));
  int64_t days = time::days_from_civil(c.year, c.month, c.day);
  if (cs >= kCentisPerDay) {
    cs -= kCentisPerDay;
    ++days;
  }
  UtcStamp u;
  time::civil_from_days(days, u.year, u.month, u.day);
  u.hour = static_cast<int>(cs / 360000);
  u.minute = static_cast<int>(cs / 6000 % 60);
  u.second = static_cast<int>(cs / 100 % 60);
  u.centisecond = static_cast<int>(cs % 100);
  return u;
}

}  // namespace gnssemu::protocol::nmea

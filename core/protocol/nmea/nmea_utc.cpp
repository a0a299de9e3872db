#include "core/protocol/nmea/nmea_utc.hpp"

#include <cmath>

#include "core/time/utc.hpp"

namespace gnssemu::protocol::nmea {

UtcStamp utc_stamp(const time::GpsTime& t, int leap_seconds) noexcept {
  constexpr int64_t kCentisPerDay = 8640000;
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

// SPDX-License-Identifier: Apache-2.0
#include "core/time/unix_time.hpp"

#include <cmath>
#include <cstdint>

#include "core/common/constants.hpp"
#include "core/time/utc.hpp"

namespace gnssemu::time {

GpsTime gps_from_unix(double unix_s) {
  const double day_s = std::floor(unix_s / kSecondsPerDay);
  CalendarTime c;
  civil_from_days(static_cast<int64_t>(day_s), c.year, c.month, c.day);
  double sod = unix_s - day_s * kSecondsPerDay;
  c.hour = static_cast<int>(sod / 3600.0);
  sod -= c.hour * 3600.0;
  c.minute = static_cast<int>(sod / 60.0);
  c.second = sod - c.minute * 60.0;
  return utc_to_gps(c);
}

double unix_from_gps(const GpsTime& t) {
  CalendarTime c = gps_to_utc(t);
  if (c.second >= 60.0) c.second -= 1.0;  // 23:59:60.x reads 23:59:59.x
  return static_cast<double>(days_from_civil(c.year, c.month, c.day)) * kSecondsPerDay + c.hour * 3600.0 +
         c.minute * 60.0 + c.second;
}

}  // namespace gnssemu::time

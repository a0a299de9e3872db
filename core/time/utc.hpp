#pragma once
// UTC <-> GPS time with leap seconds (GPS - UTC, IERS Bulletin C history).
// A leap-second count from a navigation file header overrides the table.
#include <optional>

#include "core/time/gps_time.hpp"

namespace gnssemu::time {

/// GPS - UTC in whole seconds at GPS instant t, from the built-in table
/// (0 before 1981-07-01, 18 since 2017-01-01).
int leap_seconds_at(const GpsTime& t) noexcept;

/// UTC calendar time of GPS instant t. leap_s: GPS - UTC to use; when empty
/// the built-in table is used.
CalendarTime gps_to_utc(const GpsTime& t, std::optional<int> leap_s = std::nullopt);

/// GPS instant of a UTC calendar time. leap_s as for gps_to_utc.
GpsTime utc_to_gps(const CalendarTime& utc, std::optional<int> leap_s = std::nullopt);

}  // namespace gnssemu::time

// SPDX-License-Identifier: Apache-2.0
#pragma once
// UTC <-> GPS time with leap seconds (GPS - UTC, IERS Bulletin C history).
// A leap-second count from a navigation file header overrides the table.
#include <optional>

#include "core/time/gps_time.hpp"

namespace gnssemu::time {

/// GPS - UTC in whole seconds at GPS instant t, from the built-in table
/// (0 before 1981-07-01, 18 since 2017-01-01).
int leap_seconds_at(const GpsTime& t) noexcept;

/// True when GPS instant t lies in a leap second inserted per the built-in
/// table, i.e. UTC 23:59:60.x (leap_seconds_at(t) still gives the old count).
bool in_inserted_leap_second(const GpsTime& t) noexcept;

/// UTC calendar time of GPS instant t; during an inserted leap second it is
/// 23:59:60.x of the day before the step, so UTC never repeats or goes back.
/// leap_s: GPS - UTC to use (the count before the step during an inserted
/// second); when empty the built-in table decides both the count and
/// in_leap_second, otherwise in_leap_second says whether t is inserted.
CalendarTime gps_to_utc(const GpsTime& t, std::optional<int> leap_s = std::nullopt,
                        bool in_leap_second = false);

/// GPS instant of a UTC calendar time; second 60.x is the inserted leap
/// second (before the step). leap_s as for gps_to_utc.
GpsTime utc_to_gps(const CalendarTime& utc, std::optional<int> leap_s = std::nullopt);

}  // namespace gnssemu::time

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Unix time (POSIX: seconds since 1970-01-01 00:00:00 UTC, leap seconds not
// counted) <-> GPS time, through UTC and the leap-second table of utc.hpp.
// POSIX has no 23:59:60: a Linux clock repeats 23:59:59 while a leap second
// is inserted, so both directions are exact except inside that second.
#include "core/time/gps_time.hpp"

namespace gnssemu::time {

/// GPS instant of Unix time unix_s (s, any finite value; sub-second kept to
/// double precision, ~0.3 us today). The repeated 23:59:59 of an inserted
/// leap second maps to the first one.
GpsTime gps_from_unix(double unix_s);

/// Unix time (s) of GPS instant t; inside an inserted leap second (UTC
/// 23:59:60.x) it is 23:59:59.x, as a Linux clock reads then.
double unix_from_gps(const GpsTime& t);

}  // namespace gnssemu::time

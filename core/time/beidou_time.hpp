// SPDX-License-Identifier: Apache-2.0
#pragma once
// BeiDou time (BDT): BDT = GPST - 14 s (the leap seconds between 1980 and
// 2006); week 0 starts 2006-01-01 00:00:00 BDT = GPS week 1356 + 14 s
// (multi-gnss.md §1.2; RTKLIB bdt0/bdt2gpst).
#include "core/time/gps_time.hpp"
#include "core/time/week_time.hpp"

namespace gnssemu::time {

/// GPST - BDT, s.
inline constexpr double kGpsMinusBdt_s = 14.0;
/// GPS week in which BDT week 0 starts.
inline constexpr int32_t kBdtWeekOrigin = 1356;

/// BDT week and time of week of a GPS instant.
WeekTime bdt_from_gps(const GpsTime& t) noexcept;
/// GPS instant of a BDT week (continuous) and time of week, s.
GpsTime gps_from_bdt(const WeekTime& bdt);

}  // namespace gnssemu::time

// SPDX-License-Identifier: Apache-2.0
#pragma once
// Galileo system time (GST): aligned with GPST (no offset beyond the
// broadcast GGTO, nanoseconds, not modelled); weeks counted from
// 1999-08-22 00:00, i.e. GST week = GPS week - 1024 (multi-gnss.md §1.2).
// RINEX 3 writes the GPS week in Galileo records ("GAL week" = GPS week).
#include "core/time/gps_time.hpp"
#include "core/time/week_time.hpp"

namespace gnssemu::time {

/// GPS week of GST week 0.
inline constexpr int32_t kGstWeekOrigin = 1024;

/// GST week and time of week of a GPS instant.
WeekTime gst_from_gps(const GpsTime& t) noexcept;
/// GPS instant of a GST week (continuous, may be negative) and time of week, s.
GpsTime gps_from_gst(const WeekTime& gst);

}  // namespace gnssemu::time

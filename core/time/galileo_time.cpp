// SPDX-License-Identifier: Apache-2.0
#include "core/time/galileo_time.hpp"

namespace gnssemu::time {

WeekTime gst_from_gps(const GpsTime& t) noexcept { return {t.week() - kGstWeekOrigin, t.tow_s()}; }

GpsTime gps_from_gst(const WeekTime& gst) { return GpsTime(gst.week + kGstWeekOrigin, gst.tow_s); }

}  // namespace gnssemu::time

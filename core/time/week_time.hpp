// SPDX-License-Identifier: Apache-2.0
#pragma once
// A time as a system counts it: (week, seconds of week) in that system's own
// week numbering. GPS, Galileo and BeiDou each count weeks from their own
// origin (shared/reference/multi-gnss.md §1.2); GLONASS counts days instead
// (glonass_time.hpp).
#include <cstdint>

namespace gnssemu::time {

struct WeekTime {
  int32_t week = 0;    ///< continuous week of the system (not truncated)
  double tow_s = 0.0;  ///< seconds of week, [0, 604800)
};

/// Broadcast week-number widths: the modulus of the transmitted week.
inline constexpr int32_t kGpsWeekModulus = 1024;      ///< IS-GPS-200 LNAV: 10 bits
inline constexpr int32_t kGalileoWeekModulus = 4096;  ///< Galileo OS SIS ICD: 12 bits
inline constexpr int32_t kBeiDouWeekModulus = 8192;   ///< BDS-SIS-ICD-B1I: 13 bits

}  // namespace gnssemu::time

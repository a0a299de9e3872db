// SPDX-License-Identifier: Apache-2.0
#pragma once
// The satellites a run flies, for the run's own dates, from the data there
// is (docs/models.md §Orbits for any date): nav files used as they are, the
// same data moved by whole days to the run's date, or an almanac moved and
// propagated. Every mode keeps the orbits continuous for as long as the run
// lasts: past the data each satellite stays on its last orbit. Load time.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/orbit/almanac.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"

namespace gnssemu::orbit {

enum class NavMode {
  kAuto,     ///< as_is when the nav data cover the start, else relabel
  kAsIs,     ///< the files' own dates; the start must lie in their coverage
  kRelabel,  ///< the nav data moved by whole days to the start's date
  kAlmanac,  ///< an almanac moved by whole days to the start, propagated
};

/// "auto", "as_is", "relabel", "almanac".
std::string_view nav_mode_name(NavMode mode) noexcept;
std::optional<NavMode> nav_mode_from_name(std::string_view name) noexcept;

struct ConstellationRequest {
  NavMode mode = NavMode::kAuto;
  time::GpsTime start;              ///< first epoch the run needs (GPS)
  /// Past a satellite's last set keep that orbit (true) or have none
  /// (false, as RTKLIB). The almanac mode always continues.
  bool continue_after_data = true;
};

struct Constellation {
  NavMode mode = NavMode::kAsIs;        ///< the mode used (never kAuto)
  NavData nav;                          ///< ephemerides and header for the run's dates
  double shift_s = 0.0;                 ///< how far the data were moved, s (whole days; 0: as they are)
  std::string source;                   ///< file name(s) the data came from
  std::vector<TimeSpan> data_coverage;  ///< what the data cover at their own dates
  std::vector<TimeSpan> coverage;       ///< what nav covers (data_coverage moved by shift_s)
  bool continues = true;                ///< sets stay in use after coverage.back().end

  StoreOptions store_options() const noexcept { return StoreOptions{continues}; }
  /// t lies in the coverage, or past its end when sets continue.
  bool serves(const time::GpsTime& t) const noexcept;
  /// One line for logs and --check-config: mode, shift, coverage.
  std::string describe() const;
};

/// Spans as "A – B, C – D" (GPST calendar), for messages.
std::string spans_text(const std::vector<TimeSpan>& spans);

/// From RINEX nav data (several files merged). Throws gnssemu::Error when
/// there are no ephemerides (of any system), or when mode kAsIs cannot serve
/// request.start (the message names the data's coverage). kAlmanac is
/// refused here (it needs the almanac overload).
Constellation build_constellation(const NavData& data, const ConstellationRequest& request);

/// From an almanac (mode kAuto or kAlmanac), moved by whole days so that its
/// reference time lies within the day before request.start unless it is
/// already there or up to 7 days older; header: the broadcast parameters of
/// header_from (Klobuchar; may be empty). Throws gnssemu::Error for an
/// empty almanac.
Constellation build_constellation(const std::vector<AlmanacEntry>& almanac, const std::string& source,
                                  const NavData& header_from, const ConstellationRequest& request);

}  // namespace gnssemu::orbit

// SPDX-License-Identifier: Apache-2.0
#include "core/orbit/constellation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/orbit/relabel.hpp"

namespace gnssemu::orbit {

namespace {

/// An almanac this much older than the start (or up to the ephemeris window
/// newer) is current: used at its own date.
constexpr double kAlmanacCurrentAge_s = 7.0 * kSecondsPerDay;
constexpr double kAlmanacLead_s = 7200.0;

int64_t day_index(const time::GpsTime& t) noexcept {
  return static_cast<int64_t>(std::floor((t - time::GpsTime()) / kSecondsPerDay));
}

/// The GPS day holding the most toes (the earliest of equals): a daily
/// file's own day, even when it starts with sets of the evening before.
int64_t reference_day(const std::vector<Ephemeris>& ephs) {
  std::map<int64_t, int> count;
  for (const Ephemeris& e : ephs) ++count[day_index(e.toe)];
  int64_t best = count.begin()->first;
  for (const auto& [day, n] : count)
    if (n > count[best]) best = day;
  return best;
}

std::vector<TimeSpan> moved(const std::vector<TimeSpan>& spans, double shift_s) {
  std::vector<TimeSpan> out = spans;
  for (TimeSpan& s : out) s = {s.begin + shift_s, s.end + shift_s};
  return out;
}

std::string days_text(double shift_s) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%+.0f days", shift_s / kSecondsPerDay);
  return buf;
}

}  // namespace

std::string_view nav_mode_name(NavMode mode) noexcept {
  switch (mode) {
    case NavMode::kAuto: return "auto";
    case NavMode::kAsIs: return "as_is";
    case NavMode::kRelabel: return "relabel";
    case NavMode::kAlmanac: return "almanac";
  }
  return "?";
}

std::optional<NavMode> nav_mode_from_name(std::string_view name) noexcept {
  for (NavMode m : {NavMode::kAuto, NavMode::kAsIs, NavMode::kRelabel, NavMode::kAlmanac})
    if (nav_mode_name(m) == name) return m;
  return std::nullopt;
}

std::string spans_text(const std::vector<TimeSpan>& spans) {
  if (spans.empty()) return "nothing";
  std::string out;
  for (const TimeSpan& s : spans) {
    if (!out.empty()) out += ", ";
    out += time::calendar_text(s.begin) + " to " + time::calendar_text(s.end);
  }
  return out;
}

std::string Constellation::describe() const {
  const std::string after =
      coverage.empty() ? std::string()
                       : "; after " + time::calendar_text(coverage.back().end) +
                             (continues ? " every satellite stays on its last orbit (propagated)" : " no satellites");
  switch (mode) {
    case NavMode::kAsIs:
      return "nav data as they are (" + source + "): " + spans_text(coverage) + after;
    case NavMode::kRelabel:
      return "nav data moved " + days_text(shift_s) + " (" + source + ", " + spans_text(data_coverage) +
             "): " + spans_text(coverage) + after;
    case NavMode::kAlmanac:
      return "almanac moved " + days_text(shift_s) + " (" + source + ", reference time " +
             (data_coverage.empty() ? std::string("?") : time::calendar_text(data_coverage.front().begin + 7200.0)) +
             "): propagated from " + (coverage.empty() ? std::string("?") : time::calendar_text(coverage.front().begin)) +
             " on";
    case NavMode::kAuto: break;
  }
  return "?";
}

bool Constellation::serves(const time::GpsTime& t) const noexcept {
  if (continues && !coverage.empty() && coverage.back().end < t) return true;
  return std::any_of(coverage.begin(), coverage.end(), [&](const TimeSpan& s) { return s.contains(t); });
}

Constellation build_constellation(const NavData& data, const ConstellationRequest& request) {
  if (data.ephemerides.empty()) throw Error(data.source, 0, "no ephemerides in the nav data");
  if (request.mode == NavMode::kAlmanac) throw Error("nav mode almanac needs an almanac file");
  Constellation c;
  c.source = data.source;
  c.continues = request.continue_after_data;
  c.data_coverage = EphemerisStore(data.ephemerides).coverage();
  const bool covered = std::any_of(c.data_coverage.begin(), c.data_coverage.end(),
                                   [&](const TimeSpan& s) { return s.contains(request.start); });
  const NavMode mode = request.mode == NavMode::kAuto ? (covered ? NavMode::kAsIs : NavMode::kRelabel) : request.mode;
  if (mode == NavMode::kAsIs) {
    if (!covered) {
      throw Error(data.source, 0,
                  "start " + time::calendar_text(request.start) + " lies outside the nav data (" +
                      spans_text(c.data_coverage) +
                      "); nav mode \"relabel\" (or \"auto\") moves the data to that date, or give a nav file for it");
    }
    c.mode = NavMode::kAsIs;
    c.nav = data;
    c.coverage = c.data_coverage;
    return c;
  }

  // Whole days keep the time of day, so every start on one day sees the same
  // sky at the same instant; the start falls on the data's main day, or on
  // the day after when the data begin later in the day (the orbits continue).
  double shift_s = static_cast<double>(day_index(request.start) - reference_day(data.ephemerides)) * kSecondsPerDay;
  if (request.start - shift_s < c.data_coverage.front().begin) shift_s -= kSecondsPerDay;
  const time::GpsTime mapped = request.start - shift_s;
  // Only the covered block the start falls in (or after): a later block would
  // replace the continued orbits with other ones, a jump.
  std::size_t b = 0;
  while (b + 1 < c.data_coverage.size() && !(mapped < c.data_coverage[b + 1].begin)) ++b;
  const TimeSpan block = c.data_coverage[b];
  NavData kept = data;
  kept.ephemerides.clear();
  for (const Ephemeris& e : data.ephemerides)
    if (block.contains(e.toe)) kept.ephemerides.push_back(e);
  c.mode = NavMode::kRelabel;
  c.shift_s = shift_s;
  c.nav = shift_s == 0.0 ? kept : relabel(kept, shift_s);
  c.data_coverage = {block};
  c.coverage = moved(c.data_coverage, shift_s);
  return c;
}

Constellation build_constellation(const std::vector<AlmanacEntry>& almanac, const std::string& source,
                                  const NavData& header_from, const ConstellationRequest& request) {
  if (almanac.empty()) throw Error(source, 0, "no almanac entries");
  if (request.mode != NavMode::kAuto && request.mode != NavMode::kAlmanac) {
    throw Error(source, 0, "an almanac is used in nav mode \"almanac\" only");
  }
  time::GpsTime toa = almanac.front().toa;
  for (const AlmanacEntry& a : almanac)
    if (toa < a.toa) toa = a.toa;
  const double age_s = request.start - toa;
  double shift_s = 0.0;
  if (!(age_s >= -kAlmanacLead_s && age_s <= kAlmanacCurrentAge_s)) shift_s = std::floor(age_s / kSecondsPerDay) * kSecondsPerDay;

  Constellation c;
  c.mode = NavMode::kAlmanac;
  c.source = source;
  c.shift_s = shift_s;
  c.continues = true;  // an almanac is made to be propagated
  c.nav.source = source;
  c.nav.klobuchar = header_from.klobuchar;
  for (const AlmanacEntry& a : almanac) c.nav.ephemerides.push_back(to_ephemeris(relabel(a, shift_s)));
  c.data_coverage = {TimeSpan{toa - kAlmanacLead_s, toa + kAlmanacLead_s}};
  c.coverage = moved(c.data_coverage, shift_s);
  return c;
}

}  // namespace gnssemu::orbit

// SPDX-License-Identifier: Apache-2.0
#include "core/orbit/ephemeris_store.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace gnssemu::orbit {

namespace {
/// Transmission time, s from toe's week start; unknown counts as earliest.
double transmit_key(const Ephemeris& e) noexcept {
  return e.transmit_known ? e.transmit_tow_s : -std::numeric_limits<double>::infinity();
}
/// Transmission time comparable across sets (absolute, s from the GPS epoch's week 0).
double transmit_key(const Ephemeris* e) noexcept {
  return e->transmit_known ? e->toe.week() * kSecondsPerWeek + e->transmit_tow_s
                           : -std::numeric_limits<double>::infinity();
}
}  // namespace

EphemerisStore::EphemerisStore(const std::vector<Ephemeris>& ephemerides, StoreOptions options) : options_(options) {
  for (const Ephemeris& e : ephemerides) {
    if (e.prn >= 1 && e.prn <= kMaxGpsPrn) by_prn_[static_cast<std::size_t>(e.prn)].push_back(e);
  }
  for (std::size_t prn = 1; prn <= static_cast<std::size_t>(kMaxGpsPrn); ++prn) {
    auto& v = by_prn_[prn];
    // Stable: equal (toe, transmit) keep file order, so the later one is last.
    std::stable_sort(v.begin(), v.end(), [](const Ephemeris& a, const Ephemeris& b) {
      if (a.toe != b.toe) return a.toe < b.toe;
      return transmit_key(a) < transmit_key(b);
    });
    auto& u = usable_[prn];
    // Unhealthy sets stay candidates: they are the current broadcast.
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!u.empty() && v[u.back()].toe == v[i].toe) {
        u.back() = i;  // later transmitted duplicate replaces the earlier one
      } else {
        u.push_back(i);
      }
    }
  }
}

const Ephemeris* EphemerisStore::select(int prn, const time::GpsTime& t) const noexcept {
  if (prn < 1 || prn > kMaxGpsPrn) return nullptr;
  const auto& v = by_prn_[static_cast<std::size_t>(prn)];
  const auto& u = usable_[static_cast<std::size_t>(prn)];
  if (u.empty()) return nullptr;
  // First usable set with toe >= t; its predecessor is the other candidate.
  const auto it = std::lower_bound(u.begin(), u.end(), t,
                                   [&v](std::size_t i, const time::GpsTime& tt) { return v[i].toe < tt; });
  const Ephemeris* after = it != u.end() ? &v[*it] : nullptr;
  const Ephemeris* before = it != u.begin() ? &v[*(it - 1)] : nullptr;
  auto valid = [&t](const Ephemeris* e) {
    return e != nullptr && std::fabs(t - e->toe) <= validity_half_window_s(*e);
  };
  const Ephemeris* first = after;
  const Ephemeris* second = before;
  if (before != nullptr && after != nullptr) {
    const double d_before = t - before->toe, d_after = after->toe - t;
    // Equal distance: the later transmitted, then the later toe (RTKLIB).
    if (d_before < d_after || (d_before == d_after && transmit_key(before) > transmit_key(after))) {
      first = before;
      second = after;
    }
  } else if (before != nullptr) {
    first = before;
    second = nullptr;
  }
  const Ephemeris* chosen = valid(first) ? first : valid(second) ? second : nullptr;
  if (chosen == nullptr && options_.continue_after_data && after == nullptr && before != nullptr) {
    chosen = before;  // past the satellite's last set: its orbit goes on
  }
  // A satellite flagged unhealthy in its current set is not used, even if
  // an older healthy set is still within its validity window.
  return chosen != nullptr && chosen->health == 0 ? chosen : nullptr;
}

std::size_t EphemerisStore::count(int prn) const noexcept {
  if (prn < 1 || prn > kMaxGpsPrn) return 0;
  return by_prn_[static_cast<std::size_t>(prn)].size();
}

std::size_t EphemerisStore::size() const noexcept {
  std::size_t n = 0;
  for (const auto& v : by_prn_) n += v.size();
  return n;
}

time::GpsTime EphemerisStore::first_valid() const noexcept {
  bool any = false;
  time::GpsTime best;
  for (const auto& v : by_prn_) {
    for (const Ephemeris& e : v) {
      const time::GpsTime s = e.toe - validity_half_window_s(e);
      if (!any || s < best) best = s;
      any = true;
    }
  }
  return best;
}

time::GpsTime EphemerisStore::last_valid() const noexcept {
  bool any = false;
  time::GpsTime best;
  for (const auto& v : by_prn_) {
    for (const Ephemeris& e : v) {
      const time::GpsTime s = e.toe + validity_half_window_s(e);
      if (!any || s > best) best = s;
      any = true;
    }
  }
  return best;
}

}  // namespace gnssemu::orbit

namespace gnssemu::orbit {

std::vector<TimeSpan> EphemerisStore::coverage() const {
  std::vector<TimeSpan> spans;
  for (const auto& v : by_prn_) {
    for (const Ephemeris& e : v) {
      const double w = validity_half_window_s(e);
      spans.push_back({e.toe - w, e.toe + w});
    }
  }
  std::sort(spans.begin(), spans.end(), [](const TimeSpan& a, const TimeSpan& b) { return a.begin < b.begin; });
  std::vector<TimeSpan> merged;
  for (const TimeSpan& s : spans) {
    if (!merged.empty() && !(merged.back().end < s.begin)) {
      if (merged.back().end < s.end) merged.back().end = s.end;
    } else {
      merged.push_back(s);
    }
  }
  return merged;
}

}  // namespace gnssemu::orbit

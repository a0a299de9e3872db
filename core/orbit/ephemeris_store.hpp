// SPDX-License-Identifier: Apache-2.0
#pragma once
// EphemerisStore: per satellite, the ephemeris whose toe is nearest to the
// requested time and within its validity window (RTKLIB seleph rule), if it
// is healthy. Several files go into one store: their sets are simply pooled.
//
// Rules, in order:
//  - duplicates (same PRN and toe, e.g. an IODE change, a merged file
//    listing the same set twice, or two daily files both holding the
//    midnight set): the one transmitted last wins; an unknown transmission
//    time counts as earliest, equal ones fall back to input order (later
//    wins);
//  - among the remaining sets whose validity window covers t
//    (|t - toe| <= validity_half_window_s()), the nearest toe wins; at equal
//    distance the one transmitted later wins, then the later toe. This is
//    RTKLIB's tie: uniqeph() (src/rtkcmn.c) sorts the sets by transmission
//    time, then toe, and seleph() (src/ephemeris.c) keeps the last set with
//    |t - toe| <= its best so far ("if (t<=tmin)");
//  - if that set is unhealthy (health != 0) the satellite is not used, and
//    an older healthy set is not used in its place. The choice is by toe,
//    not by transmission time: a set whose toe is nearer decides even in the
//    hour before it is broadcast (RINEX files hold the whole day);
//  - with StoreOptions::continue_after_data, past the end of a satellite's
//    last set's window that set stays in use (its orbit propagated; see
//    docs/models.md), so the constellation does not vanish when the data end.
#include <array>
#include <vector>

#include "core/common/constants.hpp"
#include "core/orbit/ephemeris.hpp"

namespace gnssemu::orbit {

/// A closed span of GPS time.
struct TimeSpan {
  time::GpsTime begin;
  time::GpsTime end;
  bool contains(const time::GpsTime& t) const noexcept { return !(t < begin) && !(end < t); }
};

struct StoreOptions {
  /// After a satellite's last set, keep using it (true) or have no set (false, RTKLIB).
  bool continue_after_data = false;
};

class EphemerisStore {
public:
  EphemerisStore() = default;
  /// Copies and indexes the ephemerides (load time; allocates).
  explicit EphemerisStore(const std::vector<Ephemeris>& ephemerides, StoreOptions options = {});

  /// Ephemeris for prn (1..32) valid at t, or nullptr (none valid, or the
  /// nearest valid set is unhealthy). No allocation; safe on the per-epoch path.
  const Ephemeris* select(int prn, const time::GpsTime& t) const noexcept;

  /// Number of ephemerides stored for prn (all, healthy or not).
  std::size_t count(int prn) const noexcept;
  std::size_t size() const noexcept;
  /// Earliest toe - validity and latest toe + validity over all sets, for
  /// picking a default epoch. Both are GpsTime{} when empty.
  time::GpsTime first_valid() const noexcept;
  time::GpsTime last_valid() const noexcept;
  /// Where the sets' validity windows cover time, as disjoint spans in
  /// ascending order (gaps between files stand out). Empty when empty.
  std::vector<TimeSpan> coverage() const;
  /// The sets stay in use after the data end (StoreOptions).
  bool continues_after_data() const noexcept { return options_.continue_after_data; }

private:
  StoreOptions options_;
  std::array<std::vector<Ephemeris>, kMaxGpsPrn + 1> by_prn_;  // sorted by toe
  // Per PRN, indices into by_prn_ of the selectable sets (healthy or not):
  // one per toe (the latest transmitted one), ascending toe.
  std::array<std::vector<std::size_t>, kMaxGpsPrn + 1> usable_;
};

}  // namespace gnssemu::orbit

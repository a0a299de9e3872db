// SPDX-License-Identifier: Apache-2.0
#pragma once
// EphemerisStore: per satellite, the ephemeris whose toe is nearest to the
// requested time and within its validity window (RTKLIB seleph/selgeph/
// selseph rules), if it is healthy. Several files go into one store: their
// sets are simply pooled.
//
// Rules, in order:
//  - Galileo: only I/NAV sets (data-source bit 9, clock for (E1,E5b)) are
//    kept, what an E1 receiver decodes and RTKLIB 2.4.3 selects by default;
//    F/NAV-only sets are not used;
//  - duplicates (same satellite and toe, e.g. an IODE change, a merged file
//    listing the same set twice, or two daily files both holding the
//    midnight set): the one transmitted last wins; an unknown transmission
//    time counts as earliest, equal ones fall back to input order (later
//    wins). Galileo: the one transmitted first (RTKLIB 2.4.3 uniqeph()
//    keeps a satellite's first set of an IODnav);
//  - among the remaining sets whose validity window covers t
//    (|t - toe| <= validity_half_window_s(): GPS half the fit interval, the
//    others their system's maximum age), the nearest toe wins (GLONASS: the
//    nearest tb; Galileo: only toe < t, as RTKLIB 2.4.3); at equal
//    distance the one transmitted later wins, then the later toe. This is
//    RTKLIB's tie: uniqeph() (src/rtkcmn.c) sorts the sets by transmission
//    time, then toe, and seleph() (src/ephemeris.c) keeps the last set with
//    |t - toe| <= its best so far ("if (t<=tmin)");
//  - if that set is unhealthy the satellite is not used (GPS health != 0;
//    QZSS health other than bit 0, which RTKLIB 2.4.3 masks; Galileo E1-B
//    HS or DVS set, the E1 user's signal; BeiDou SatH1 != 0; GLONASS Bn !=
//    0; SBAS health != 0), and
//    an older healthy set is not used in its place. The choice is by toe,
//    not by transmission time: a set whose toe is nearer decides even in the
//    hour before it is broadcast (RINEX files hold the whole day);
//  - with StoreOptions::continue_after_data, past the end of a satellite's
//    last set's window that set stays in use (its orbit propagated; see
//    docs/models.md), so the constellation does not vanish when the data end.
//    GLONASS: the last set is integrated once, at construction, into sets
//    every 30 min for 8 days (the same trajectory), so that a state past
//    the data costs at most 15 min of integration, not days of it.
//    SBAS: the last set's state at the end of its window, held (no
//    velocity, acceleration or clock drift).
#include <array>
#include <cstdint>
#include <vector>

#include "core/common/sat_id.hpp"
#include "core/orbit/ephemeris.hpp"

namespace gnssemu::orbit {

/// A closed span of GPS time.
struct TimeSpan {
  time::GpsTime begin;
  time::GpsTime end;
  bool contains(const time::GpsTime& t) const noexcept { return !(t < begin) && !(end < t); }
};

/// Spacing of the continued GLONASS sets, s (the broadcast tb spacing).
inline constexpr double kGlonassContinuationStep_s = 1800.0;

struct StoreOptions {
  /// After a satellite's last set, keep using it (true) or have no set (false, RTKLIB).
  bool continue_after_data = false;
};

class EphemerisStore {
public:
  EphemerisStore() = default;
  /// Copies and indexes the ephemerides (load time; allocates).
  explicit EphemerisStore(const std::vector<Ephemeris>& ephemerides, StoreOptions options = {});

  /// Ephemeris for sat valid at t, or nullptr (none valid, an invalid sat,
  /// or the nearest valid set is unhealthy). No allocation; safe on the
  /// per-epoch path.
  const Ephemeris* select(SatId sat, const time::GpsTime& t) const noexcept;
  /// The same, and until: select(sat, t') is the same for every t' in
  /// [t, until) (a bound that may fall short; until == t: none known). A
  /// caller re-selects only when leaving that span.
  const Ephemeris* select(SatId sat, const time::GpsTime& t, time::GpsTime& until) const noexcept;

  /// Number of ephemerides stored for sat (all, healthy or not; Galileo:
  /// the I/NAV sets).
  std::size_t count(SatId sat) const noexcept;
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
  /// Hash of the contents (satellites, toe, IODs, options), fixed at
  /// construction: a store replaced by one with other sets has another
  /// fingerprint, so a cache of what it holds knows when to rebuild.
  std::uint64_t fingerprint() const noexcept { return fingerprint_; }

private:
  StoreOptions options_;
  std::uint64_t fingerprint_ = 0;
  std::array<std::vector<Ephemeris>, kNumSats> by_sat_;  // by SatId::index(), sorted by toe
  // Per satellite, indices into by_sat_ of the selectable sets (healthy or
  // not): one per toe (the latest transmitted one), ascending toe.
  std::array<std::vector<std::size_t>, kNumSats> usable_;
  // With continue_after_data: GLONASS's last set continued, tb every
  // kGlonassContinuationStep_s after it; SBAS's held.
  std::array<std::vector<Ephemeris>, kNumSats> continued_;
};

}  // namespace gnssemu::orbit

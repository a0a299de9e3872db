#pragma once
// EphemerisStore: per satellite, the ephemeris whose toe is nearest to the
// requested time and within its validity window (RTKLIB seleph rule), if it
// is healthy.
//
// Rules, in order:
//  - duplicates (same PRN and toe, e.g. an IODE change or a merged file
//    listing the same set twice): the one transmitted last wins; an unknown
//    transmission time counts as earliest, equal ones fall back to file order
//    (later wins);
//  - among the remaining sets whose validity window covers t
//    (|t - toe| <= validity_half_window_s()), the nearest toe wins; at equal
//    distance the later toe wins (the newer upload);
//  - if that set is unhealthy (health != 0) the satellite is not used, and
//    an older healthy set is not used in its place. The choice is by toe,
//    not by transmission time: a set whose toe is nearer decides even in the
//    hour before it is broadcast (RINEX files hold the whole day).
#include <array>
#include <vector>

#include "core/common/constants.hpp"
#include "core/orbit/ephemeris.hpp"

namespace gnssemu::orbit {

class EphemerisStore {
public:
  EphemerisStore() = default;
  /// Copies and indexes the ephemerides (load time; allocates).
  explicit EphemerisStore(const std::vector<Ephemeris>& ephemerides);

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

private:
  std::array<std::vector<Ephemeris>, kMaxGpsPrn + 1> by_prn_;  // sorted by toe
  // Per PRN, indices into by_prn_ of the selectable sets (healthy or not):
  // one per toe (the latest transmitted one), ascending toe.
  std::array<std::vector<std::size_t>, kMaxGpsPrn + 1> usable_;
};

}  // namespace gnssemu::orbit

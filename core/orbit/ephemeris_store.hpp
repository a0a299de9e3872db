#pragma once
// EphemerisStore: per satellite, the healthy ephemeris whose toe is nearest
// to the requested time and within its validity window (RTKLIB seleph rule).
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

  /// Ephemeris for prn (1..32) valid at t, or nullptr. Unhealthy sets are
  /// never returned. No allocation; safe on the per-epoch path.
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
};

}  // namespace gnssemu::orbit

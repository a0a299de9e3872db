#pragma once
// TruthTrack: a truth trajectory interpolated linearly to any time inside it.
#include <cstddef>
#include <vector>

#include "core/world/truth.hpp"
#include "tools/gnssemu/truth_csv.hpp"

namespace gnssemu::cli {

class TruthTrack {
public:
  /// samples: strictly increasing in time, at least one (read_truth_csv guarantees both).
  explicit TruthTrack(std::vector<TruthSample> samples);

  /// Truth at t: position linear between the neighbouring samples; velocity
  /// linear when the samples carry it, else the segment's mean velocity (zero
  /// for a single sample). valid == false outside [first, last], and inside a
  /// segment with a no-truth end (TruthSample::valid) except at a valid end itself.
  world::Truth at(const time::GpsTime& t) const noexcept;

  const time::GpsTime& first() const noexcept { return samples_.front().t; }
  const time::GpsTime& last() const noexcept { return samples_.back().t; }
  const std::vector<TruthSample>& samples() const noexcept { return samples_; }

private:
  std::vector<TruthSample> samples_;
  mutable std::size_t hint_ = 0;  // last segment; epochs usually move forward
};

}  // namespace gnssemu::cli

// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu batch --rinex-obs FILE --rinex-nav FILE`: the receiver's raw
// measurements as a RINEX 3.04 observation file and the broadcast sets it
// measured with as a RINEX 3.04 navigation file (docs/raw-output.md).
#include <memory>
#include <optional>
#include <ostream>
#include <vector>

#include "config/config.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/rinex/rinex_obs_writer.hpp"
#include "tools/gnssemu/batch/batch.hpp"

namespace gnssemu::cli {

class RinexOutput final : public BatchObserver {
public:
  /// obs, nav: either may be null. nav_data and store: the run's satellites
  /// (the store selects each epoch's set as the receiver's does).
  RinexOutput(const config::Config& config, const orbit::NavData& nav_data, orbit::StoreOptions store,
              std::ostream* obs, std::ostream* nav);
  void on_raw(const time::GpsTime& t, const receiver::RawEpoch& raw, const world::Truth& truth) override;
  void on_epoch(const time::GpsTime&, const receiver::Fix&, const world::Truth&) override {}
  /// Finish the observation file, write the navigation file.
  void finish();

private:
  const orbit::NavData& nav_data_;
  orbit::EphemerisStore store_;
  std::ostream* nav_;
  rinex::ObsHeaderInfo info_;
  std::optional<rinex::ObsWriter> obs_;
  std::vector<const orbit::Ephemeris*> used_;  ///< every set a measurement was made with, first use first
};

}  // namespace gnssemu::cli

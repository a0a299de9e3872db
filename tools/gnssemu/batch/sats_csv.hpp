// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu batch --sats FILE`: per epoch and satellite in view (above the
// horizon with a healthy ephemeris) `gps_week,tow_s,sat,prn,az_deg,el_deg,
// cn0_dbhz,tracked,used` (docs/cli.md). cn0_dbhz 0 when not tracked;
// tracked, used 1/0.
#include <ostream>

#include "tools/gnssemu/batch/batch.hpp"

namespace gnssemu::cli {

inline constexpr const char* kSatsCsvHeader = "gps_week,tow_s,sat,prn,az_deg,el_deg,cn0_dbhz,tracked,used";

class SatsCsvWriter final : public BatchObserver {
public:
  /// Writes the header line to out at once.
  explicit SatsCsvWriter(std::ostream& out);
  void on_epoch(const time::GpsTime& t, const receiver::Fix& fix, const world::Truth& truth) override;

private:
  std::ostream& out_;
  std::string row_;
};

}  // namespace gnssemu::cli

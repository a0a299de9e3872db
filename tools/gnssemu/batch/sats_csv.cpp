// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/batch/sats_csv.hpp"

#include <fmt/format.h>

#include <iterator>

#include "core/common/constants.hpp"

namespace gnssemu::cli {

SatsCsvWriter::SatsCsvWriter(std::ostream& out) : out_(out) { out_ << kSatsCsvHeader << '\n'; }

void SatsCsvWriter::on_epoch(const time::GpsTime& t, const receiver::Fix& fix, const world::Truth& /*truth*/) {
  row_.clear();
  for (int i = 0; i < fix.num_sats; ++i) {
    const receiver::SatInfo& s = fix.sats[i];
    fmt::format_to(std::back_inserter(row_), "{},{:.3f},{},{},{:.2f},{:.2f},{:.1f},{},{}\n", t.week(), t.tow_s(),
                   sat_name(s.sat).data(), s.sat.prn(),
                   s.az_rad * kRadToDeg, s.el_rad * kRadToDeg, s.tracked ? s.cn0_dbhz : 0.0, s.tracked ? 1 : 0,
                   s.used ? 1 : 0);
  }
  out_.write(row_.data(), static_cast<std::streamsize>(row_.size()));
}

}  // namespace gnssemu::cli

// SPDX-License-Identifier: Apache-2.0
#pragma once
// The fleet overview (docs/status.md §"/api/overview"): one short row per
// receiver (fix, satellites, error, truth, active faults, port totals) so the
// status page can show a fleet of 1000 receivers in one table without
// fetching each receiver's full status. Rows are a view of the producers'
// current state; serialising them does no geometry and no allocation once
// the output string has capacity.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>

#include "core/receiver/fix.hpp"

namespace gnssemu::daemon {

class StatusProducer;
struct FaultStatus;

/// One receiver's summary as StatusProducer::overview() gives it.
struct OverviewRow {
  uint64_t epochs = 0;
  receiver::FixType fix_type = receiver::FixType::kNone;
  receiver::CarrierSolution carrier = receiver::CarrierSolution::kNone;
  bool diff = false;  ///< differential corrections in the solution (SBAS or RTCM)
  int num_used = 0, num_tracked = 0, num_visible = 0;
  double h_err_m = std::numeric_limits<double>::quiet_NaN();  ///< |fix - truth| horizontal, m; NaN: no fix or no truth
  double h_acc_m = std::numeric_limits<double>::quiet_NaN();  ///< reported; NaN: no fix
  double cep95_m = std::numeric_limits<double>::quiet_NaN();  ///< of the kept history; NaN: no sample
  bool truth_valid = false;
  std::string_view truth_source = "none";  ///< simulator, demo, none (static text)
  bool truth_fresh = false;
  double truth_age_s = std::numeric_limits<double>::quiet_NaN();  ///< since its vehicle's last packet; NaN: none
  std::span<const FaultStatus> faults;     ///< every fault the receiver runs (active and scheduled)
  uint64_t bytes_written = 0;   ///< summed over its ports
  uint64_t epochs_dropped = 0;  ///< summed over its ports
  uint64_t messages_dropped = 0;
  std::size_t ports = 0;
};

/// A receiver of the fleet, as the daemon lists them.
struct OverviewEntry {
  std::string_view vehicle;
  std::string_view receiver;
  const StatusProducer* status = nullptr;  ///< required
};

inline constexpr std::size_t kOverviewMaxRows = 1000;     ///< default and largest ?limit=
inline constexpr std::size_t kOverviewMaxFaultIds = 8;    ///< active fault ids listed per row

/// The column /api/overview orders the whole fleet by before paging
/// (?sort=): the status page's column keys.
enum class OverviewSort { kConfig, kName, kFix, kSats, kHErr, kHAcc, kTruth, kFaults, kBytes, kDropped };

/// /api/overview's query: the fleet ordered by sort (ascending unless
/// descending; ties and kConfig in the configuration's order), then limit
/// rows from offset.
struct OverviewQuery {
  std::size_t offset = 0;
  std::size_t limit = kOverviewMaxRows;
  OverviewSort sort = OverviewSort::kConfig;
  bool descending = false;
};

/// Parse "limit=N&offset=M&sort=KEY&order=asc|desc" (each optional; KEY one
/// of name, fix, sats, herr, hacc, truth, faults, bytes, dropped). Returns ""
/// and fills q, or the reason the query is refused (an unknown or repeated
/// key, a value that is not a whole number, limit outside [1,
/// kOverviewMaxRows], an unknown sort key or order).
std::string parse_overview_query(std::string_view query, OverviewQuery& q);

/// Order entries by q.sort (stable: ties keep their order). A missing value
/// (no fix: no error, no hAcc) sorts last in either order. name is natural
/// order of vehicle then receiver ("v9" before "v10"). Allocates (a
/// request's work, not an epoch's).
void sort_overview(std::span<OverviewEntry> entries, const OverviewQuery& q);

/// Append {"version":1,"total":N,"offset":..,"limit":..,"rows":[...]} for
/// entries [offset, offset + limit), in the order given.
void write_overview(std::string& out, std::span<const OverviewEntry> entries, const OverviewQuery& q) noexcept;

}  // namespace gnssemu::daemon

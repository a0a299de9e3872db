// SPDX-License-Identifier: Apache-2.0
#pragma once
// The one-line summary of a task (docs/sweep.md §Summary): fix availability,
// error percentiles, the largest error while a fix was reported, the
// receiver's hAcc/vAcc against its true error, fix loss and recovery around
// each fault, and how soon the receiver flagged spoofing, jamming and
// faulty satellites. Computed from the epochs batch sees, as its --errors
// rows and the UBX monitors would report them.
#include <limits>
#include <string>
#include <vector>

#include "core/faults/fault_event.hpp"
#include "tools/gnssemu/batch/batch.hpp"

namespace gnssemu::cli::sweep {

struct TaskSummary {
  int epochs = 0;
  double avail_3d = 0.0;       ///< fraction of epochs with a 3D fix [0, 1]
  double ttff_s = kNaN;        ///< first 2D/3D fix after the first epoch, s
  double h50_m = kNaN, h95_m = kNaN, h99_m = kNaN;  ///< horizontal error percentiles (nearest rank) over 2D/3D fixes
  double v50_m = kNaN, v95_m = kNaN, v99_m = kNaN;  ///< |vertical error| percentiles
  double h_max_fix_m = kNaN;   ///< largest horizontal error of any epoch reporting a position (dead reckoning too)
  double v_max_fix_m = kNaN;   ///< same, |vertical|
  double h_over_k_hacc = kNaN; ///< fraction of 2D/3D fixes with horizontal error > k * hAcc
  double v_over_k_vacc = kNaN; ///< fraction of 3D fixes with |vertical error| > k * vAcc
  double fix_lost_s = kNaN;    ///< soonest loss of the 2D/3D fix after a fault starts, s
  double refix_s = kNaN;       ///< slowest return of a 3D fix after a fault ends, s (NaN: never, or no fault ends)
  double spoof_detect_s = kNaN;///< first spoofer start to spoofDetState >= 2 (NAV-STATUS), s
  double jam_detect_s = kNaN;  ///< first jammer start to jammingState >= warning (MON-HW, monitor enabled), s
  int raim_excl_epochs = 0;    ///< epochs with a satellite excluded by fault detection
  double raim_detect_s = kNaN; ///< first satellite fault start to the first exclusion, s

  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
};

/// Watches a batch run and fills a TaskSummary.
class SummaryObserver final : public BatchObserver {
public:
  /// events: the task's scenario (start times from the first epoch; port
  /// events ignored); hacc_k: k of the consistency test (> 0).
  SummaryObserver(const std::vector<faults::FaultEvent>& events, double hacc_k);
  void on_epoch(const time::GpsTime& t, const receiver::Fix& fix, const world::Truth& truth) override;
  /// The summary of every epoch seen so far.
  TaskSummary summary() const;

private:
  struct EventTimes {
    faults::FaultType type;
    double start_s, end_s;
    double lost_s = TaskSummary::kNaN, refix_s = TaskSummary::kNaN;
  };
  std::vector<EventTimes> events_;
  double k_;
  time::GpsTime t0_;
  TaskSummary s_;
  int fixes_3d_ = 0, over_h_ = 0, over_v_ = 0, fixes_ = 0;
  std::vector<double> h_, v_;
  double first_fix_s_ = TaskSummary::kNaN;
  bool spoof_found_ = false, jam_found_ = false, raim_found_ = false;
};

/// summary.csv: header and the one row (NaN as an empty cell; fixed decimals,
/// so equal runs give equal bytes).
std::string summary_csv_text(const TaskSummary& s, int task_id, const std::string& plan_hash);
/// The metric columns of summary.csv after plan_hash and task_id, in order.
const std::vector<std::string>& summary_columns();

}  // namespace gnssemu::cli::sweep

// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/collect/task_summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/geo/geodesy.hpp"
#include "core/protocol/ubx/device/ubx_front_end.hpp"
#include "core/statistics/statistics.hpp"
#include "tools/gnssemu/sweep/collect/csv_row.hpp"

namespace gnssemu::cli::sweep {

namespace {

std::string cell(double v, int decimals) { return std::isfinite(v) ? fmt::format("{:.{}f}", v, decimals) : std::string(); }

double first_start(const std::vector<faults::FaultEvent>& events, faults::FaultType type) {
  double s = TaskSummary::kNaN;
  for (const faults::FaultEvent& e : events) {
    if (e.type == type && !(e.start_s >= s)) s = e.start_s;
  }
  return s;
}

}  // namespace

SummaryObserver::SummaryObserver(const std::vector<faults::FaultEvent>& events, double hacc_k) : k_(hacc_k) {
  for (const faults::FaultEvent& e : events) {
    if (e.type != faults::FaultType::kPort) events_.push_back({e.type, e.start_s, e.end_s()});
  }
  s_.spoof_detect_s = first_start(events, faults::FaultType::kSpoofer);
  s_.jam_detect_s = first_start(events, faults::FaultType::kJammer);
  s_.raim_detect_s = first_start(events, faults::FaultType::kSatellite);
}

void SummaryObserver::on_epoch(const time::GpsTime& t, const receiver::Fix& fix, const world::Truth& truth) {
  if (s_.epochs == 0) t0_ = t;
  ++s_.epochs;
  const double el = t - t0_;
  const bool has_fix = fix.type != receiver::FixType::kNone && truth.valid;
  const bool gnss = has_fix && receiver::is_gnss_fix(fix.type);
  const bool fix3d = gnss && fix.type == receiver::FixType::k3D;
  if (gnss && std::isnan(first_fix_s_)) first_fix_s_ = el;
  if (fix3d) ++fixes_3d_;
  if (has_fix) {
    const Lla lla = geo::lla_from_ecef(truth.pos_m);
    const Enu d = geo::ecef_to_enu_vector(fix.pos_m - truth.pos_m, lla.lat_rad, lla.lon_rad);
    const double h = std::hypot(d.x, d.y), v = std::fabs(d.z);
    if (!(h <= s_.h_max_fix_m)) s_.h_max_fix_m = h;
    if (!(v <= s_.v_max_fix_m)) s_.v_max_fix_m = v;
    if (gnss) {
      ++fixes_;
      h_.push_back(h);
      v_.push_back(v);
      over_h_ += h > k_ * fix.h_acc_m;
      if (fix3d) over_v_ += v > k_ * fix.v_acc_m;
    }
  }
  for (EventTimes& e : events_) {
    if (el >= e.start_s && std::isnan(e.lost_s) && !gnss) e.lost_s = el - e.start_s;
    if (el >= e.end_s && std::isnan(e.refix_s) && fix3d) e.refix_s = el - e.end_s;
  }
  // Detection: relative to the first event of the kind; NaN start = no such event.
  if (std::isfinite(s_.spoof_detect_s) && !spoof_found_ && el >= s_.spoof_detect_s &&
      protocol::ubx::spoof_det_state(fix) >= 2) {
    s_.spoof_detect_s = el - s_.spoof_detect_s;
    spoof_found_ = true;
  }
  if (std::isfinite(s_.jam_detect_s) && !jam_found_ && el >= s_.jam_detect_s) {
    // The monitor as a host that enabled it (CFG-ITFM) would see it.
    protocol::ubx::EpochInfo info;
    info.itfm.enabled = true;
    info.ttff_ms = std::isnan(first_fix_s_) ? 0u : static_cast<std::uint32_t>(first_fix_s_ * 1000.0) + 1u;
    if (protocol::ubx::front_end(fix, info).jamming_state >= protocol::ubx::JammingState::kWarning) {
      s_.jam_detect_s = el - s_.jam_detect_s;
      jam_found_ = true;
    }
  }
  bool excluded = false;
  for (int i = 0; i < fix.num_sats; ++i) excluded = excluded || fix.sats[i].excluded;
  s_.raim_excl_epochs += excluded;
  if (excluded && std::isfinite(s_.raim_detect_s) && !raim_found_ && el >= s_.raim_detect_s) {
    s_.raim_detect_s = el - s_.raim_detect_s;
    raim_found_ = true;
  }
}

TaskSummary SummaryObserver::summary() const {
  TaskSummary s = s_;
  if (!spoof_found_) s.spoof_detect_s = TaskSummary::kNaN;
  if (!jam_found_) s.jam_detect_s = TaskSummary::kNaN;
  if (!raim_found_) s.raim_detect_s = TaskSummary::kNaN;
  s.ttff_s = first_fix_s_;
  s.avail_3d = s.epochs > 0 ? static_cast<double>(fixes_3d_) / s.epochs : 0.0;
  if (!h_.empty()) {
    std::vector<double> h = h_, v = v_;
    std::sort(h.begin(), h.end());
    std::sort(v.begin(), v.end());
    s.h50_m = statistics::percentile_nearest_rank_sorted(h, 0.50);
    s.h95_m = statistics::percentile_nearest_rank_sorted(h, 0.95);
    s.h99_m = statistics::percentile_nearest_rank_sorted(h, 0.99);
    s.v50_m = statistics::percentile_nearest_rank_sorted(v, 0.50);
    s.v95_m = statistics::percentile_nearest_rank_sorted(v, 0.95);
    s.v99_m = statistics::percentile_nearest_rank_sorted(v, 0.99);
    s.h_over_k_hacc = static_cast<double>(over_h_) / fixes_;
  }
  if (fixes_3d_ > 0) s.v_over_k_vacc = static_cast<double>(over_v_) / fixes_3d_;
  bool ended = false, never = false;
  for (const EventTimes& e : events_) {
    if (std::isfinite(e.lost_s) && !(e.lost_s >= s.fix_lost_s)) s.fix_lost_s = e.lost_s;
    if (!std::isfinite(e.end_s)) continue;
    ended = true;
    never = never || std::isnan(e.refix_s);
    if (std::isfinite(e.refix_s) && !(e.refix_s <= s.refix_s)) s.refix_s = e.refix_s;
  }
  if (!ended || never) s.refix_s = TaskSummary::kNaN;
  return s;
}

const std::vector<std::string>& summary_columns() {
  static const std::vector<std::string> kColumns{
      "epochs",      "avail_3d",      "ttff_s",        "h50_m",      "h95_m",   "h99_m",          "v50_m",
      "v95_m",       "v99_m",         "h_max_fix_m",   "v_max_fix_m", "h_over_k_hacc", "v_over_k_vacc", "fix_lost_s",
      "refix_s",     "spoof_detect_s", "jam_detect_s", "raim_excl_epochs", "raim_detect_s"};
  return kColumns;
}

std::string summary_csv_text(const TaskSummary& s, int task_id, const std::string& plan_hash) {
  std::vector<std::string> head{"plan_hash", "task_id"};
  head.insert(head.end(), summary_columns().begin(), summary_columns().end());
  const std::vector<std::string> row{plan_hash,
                                     std::to_string(task_id),
                                     std::to_string(s.epochs),
                                     cell(s.avail_3d, 4),
                                     cell(s.ttff_s, 2),
                                     cell(s.h50_m, 3),
                                     cell(s.h95_m, 3),
                                     cell(s.h99_m, 3),
                                     cell(s.v50_m, 3),
                                     cell(s.v95_m, 3),
                                     cell(s.v99_m, 3),
                                     cell(s.h_max_fix_m, 3),
                                     cell(s.v_max_fix_m, 3),
                                     cell(s.h_over_k_hacc, 4),
                                     cell(s.v_over_k_vacc, 4),
                                     cell(s.fix_lost_s, 2),
                                     cell(s.refix_s, 2),
                                     cell(s.spoof_detect_s, 2),
                                     cell(s.jam_detect_s, 2),
                                     std::to_string(s.raim_excl_epochs),
                                     cell(s.raim_detect_s, 2)};
  return csv_row(head) + csv_row(row);
}

}  // namespace gnssemu::cli::sweep

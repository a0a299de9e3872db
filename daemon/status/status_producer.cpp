// SPDX-License-Identifier: Apache-2.0
#include "daemon/status/status_producer.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/statistics/statistics.hpp"
#include "daemon/status/json_writer.hpp"
#include "daemon/status/sat_state.hpp"

namespace gnssemu::daemon {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();


}  // namespace

void StatusProducer::RateMeter::add(double t_s, double total) noexcept {
  t_s_[next_] = t_s;
  v_[next_] = total;
  next_ = (next_ + 1) % kSamples;
  n_ = std::min(n_ + 1, kSamples);
}

double StatusProducer::RateMeter::rate() const noexcept {
  if (n_ < 2) return kNaN;
  const std::size_t newest = (next_ + kSamples - 1) % kSamples;
  std::size_t oldest = newest;
  for (std::size_t k = 1; k < n_; ++k) {
    const std::size_t i = (newest + kSamples - k) % kSamples;
    if (t_s_[newest] - t_s_[i] > kWindowS) break;
    oldest = i;
  }
  const double dt = t_s_[newest] - t_s_[oldest];
  return dt > 0.0 ? (v_[newest] - v_[oldest]) / dt : kNaN;
}

StatusProducer::StatusProducer(StatusSettings settings) : settings_(std::move(settings)) {}

void StatusProducer::set_ports(std::vector<PortInfo> ports) {
  ports_.clear();
  ports_.reserve(ports.size());
  for (PortInfo& p : ports) ports_.push_back(PortSlot{std::move(p), {}, {}});
}

void StatusProducer::set_port_counters(std::size_t i, const PortCounters& c) noexcept {
  if (i >= ports_.size()) return;
  ports_[i].counters = c;
  ports_[i].bytes.add(run_s_, static_cast<double>(c.bytes_offered));
}

void StatusProducer::set_truth(const TruthCounters& c) noexcept {
  truth_counters_ = c;
  truth_rate_.add(run_s_, static_cast<double>(c.packets_accepted));
}

void StatusProducer::set_faults(std::span<const FaultStatus> faults) { faults_.assign(faults.begin(), faults.end()); }

void StatusProducer::on_epoch(const EpochStatus& e) noexcept {
  if (e.fix == nullptr || e.truth == nullptr) return;
  fix_ = *e.fix;
  truth_ = *e.truth;
  run_s_ = e.run_s;
  uptime_s_ = e.uptime_s;
  ttff_s_ = e.ttff_s;
  ++epochs_;
  error_valid_ = fix_.type != receiver::FixType::kNone && truth_.valid;
  HistoryPoint h;
  h.t_s = run_s_;
  h.fix_type = static_cast<int>(fix_.type);
  h.num_used = fix_.num_used;
  h.num_tracked = fix_.num_tracked;
  h.e_m = h.n_m = h.u_m = kNaN;
  h.h_acc_m = h.v_acc_m = kNaN;
  if (fix_.type != receiver::FixType::kNone) {
    h.h_acc_m = fix_.h_acc_m;
    h.v_acc_m = fix_.v_acc_m;
  }
  if (error_valid_) {
    const Lla at = geo::lla_from_ecef(truth_.pos_m);
    const Enu d = geo::ecef_to_enu_vector(fix_.pos_m - truth_.pos_m, at.lat_rad, at.lon_rad);
    e_m_ = d.x;
    n_m_ = d.y;
    u_m_ = d.z;
    h.e_m = d.x;
    h.n_m = d.y;
    h.u_m = d.z;
  }
  history_[history_next_] = h;
  history_next_ = (history_next_ + 1) % kHistory;
  history_n_ = std::min(history_n_ + 1, kHistory);
  update_error_stats();
}

void StatusProducer::update_error_stats() noexcept {
  std::size_t n = 0;
  for (std::size_t i = 0; i < history_n_; ++i) {
    const HistoryPoint& p = history_[i];
    // Dead-reckoning epochs are plotted but are not GNSS fixes (batch's rule).
    if (std::isfinite(p.e_m) && receiver::is_gnss_fix(static_cast<receiver::FixType>(p.fix_type))) {
      scratch_[n++] = std::hypot(p.e_m, p.n_m);
    }
  }
  error_samples_ = static_cast<int>(n);
  const std::span<double> h(scratch_.data(), n);
  std::sort(h.begin(), h.end());
  cep50_m_ = statistics::percentile_nearest_rank_sorted(h, 0.5);
  cep95_m_ = statistics::percentile_nearest_rank_sorted(h, 0.95);
}

OverviewRow StatusProducer::overview() const noexcept {
  OverviewRow r;
  const bool has_fix = fix_.type != receiver::FixType::kNone;
  r.epochs = epochs_;
  r.fix_type = fix_.type;
  r.carrier = has_fix ? fix_.carr_soln : receiver::CarrierSolution::kNone;
  r.diff = has_fix && fix_.diff_soln;
  r.num_used = fix_.num_used;
  r.num_tracked = fix_.num_tracked;
  r.num_visible = fix_.num_visible;
  r.h_err_m = error_valid_ ? std::hypot(e_m_, n_m_) : kNaN;
  r.h_acc_m = has_fix ? fix_.h_acc_m : kNaN;
  r.cep95_m = cep95_m_;
  r.truth_valid = truth_.valid;
  r.truth_source = truth_counters_.simulator ? "simulator" : truth_counters_.demo ? "demo" : "none";
  r.truth_fresh = truth_counters_.fresh;
  r.truth_age_s = truth_counters_.simulator ? truth_counters_.age_s : kNaN;
  r.faults = faults_;
  r.ports = ports_.size();
  for (const PortSlot& p : ports_) {
    r.bytes_written += p.counters.bytes_written;
    r.epochs_dropped += p.counters.epochs_dropped;
    r.messages_dropped += p.counters.messages_dropped;
  }
  return r;
}

void StatusProducer::write_history(JsonWriter& w, std::size_t history_max) const noexcept {
  const std::size_t n = std::min(history_max, history_n_);
  const std::size_t first = (history_next_ + kHistory - n) % kHistory;
  auto column = [&](std::string_view name, auto get, int decimals) {
    w.key(name);
    w.begin_array();
    for (std::size_t k = 0; k < n; ++k) w.number(get(history_[(first + k) % kHistory]), decimals);
    w.end_array();
  };
  w.key("history");
  w.begin_object();
  column("t_s", [](const HistoryPoint& p) { return p.t_s; }, 3);
  column("e_m", [](const HistoryPoint& p) { return p.e_m; }, 3);
  column("n_m", [](const HistoryPoint& p) { return p.n_m; }, 3);
  column("u_m", [](const HistoryPoint& p) { return p.u_m; }, 3);
  column("h_acc_m", [](const HistoryPoint& p) { return p.h_acc_m; }, 3);
  column("v_acc_m", [](const HistoryPoint& p) { return p.v_acc_m; }, 3);
  column("fix_type", [](const HistoryPoint& p) { return static_cast<double>(p.fix_type); }, 0);
  column("num_used", [](const HistoryPoint& p) { return static_cast<double>(p.num_used); }, 0);
  column("num_tracked", [](const HistoryPoint& p) { return static_cast<double>(p.num_tracked); }, 0);
  w.end_object();
}

void StatusProducer::write_json(std::string& out, std::size_t history_max) const noexcept {
  JsonWriter w(out);
  const bool has_fix = fix_.type != receiver::FixType::kNone;
  w.begin_object();
  w.field_int("version", 1);

  w.key("epoch");
  w.begin_object();
  w.field_int("count", static_cast<int64_t>(epochs_));
  w.field("run_s", run_s_, 3);
  w.field_int("gps_week", fix_.t.week());
  w.field("tow_s", fix_.t.tow_s(), 3);
  w.key("utc");
  try {
    const time::CalendarTime c = (fix_.t - static_cast<double>(fix_.leap_seconds)).to_calendar();
    std::array<char, 40> buf{};
    const auto r = fmt::format_to_n(buf.data(), buf.size(), "{:04d}-{:02d}-{:02d}T{:02d}:{:02d}:{:06.3f}Z", c.year,
                                    c.month, c.day, c.hour, c.minute, c.second);
    w.string(std::string_view(buf.data(), std::min(r.size, buf.size())));
  } catch (...) {
    w.null();
  }
  w.field("rate_hz", settings_.rate_hz, 3);
  w.field_string("time_mode", settings_.time_mode);
  w.field("uptime_s", uptime_s_, 3);
  w.end_object();

  w.key("fix");
  w.begin_object();
  w.field_int("type", static_cast<int>(fix_.type));
  w.field_string("type_name", receiver::fix_type_name(fix_.type));
  w.field_bool("time_valid", fix_.time_valid);
  auto fix_number = [&](std::string_view name, double v, int decimals) { w.field(name, has_fix ? v : kNaN, decimals); };
  fix_number("lat_deg", fix_.lla.lat_rad * kRadToDeg, 8);
  fix_number("lon_deg", fix_.lla.lon_rad * kRadToDeg, 8);
  fix_number("height_m", fix_.lla.height_m, 3);
  fix_number("msl_m", fix_.lla.height_m - fix_.geoid_sep_m, 3);
  fix_number("speed_m_s", fix_.speed_m_s, 3);
  fix_number("course_deg", fix_.course_rad * kRadToDeg, 2);
  fix_number("h_acc_m", fix_.h_acc_m, 3);
  fix_number("v_acc_m", fix_.v_acc_m, 3);
  w.field_int("num_used", fix_.num_used);
  w.field_int("num_tracked", fix_.num_tracked);
  w.field_int("num_visible", fix_.num_visible);
  w.field("ttff_s", ttff_s_ > 0.0 ? ttff_s_ : kNaN, 3);
  w.key("dop");
  w.begin_object();
  fix_number("gdop", fix_.dop.gdop, 2);
  fix_number("pdop", fix_.dop.pdop, 2);
  fix_number("hdop", fix_.dop.hdop, 2);
  fix_number("vdop", fix_.dop.vdop, 2);
  fix_number("tdop", fix_.dop.tdop, 2);
  w.end_object();
  w.end_object();

  w.key("truth");
  w.begin_object();
  w.field_bool("valid", truth_.valid);
  w.field_string("source", truth_counters_.simulator ? "simulator" : truth_counters_.demo ? "demo" : "none");
  w.field_bool("fresh", truth_counters_.fresh);
  w.field("age_s", truth_counters_.simulator ? truth_counters_.age_s : kNaN, 3);
  const Lla tl = geo::lla_from_ecef(truth_.pos_m);
  w.field("lat_deg", truth_.valid ? tl.lat_rad * kRadToDeg : kNaN, 8);
  w.field("lon_deg", truth_.valid ? tl.lon_rad * kRadToDeg : kNaN, 8);
  w.field("height_m", truth_.valid ? tl.height_m : kNaN, 3);
  w.field_int("packets", static_cast<int64_t>(truth_counters_.packets_accepted));
  w.field("rate_hz", truth_rate_.rate(), 2);
  uint64_t dropped = 0;
  for (uint64_t d : truth_counters_.dropped) dropped += d;
  w.field_int("dropped", static_cast<int64_t>(dropped));
  w.key("drops");
  w.begin_object();
  for (std::size_t r = 0; r < kDropReasonCount; ++r) {
    if (truth_counters_.dropped[r] == 0) continue;
    w.field_int(drop_reason_name(static_cast<DropReason>(r)), static_cast<int64_t>(truth_counters_.dropped[r]));
  }
  w.end_object();
  w.end_object();

  w.key("corrections");
  w.begin_object();
  w.field_int("messages", static_cast<int64_t>(corrections_.messages));
  w.field_int("used", static_cast<int64_t>(corrections_.used));
  w.field_int("crc_failed", static_cast<int64_t>(corrections_.crc_failed));
  w.field_int("ignored", static_cast<int64_t>(corrections_.ignored));
  w.field_int("lost", static_cast<int64_t>(corrections_.lost));
  w.field_int("epochs", static_cast<int64_t>(corrections_.epochs));
  w.field_int("station_id", corrections_.station_id);
  w.field("age_s", corrections_.age_s, 2);
  w.field("baseline_m", corrections_.baseline_m, 3);
  w.field_int("baseline_big", static_cast<int64_t>(corrections_.baseline_big));
  w.field_int("long_baseline", static_cast<int64_t>(corrections_.long_baseline));
  w.end_object();

  w.key("error");
  w.begin_object();
  w.field_bool("valid", error_valid_);
  w.field("e_m", error_valid_ ? e_m_ : kNaN, 3);
  w.field("n_m", error_valid_ ? n_m_ : kNaN, 3);
  w.field("u_m", error_valid_ ? u_m_ : kNaN, 3);
  w.field("h_m", error_valid_ ? std::hypot(e_m_, n_m_) : kNaN, 3);
  w.field("v_m", error_valid_ ? std::fabs(u_m_) : kNaN, 3);
  w.field("cep50_m", cep50_m_, 3);
  w.field("cep95_m", cep95_m_, 3);
  w.field_int("samples", error_samples_);
  w.end_object();

  w.key("settings");
  w.begin_object();
  w.field("elevation_mask_deg", settings_.elevation_mask_deg, 2);
  w.field("acquire_dbhz", settings_.acquire_dbhz, 1);
  w.field("lose_dbhz", settings_.lose_dbhz, 1);
  w.end_object();

  w.key("satellites");
  w.begin_array();
  for (int i = 0; i < fix_.num_sats; ++i) {
    const receiver::SatInfo& s = fix_.sats[i];
    w.begin_object();
    w.field_string("sat", std::string_view(sat_name(s.sat).data(), 3));
    w.field_int("prn", s.sat.prn());
    w.field("az_deg", s.az_rad * kRadToDeg, 1);
    w.field("el_deg", s.el_rad * kRadToDeg, 1);
    w.field("cn0_dbhz", s.tracked ? s.cn0_dbhz : 0.0, 1);
    w.field_string("state", sat_state_name(sat_state(s)));
    w.field_bool("used", s.used);
    w.field_bool("tracked", s.tracked);
    w.field_bool("excluded", s.excluded);
    w.field_bool("nlos", s.nlos);
    w.field_bool("blocked", s.blocked);
    w.field("residual_m", s.used ? s.residual_m : kNaN, 2);
    w.field("nlos_delay_m", s.nlos ? s.nlos_delay_m : kNaN, 2);
    w.end_object();
  }
  w.end_array();

  w.key("ports");
  w.begin_array();
  for (const PortSlot& p : ports_) {
    const PortCounters& c = p.counters;
    const double bytes_per_s = p.bytes.rate();
    const double line_bytes_per_s = c.baud_bps / 10.0;  // 8N1
    w.begin_object();
    w.field_string("name", p.info.name);
    w.field_string("type", p.info.type);
    w.field_string("where", p.info.where);
    w.field_string("protocols", c.protocols);
    w.field_int("baud", c.baud_bps);
    w.field_int("bytes_offered", static_cast<int64_t>(c.bytes_offered));
    w.field_int("bytes_written", static_cast<int64_t>(c.bytes_written));
    w.field("bytes_per_s", bytes_per_s, 1);
    w.field("line_use", c.baud_bps > 0 ? bytes_per_s / line_bytes_per_s : kNaN, 4);
    w.field("tx_fill", c.tx_capacity_bytes > 0.0 ? c.tx_level_bytes / c.tx_capacity_bytes : kNaN, 4);
    w.field_int("epochs_written", static_cast<int64_t>(c.epochs_written));
    w.field_int("epochs_dropped", static_cast<int64_t>(c.epochs_dropped));
    w.field_int("messages_dropped", static_cast<int64_t>(c.messages_dropped));
    // One counter per link fault, so a tester sees each act (docs/faults.md §5).
    const LinkFaultStats& l = c.link_faults;
    w.field_int("link_bytes_lost", static_cast<int64_t>(l.bytes_lost));
    w.field_int("link_messages_corrupted", static_cast<int64_t>(l.messages_corrupted));
    w.field_int("link_messages_dropped", static_cast<int64_t>(l.messages_dropped));
    w.field_int("link_epochs_delayed", static_cast<int64_t>(l.epochs_delayed));
    w.field_int("link_epochs_frozen", static_cast<int64_t>(l.epochs_frozen));
    w.field_int("link_epochs_stopped", static_cast<int64_t>(l.epochs_stopped));
    w.field_int("link_replies_stopped", static_cast<int64_t>(l.replies_stopped));
    w.field_int("link_epochs_skipped", static_cast<int64_t>(l.epochs_skipped));
    w.field_int("link_epochs_wrong_fix", static_cast<int64_t>(l.epochs_wrong_fix));
    w.end_object();
  }
  w.end_array();

  w.key("faults");
  w.begin_array();
  for (const FaultStatus& f : faults_) {
    w.begin_object();
    w.field_string("id", f.id);
    w.field_string("type", f.type);
    w.field_string("description", f.description);
    w.field("start_s", f.start_s, 3);
    w.field("end_s", f.end_s, 3);
    w.field_bool("active", f.active);
    w.end_object();
  }
  w.end_array();

  write_history(w, history_max);
  w.end_object();
}

}  // namespace gnssemu::daemon

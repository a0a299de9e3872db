// SPDX-License-Identifier: Apache-2.0
#include "daemon/status/overview.hpp"

#include <algorithm>
#include <charconv>

#include "daemon/status/json_writer.hpp"
#include "daemon/status/status_producer.hpp"

namespace gnssemu::daemon {

namespace {

std::string_view carrier_name(receiver::CarrierSolution c) noexcept {
  switch (c) {
    case receiver::CarrierSolution::kFloat: return "float";
    case receiver::CarrierSolution::kFixed: return "fixed";
    case receiver::CarrierSolution::kNone: break;
  }
  return "none";
}

bool whole_number(std::string_view v, std::size_t& n) noexcept {
  if (v.empty()) return false;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
  return r.ec == std::errc() && r.ptr == v.data() + v.size();
}

void write_row(JsonWriter& w, const OverviewEntry& e) noexcept {
  const OverviewRow r = e.status->overview();
  w.begin_object();
  w.field_string("vehicle", e.vehicle);
  w.field_string("receiver", e.receiver);
  w.field_int("epochs", static_cast<int64_t>(r.epochs));
  w.field_int("fix_type", static_cast<int>(r.fix_type));
  w.field_string("fix_name", receiver::fix_type_name(r.fix_type));
  w.field_string("carrier", carrier_name(r.carrier));
  w.field_bool("diff", r.diff);
  w.field_int("num_used", r.num_used);
  w.field_int("num_tracked", r.num_tracked);
  w.field_int("num_visible", r.num_visible);
  w.field("h_err_m", r.h_err_m, 3);
  w.field("h_acc_m", r.h_acc_m, 3);
  w.field("cep95_m", r.cep95_m, 3);
  w.field_bool("truth_valid", r.truth_valid);
  w.field_string("truth_source", r.truth_source);
  w.field_bool("truth_fresh", r.truth_fresh);
  w.field("truth_age_s", r.truth_age_s, 3);
  std::size_t active = 0;
  for (const FaultStatus& f : r.faults) active += f.active ? 1 : 0;
  w.field_int("faults_active", static_cast<int64_t>(active));
  w.field_int("faults_scheduled", static_cast<int64_t>(r.faults.size()));
  w.key("active_faults");
  w.begin_array();
  std::size_t listed = 0;
  for (const FaultStatus& f : r.faults) {
    if (!f.active || listed == kOverviewMaxFaultIds) continue;
    ++listed;
    w.begin_object();
    w.field_string("id", f.id);
    w.field_string("type", f.type);
    w.end_object();
  }
  w.end_array();
  w.field_int("ports", static_cast<int64_t>(r.ports));
  w.field_int("bytes_written", static_cast<int64_t>(r.bytes_written));
  w.field_int("epochs_dropped", static_cast<int64_t>(r.epochs_dropped));
  w.field_int("messages_dropped", static_cast<int64_t>(r.messages_dropped));
  w.end_object();
}

}  // namespace

std::string parse_overview_query(std::string_view query, OverviewQuery& q) {
  OverviewQuery out;
  bool have_limit = false, have_offset = false;
  std::size_t pos = 0;
  while (pos < query.size()) {
    std::size_t end = query.find('&', pos);
    if (end == std::string_view::npos) end = query.size();
    const std::string_view item = query.substr(pos, end - pos);
    pos = end + 1;
    if (item.empty()) continue;
    const std::size_t eq = item.find('=');
    const std::string_view key = item.substr(0, eq);
    const std::string_view value = eq == std::string_view::npos ? std::string_view() : item.substr(eq + 1);
    if (key == "limit") {
      if (have_limit) return "limit given twice";
      have_limit = true;
      if (!whole_number(value, out.limit) || out.limit < 1 || out.limit > kOverviewMaxRows) {
        return "limit must be a whole number in [1, " + std::to_string(kOverviewMaxRows) + "], not '" +
               std::string(value) + "'";
      }
    } else if (key == "offset") {
      if (have_offset) return "offset given twice";
      have_offset = true;
      if (!whole_number(value, out.offset)) {
        return "offset must be a whole number >= 0, not '" + std::string(value) + "'";
      }
    } else {
      return "unknown query parameter '" + std::string(key.substr(0, 64)) + "' (/api/overview takes limit, offset)";
    }
  }
  q = out;
  return {};
}

void write_overview(std::string& out, std::span<const OverviewEntry> entries, const OverviewQuery& q) noexcept {
  JsonWriter w(out);
  const std::size_t first = std::min(q.offset, entries.size());
  const std::size_t last = first + std::min(q.limit, entries.size() - first);
  w.begin_object();
  w.field_int("version", 1);
  w.field_int("total", static_cast<int64_t>(entries.size()));
  w.field_int("offset", static_cast<int64_t>(q.offset));
  w.field_int("limit", static_cast<int64_t>(q.limit));
  w.key("rows");
  w.begin_array();
  for (std::size_t i = first; i < last; ++i) write_row(w, entries[i]);
  w.end_array();
  w.end_object();
}

}  // namespace gnssemu::daemon

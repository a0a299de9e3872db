// SPDX-License-Identifier: Apache-2.0
#include "daemon/status/overview.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>
#include <utility>
#include <vector>

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

std::size_t active_count(std::span<const FaultStatus> faults) noexcept {
  std::size_t n = 0;
  for (const FaultStatus& f : faults) n += f.active ? 1 : 0;
  return n;
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
  w.field_int("faults_active", static_cast<int64_t>(active_count(r.faults)));
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

struct SortKeyName {
  std::string_view name;
  OverviewSort sort;
};
constexpr SortKeyName kSortKeys[] = {{"name", OverviewSort::kName},   {"fix", OverviewSort::kFix},
                                     {"sats", OverviewSort::kSats},   {"herr", OverviewSort::kHErr},
                                     {"hacc", OverviewSort::kHAcc},   {"truth", OverviewSort::kTruth},
                                     {"faults", OverviewSort::kFaults}, {"bytes", OverviewSort::kBytes},
                                     {"dropped", OverviewSort::kDropped}};

std::string sort_key_list() {
  std::string out;
  for (const SortKeyName& k : kSortKeys) out += (out.empty() ? "" : ", ") + std::string(k.name);
  return out;
}

/// Natural order: digit runs compare as numbers ("v9" < "v10"), the rest
/// byte by byte. <0, 0, >0.
int natural_compare(std::string_view a, std::string_view b) noexcept {
  std::size_t i = 0, j = 0;
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && a[ie] == '0') ++ie;  // leading zeros do not count
      while (je < b.size() && b[je] == '0') ++je;
      std::size_t ae = ie, be = je;
      while (ae < a.size() && digit(a[ae])) ++ae;
      while (be < b.size() && digit(b[be])) ++be;
      if (ae - ie != be - je) return ae - ie < be - je ? -1 : 1;
      if (const int c = a.substr(ie, ae - ie).compare(b.substr(je, be - je)); c != 0) return c;
      i = ae;
      j = be;
      continue;
    }
    if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]) ? -1 : 1;
    ++i;
    ++j;
  }
  if (a.size() - i == b.size() - j) return 0;
  return a.size() - i < b.size() - j ? -1 : 1;
}

int carrier_rank(const OverviewRow& r) noexcept {
  switch (r.carrier) {
    case receiver::CarrierSolution::kFixed: return 3;
    case receiver::CarrierSolution::kFloat: return 2;
    case receiver::CarrierSolution::kNone: break;
  }
  return r.diff ? 1 : 0;
}

/// A row's sort value: (missing, primary, secondary); missing rows go last.
struct SortValue {
  bool missing = false;
  double a = 0.0, b = 0.0;
};

SortValue sort_value(const OverviewRow& r, OverviewSort s) noexcept {
  switch (s) {
    case OverviewSort::kFix: return {false, static_cast<double>(r.fix_type), static_cast<double>(carrier_rank(r))};
    case OverviewSort::kSats: return {false, static_cast<double>(r.num_used), static_cast<double>(r.num_tracked)};
    case OverviewSort::kHErr: return {!std::isfinite(r.h_err_m), r.h_err_m, 0.0};
    case OverviewSort::kHAcc: return {!std::isfinite(r.h_acc_m), r.h_acc_m, 0.0};
    case OverviewSort::kTruth:  // no truth, stopped simulator, fresh; then the oldest packet first
      return {false, r.truth_valid ? (r.truth_fresh ? 2.0 : 1.0) : 0.0,
              std::isfinite(r.truth_age_s) ? -r.truth_age_s : 0.0};
    case OverviewSort::kFaults:
      return {false, static_cast<double>(active_count(r.faults)), static_cast<double>(r.faults.size())};
    case OverviewSort::kBytes: return {false, static_cast<double>(r.bytes_written), 0.0};
    case OverviewSort::kDropped:
      return {false, static_cast<double>(r.epochs_dropped + r.messages_dropped), 0.0};
    case OverviewSort::kConfig:
    case OverviewSort::kName: break;
  }
  return {};
}

}  // namespace

void sort_overview(std::span<OverviewEntry> entries, const OverviewQuery& q) {
  if (q.sort == OverviewSort::kConfig) return;
  const int sign = q.descending ? -1 : 1;
  if (q.sort == OverviewSort::kName) {
    std::stable_sort(entries.begin(), entries.end(), [sign](const OverviewEntry& x, const OverviewEntry& y) {
      int c = natural_compare(x.vehicle, y.vehicle);
      if (c == 0) c = natural_compare(x.receiver, y.receiver);
      return sign * c < 0;
    });
    return;
  }
  // Each row's value once (overview() sums its ports), not once per comparison.
  std::vector<std::pair<SortValue, OverviewEntry>> keyed;
  keyed.reserve(entries.size());
  for (const OverviewEntry& e : entries) keyed.emplace_back(sort_value(e.status->overview(), q.sort), e);
  std::stable_sort(keyed.begin(), keyed.end(), [sign](const auto& x, const auto& y) {
    const SortValue& a = x.first;
    const SortValue& b = y.first;
    if (a.missing != b.missing) return b.missing;
    if (a.missing) return false;
    if (a.a != b.a) return sign * (a.a < b.a ? -1 : 1) < 0;
    if (a.b != b.b) return sign * (a.b < b.b ? -1 : 1) < 0;
    return false;
  });
  for (std::size_t i = 0; i < keyed.size(); ++i) entries[i] = keyed[i].second;
}

std::string parse_overview_query(std::string_view query, OverviewQuery& q) {
  OverviewQuery out;
  bool have_limit = false, have_offset = false, have_sort = false, have_order = false;
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
    } else if (key == "sort") {
      if (have_sort) return "sort given twice";
      have_sort = true;
      const auto* k = std::find_if(std::begin(kSortKeys), std::end(kSortKeys),
                                   [value](const SortKeyName& n) { return n.name == value; });
      if (k == std::end(kSortKeys)) {
        return "sort must be one of " + sort_key_list() + ", not '" + std::string(value.substr(0, 64)) + "'";
      }
      out.sort = k->sort;
    } else if (key == "order") {
      if (have_order) return "order given twice";
      have_order = true;
      if (value != "asc" && value != "desc") return "order must be asc or desc, not '" + std::string(value.substr(0, 64)) + "'";
      out.descending = value == "desc";
    } else {
      return "unknown query parameter '" + std::string(key.substr(0, 64)) +
             "' (/api/overview takes limit, offset, sort, order)";
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

// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/report/plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string_view>
#include <vector>

#include "core/common/error.hpp"
#include "core/common/sat_id.hpp"

namespace gnssemu::cli {

namespace {

std::vector<std::string_view> split(std::string_view line, char sep) {
  std::vector<std::string_view> out;
  std::size_t pos = 0;
  for (;;) {
    const std::size_t end = line.find(sep, pos);
    out.push_back(line.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos));
    if (end == std::string_view::npos) return out;
    pos = end + 1;
  }
}

std::ifstream open_input(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path, 0, "file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, 0, "cannot open");
  return in;
}

/// A CSV file with a header line, read row by row; columns by name.
class CsvReader {
public:
  explicit CsvReader(const std::string& path) : path_(path), in_(open_input(path)) {
    if (!next_line()) throw Error(path_, 1, "empty file: a header line is needed");
    std::size_t i = 0;
    for (std::string_view h : split(line_, ',')) columns_[std::string(trim(h))] = i++;
  }
  bool has(const std::string& name) const { return columns_.count(name) != 0; }
  std::size_t column(const std::string& name) const {
    const auto it = columns_.find(name);
    if (it == columns_.end()) throw Error(path_, 1, "no column '" + name + "' in the header");
    return it->second;
  }
  /// Next data row; false at the end. Blank lines are skipped.
  bool next() {
    do {
      if (!next_line()) return false;
    } while (trim(line_).empty());
    fields_ = split(line_, ',');
    if (fields_.size() != columns_.size()) {
      throw Error(path_, line_no_, fmt::format("{} fields, the header has {}", fields_.size(), columns_.size()));
    }
    return true;
  }
  std::string_view text(std::size_t col) const { return trim(fields_[col]); }
  bool empty(std::size_t col) const { return text(col).empty(); }
  double number(std::size_t col, const std::string& name) const {
    const std::string_view t = text(col);
    double v = 0.0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size() || !std::isfinite(v)) {
      throw Error(path_, line_no_, fmt::format("column '{}': '{}' is not a finite number", name, t));
    }
    return v;
  }
  /// An empty cell is NaN.
  double number_or_nan(std::size_t col, const std::string& name) const {
    return empty(col) ? kNoValue : number(col, name);
  }
  int integer(std::size_t col, const std::string& name, int lo, int hi) const {
    const double v = number(col, name);
    if (v != std::floor(v) || v < lo || v > hi) {
      throw Error(path_, line_no_, fmt::format("column '{}': {} is not an integer in [{}, {}]", name, text(col), lo, hi));
    }
    return static_cast<int>(v);
  }
  int line() const { return line_no_; }
  const std::string& path() const { return path_; }

private:
  static std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
  }
  bool next_line() {
    if (!std::getline(in_, line_)) return false;
    ++line_no_;
    return true;
  }
  std::string path_;
  std::ifstream in_;
  std::string line_;
  int line_no_ = 0;
  std::map<std::string, std::size_t> columns_;
  std::vector<std::string_view> fields_;
};

time::GpsTime row_time(const CsvReader& r, std::size_t week_col, std::size_t tow_col) {
  const int week = r.integer(week_col, "gps_week", 0, 9999);
  const double tow = r.number(tow_col, "tow_s");
  if (tow < 0.0 || tow >= kSecondsPerWeek) {
    throw Error(r.path(), r.line(), fmt::format("column 'tow_s': {} outside [0, 604800)", tow));
  }
  return time::GpsTime(week, tow);
}

/// Key of an epoch in milliseconds since GPS week 0.
int64_t epoch_key(const time::GpsTime& t) {
  return static_cast<int64_t>(t.week()) * 604800000 + static_cast<int64_t>(std::llround(t.tow_s() * 1e3));
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

/// The body of a checksummed NMEA sentence starting at '$' in s, or "".
std::string_view nmea_body(std::string_view s) {
  const std::size_t star = s.find('*');
  if (star == std::string_view::npos || star + 2 >= s.size() + 0 || star + 3 > s.size()) return {};
  uint8_t sum = 0;
  for (std::size_t i = 1; i < star; ++i) sum = static_cast<uint8_t>(sum ^ static_cast<uint8_t>(s[i]));
  const int hi = hex_digit(s[star + 1]), lo = hex_digit(s[star + 2]);
  if (hi < 0 || lo < 0 || sum != hi * 16 + lo) return {};
  return s.substr(1, star - 1);
}

}  // namespace

void read_errors_csv(const std::string& path, ReportData& data) {
  CsvReader r(path);
  const std::size_t week = r.column("gps_week"), tow = r.column("tow_s"), type = r.column("fix_type"),
                    nsat = r.column("nsat"), e = r.column("e_m"), n = r.column("n_m"), u = r.column("u_m");
  const bool acc = r.has("hacc_m") && r.has("vacc_m");
  const std::size_t hacc = acc ? r.column("hacc_m") : 0, vacc = acc ? r.column("vacc_m") : 0;
  const bool vis = r.has("nvisible") && r.has("ntracked");
  const std::size_t nvis = vis ? r.column("nvisible") : 0, ntr = vis ? r.column("ntracked") : 0;
  while (r.next()) {
    ReportEpoch ep;
    ep.t = row_time(r, week, tow);
    if (!data.epochs.empty() && !(data.epochs.back().t < ep.t)) {
      throw Error(path, r.line(), "epochs must be in increasing time");
    }
    ep.fix_type = r.integer(type, "fix_type", 0, 3);
    ep.num_used = r.integer(nsat, "nsat", 0, 64);
    ep.e_m = r.number_or_nan(e, "e_m");
    ep.n_m = r.number_or_nan(n, "n_m");
    ep.u_m = r.number_or_nan(u, "u_m");
    // A fix with no error columns is batch's row for an epoch without truth
    // (the receiver coasting through a truth gap): kept, not in the statistics.
    if (std::isnan(ep.e_m) != std::isnan(ep.n_m) || std::isnan(ep.e_m) != std::isnan(ep.u_m)) {
      throw Error(path, r.line(), "e_m, n_m, u_m must be all given or all empty");
    }
    if (acc) {
      ep.h_acc_m = r.number_or_nan(hacc, "hacc_m");
      ep.v_acc_m = r.number_or_nan(vacc, "vacc_m");
    }
    if (vis) {
      ep.num_visible = r.integer(nvis, "nvisible", 0, 64);
      ep.num_tracked = r.integer(ntr, "ntracked", 0, 64);
    }
    data.epochs.push_back(ep);
  }
  if (data.epochs.empty()) throw Error(path, r.line(), "no epochs");
}

void read_sats_csv(const std::string& path, ReportData& data) {
  CsvReader r(path);
  const std::size_t week = r.column("gps_week"), tow = r.column("tow_s"), prn = r.column("prn"),
                    az = r.column("az_deg"), el = r.column("el_deg"), cn0 = r.column("cn0_dbhz"),
                    tracked = r.column("tracked"), used = r.column("used");
  // sat (RINEX name) names the satellite; files without it are GPS by prn.
  const bool has_sat = r.has("sat");
  const std::size_t sat_col = has_sat ? r.column("sat") : 0;
  const bool know_fixes = !data.epochs.empty();
  const bool derive_counts =
      know_fixes && std::all_of(data.epochs.begin(), data.epochs.end(), [](const ReportEpoch& e) { return e.num_tracked < 0; });
  std::map<int64_t, std::pair<int, int>> counts;  // epoch -> visible (el >= mask or any), tracked
  const std::size_t first = data.sats.size();
  while (r.next()) {
    ReportSat s;
    s.t = row_time(r, week, tow);
    if (data.sats.size() > first && s.t < data.sats.back().t) throw Error(path, r.line(), "rows must be in time order");
    if (has_sat) {
      const std::optional<SatId> sat = parse_sat(r.text(sat_col));
      if (!sat) throw Error(path, r.line(), "column 'sat': '" + std::string(r.text(sat_col)) + "' is not a satellite");
      s.sat = *sat;
    } else {
      s.sat = SatId::gps(r.integer(prn, "prn", 1, system_size(GnssSystem::kGps)));
    }
    s.az_deg = r.number(az, "az_deg");
    s.el_deg = r.number(el, "el_deg");
    if (s.az_deg < 0.0 || s.az_deg >= 360.0 || s.el_deg < -90.0 || s.el_deg > 90.0) {
      throw Error(path, r.line(), fmt::format("azimuth {} / elevation {} out of range", s.az_deg, s.el_deg));
    }
    s.cn0_dbhz = r.number(cn0, "cn0_dbhz");
    const bool is_tracked = r.integer(tracked, "tracked", 0, 1) == 1;
    s.used = r.integer(used, "used", 0, 1) == 1;
    if (s.used && !is_tracked) throw Error(path, r.line(), "used but not tracked");
    const bool below = std::isfinite(data.elevation_mask_deg) && s.el_deg < data.elevation_mask_deg;
    // Tracked but not used is not necessarily excluded by fault detection
    // (NLOS, no ephemeris yet, PDOP or channel limits): the CSV does not say.
    if (s.used) {
      s.state = "used";
    } else if (is_tracked) {
      s.state = "tracked";
    } else {
      s.state = below ? "below_mask" : "searching";
    }
    if (!is_tracked) s.cn0_dbhz = 0.0;
    if (derive_counts) {
      auto& c = counts[epoch_key(s.t)];
      if (!below) ++c.first;
      if (is_tracked) ++c.second;
    }
    data.sats.push_back(s);
  }
  for (ReportEpoch& e : data.epochs) {
    const auto it = counts.find(epoch_key(e.t));
    if (it == counts.end()) continue;
    e.num_visible = it->second.first;
    e.num_tracked = it->second.second;
  }
}

void read_multipath_csv(const std::string& path, ReportData& data) {
  CsvReader r(path);
  const std::size_t az_rays = r.column("azimuth_rays"), rays = r.column("rays"), bounces = r.column("max_bounces"),
                    reuse_m = r.column("reuse_m"), reuse_deg = r.column("reuse_deg"),
                    mean = r.column("us_per_epoch_mean"), p95 = r.column("us_per_epoch_p95"),
                    pos_rms = r.column("pos_err_rms_m"), pos_max = r.column("pos_err_max_m"),
                    nlos_rms = r.column("nlos_delay_err_rms_m"), mis = r.column("misclassified_pct");
  const std::size_t before = data.multipath.size();
  while (r.next()) {
    MultipathRow m;
    const int cone = r.integer(az_rays, "azimuth_rays", 0, 1 << 24);
    const int hemi = r.integer(rays, "rays", 0, 1 << 24);
    const double rm = r.number(reuse_m, "reuse_m"), rd = r.number(reuse_deg, "reuse_deg");
    m.label = fmt::format("{} {}, {} bounces{}", cone > 0 ? "cone" : "hemisphere", cone > 0 ? cone : hemi,
                          r.integer(bounces, "max_bounces", 0, 64),
                          rm > 0.0 ? fmt::format(", reuse {:g} m / {:g}°", rm, rd) : std::string());
    m.us_per_epoch_mean = r.number(mean, "us_per_epoch_mean");
    m.us_per_epoch_p95 = r.number(p95, "us_per_epoch_p95");
    m.pos_err_rms_m = r.number_or_nan(pos_rms, "pos_err_rms_m");
    m.pos_err_max_m = r.number_or_nan(pos_max, "pos_err_max_m");
    m.nlos_delay_err_rms_m = r.number_or_nan(nlos_rms, "nlos_delay_err_rms_m");
    m.misclassified_pct = r.number_or_nan(mis, "misclassified_pct");
    data.multipath.push_back(m);
  }
  if (data.multipath.size() == before) throw Error(path, r.line(), "no rows");
}

Cn0Reference read_cn0_reference(const std::string& path) {
  Cn0Reference ref;
  ref.source = std::filesystem::path(path).filename().string();
  {
    std::ifstream probe = open_input(path);
    std::string first;
    while (std::getline(probe, first) && (first.empty() || first[0] == '#')) {
    }
    if (first.find("el_deg") != std::string::npos && first.find("cn0_dbhz") != std::string::npos) {
      CsvReader r(path);
      const std::size_t el = r.column("el_deg"), cn0 = r.column("cn0_dbhz");
      while (r.next()) {
        const double e = r.number(el, "el_deg"), c = r.number(cn0, "cn0_dbhz");
        if (e < -90.0 || e > 90.0 || c < 0.0 || c > 99.0) {
          throw Error(path, r.line(), fmt::format("elevation {} / C/N0 {} out of range", e, c));
        }
        ref.el_deg.push_back(e);
        ref.cn0_dbhz.push_back(c);
      }
      if (ref.el_deg.empty()) throw Error(path, r.line(), "no rows");
      return ref;
    }
  }
  // NMEA 0183 GSV: $GPGSV,total,num,in_view{,prn,el,az,snr}[,signal]*hh (NMEA 4.11 §GSV).
  std::ifstream in = open_input(path);
  std::string line;
  int sentences = 0;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '#') continue;
    for (std::size_t p = line.find("$GPGSV"); p != std::string::npos; p = line.find("$GPGSV", p + 1)) {
      const std::string_view body = nmea_body(std::string_view(line).substr(p));
      if (body.empty()) continue;
      const std::vector<std::string_view> f = split(body, ',');
      ++sentences;
      for (std::size_t k = 4; k + 3 < f.size(); k += 4) {
        int prn = 0, el = 0, snr = 0;
        const auto num = [](std::string_view t, int& v) {
          const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
          return !t.empty() && r.ec == std::errc() && r.ptr == t.data() + t.size();
        };
        if (!num(f[k], prn) || !num(f[k + 1], el) || !num(f[k + 3], snr)) continue;  // not tracked: empty SNR
        if (prn < 1 || prn > system_size(GnssSystem::kGps) || el < 0 || el > 90 || snr <= 0 || snr > 99) continue;
        ref.el_deg.push_back(el);
        ref.cn0_dbhz.push_back(snr);
      }
    }
  }
  if (ref.el_deg.empty()) {
    throw Error(path, 0,
                sentences ? "no GPS satellite with elevation and C/N0 in its $GPGSV sentences"
                          : "neither a CSV with el_deg,cn0_dbhz nor an NMEA log with $GPGSV sentences");
  }
  return ref;
}

void write_cn0_comparison(const ReportData& data, std::ostream& err) {
  if (!data.reference) return;
  double sum = 0.0;
  int n = 0;
  err << "C/N0 against elevation (median per bin, dB-Hz): this run vs " << data.reference->source << '\n';
  const auto cell = [](double v, const char* f) { return std::isfinite(v) ? fmt::format(fmt::runtime(f), v) : "    -"; };
  for (const Cn0Bin& b : cn0_bins(data)) {
    const double d = b.sim_median_dbhz - b.ref_median_dbhz;
    err << fmt::format("  el {:2.0f}-{:2.0f}: {} ({:5d})  vs {} ({:5d})  diff {}\n", b.el_lo_deg, b.el_hi_deg,
                       cell(b.sim_median_dbhz, "{:5.1f}"), b.sim_n, cell(b.ref_median_dbhz, "{:5.1f}"), b.ref_n,
                       cell(d, "{:+5.1f}"));
    if (std::isfinite(d)) {
      sum += std::fabs(d);
      ++n;
    }
  }
  if (n > 0) err << fmt::format("  mean |diff| over {} bins with both: {:.2f} dB-Hz\n", n, sum / n);
}

void run_plot(const PlotArgs& a, std::ostream& out, std::ostream& err) {
  if (a.errors_path.empty() && a.sats_path.empty() && a.multipath_path.empty()) {
    throw Error("plot: give --errors, --sats and/or --multipath");
  }
  ReportData data;
  data.elevation_mask_deg = a.mask_deg;
  if (!a.errors_path.empty()) {
    read_errors_csv(a.errors_path, data);
    data.inputs.push_back("errors: " + a.errors_path);
  }
  if (!a.sats_path.empty()) {
    read_sats_csv(a.sats_path, data);
    data.inputs.push_back("satellites: " + a.sats_path);
  }
  if (!a.multipath_path.empty()) {
    read_multipath_csv(a.multipath_path, data);
    data.inputs.push_back("bench multipath: " + a.multipath_path);
  }
  if (!a.reference_path.empty()) {
    data.reference = read_cn0_reference(a.reference_path);
    data.inputs.push_back("C/N0 reference: " + a.reference_path);
  }
  data.title = "gnssemu plot";
  const std::string path = write_report(data, a.out_dir);
  write_cn0_comparison(data, err);
  out << path << '\n';
}

}  // namespace gnssemu::cli

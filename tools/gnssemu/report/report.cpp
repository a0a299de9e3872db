// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/report/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/statistics/statistics.hpp"
#include "daemon/status/json_writer.hpp"
#include "daemon/status/sat_state.hpp"
#include "daemon/status/web_assets.hpp"

namespace gnssemu::cli {

namespace {

// Points the browser draws comfortably per chart; longer runs are thinned
// by a whole-epoch stride (statistics always use every epoch).
constexpr std::size_t kMaxSeriesPoints = 20000;
constexpr std::size_t kMaxSkyPoints = 40000;
constexpr std::size_t kCdfPoints = 500;
constexpr double kBinDeg = 5.0;

std::string asset(std::string_view url) {
  const web::Asset* a = web::find_asset(url);
  if (a == nullptr) throw Error(fmt::format("report: asset {} is not embedded", url));
  return std::string(a->text);
}

/// Text inside <script>: "</" would end the element early (HTML §4.12.1.3).
std::string script_safe(std::string s) {
  for (std::size_t p = s.find("</"); p != std::string::npos; p = s.find("</", p + 3)) s.replace(p, 2, "<\\/");
  return s;
}

std::string html_escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string report_json(const ReportData& d) {
  std::string out;
  daemon::JsonWriter w(out);
  const time::GpsTime t0 = !d.epochs.empty() ? d.epochs.front().t : !d.sats.empty() ? d.sats.front().t : time::GpsTime();
  w.begin_object();
  w.field_string("title", d.title);
  w.key("inputs");
  w.begin_array();
  for (const std::string& s : d.inputs) w.string(s);
  w.end_array();
  w.field_int("gps_week", t0.week());
  w.field("tow_s", t0.tow_s(), 3);
  w.field("elevation_mask_deg", d.elevation_mask_deg, 2);
  w.field("acquire_dbhz", d.acquire_dbhz, 1);
  w.field("lose_dbhz", d.lose_dbhz, 1);

  // Statistics over every epoch.
  std::vector<double> h, v;
  int fixes = 0, fixes_3d = 0;
  for (const ReportEpoch& e : d.epochs) {
    // Dead reckoning (fix type 1) is extrapolation, not a GNSS fix: counted
    // neither as a fix nor in the error statistics (as batch's summary).
    const bool gnss_fix = receiver::is_gnss_fix(static_cast<receiver::FixType>(e.fix_type));
    if (gnss_fix) ++fixes;
    if (e.fix_type == 3) ++fixes_3d;
    if (gnss_fix && std::isfinite(e.e_m) && std::isfinite(e.n_m)) {
      h.push_back(std::hypot(e.e_m, e.n_m));
      if (std::isfinite(e.u_m)) v.push_back(std::fabs(e.u_m));
    }
  }
  std::sort(h.begin(), h.end());
  std::sort(v.begin(), v.end());
  w.key("summary");
  w.begin_object();
  w.field_int("epochs", static_cast<int64_t>(d.epochs.size()));
  w.field_int("fixes", fixes);
  w.field_int("fixes_3d", fixes_3d);
  w.field_int("error_samples", static_cast<int64_t>(h.size()));
  w.field("cep50_m", statistics::percentile_nearest_rank(h, 0.5), 3);
  w.field("cep95_m", statistics::percentile_nearest_rank(h, 0.95), 3);
  w.field("h_rms_m", statistics::rms(h), 3);
  w.field("h_max_m", h.empty() ? kNoValue : h.back(), 3);
  w.field("v50_m", statistics::percentile_nearest_rank(v, 0.5), 3);
  w.field("v95_m", statistics::percentile_nearest_rank(v, 0.95), 3);
  w.field("v_rms_m", statistics::rms(v), 3);
  w.end_object();

  w.key("cdf");
  w.begin_object();
  w.key("h_m");
  w.begin_array();
  const std::size_t cdf_n = std::min(h.size(), kCdfPoints);
  for (std::size_t k = 0; k < cdf_n; ++k) w.number(h[(k + 1) * h.size() / cdf_n - 1], 3);
  w.end_array();
  w.key("p");
  w.begin_array();
  for (std::size_t k = 0; k < cdf_n; ++k)
    w.number(static_cast<double>((k + 1) * h.size() / cdf_n) / static_cast<double>(h.size()), 4);
  w.end_array();
  w.end_object();

  const std::size_t stride = std::max<std::size_t>(1, (d.epochs.size() + kMaxSeriesPoints - 1) / kMaxSeriesPoints);
  w.key("epochs");
  w.begin_object();
  w.field_int("stride", static_cast<int64_t>(stride));
  auto column = [&](std::string_view name, auto get, int decimals) {
    w.key(name);
    w.begin_array();
    for (std::size_t i = 0; i < d.epochs.size(); i += stride) w.number(get(d.epochs[i]), decimals);
    w.end_array();
  };
  column("t_s", [&](const ReportEpoch& e) { return e.t - t0; }, 3);
  column("fix_type", [](const ReportEpoch& e) { return static_cast<double>(e.fix_type); }, 0);
  column("e_m", [](const ReportEpoch& e) { return e.e_m; }, 3);
  column("n_m", [](const ReportEpoch& e) { return e.n_m; }, 3);
  column("u_m", [](const ReportEpoch& e) { return e.u_m; }, 3);
  column("h_acc_m", [](const ReportEpoch& e) { return e.fix_type ? e.h_acc_m : kNoValue; }, 3);
  column("v_acc_m", [](const ReportEpoch& e) { return e.fix_type ? e.v_acc_m : kNoValue; }, 3);
  column("used", [](const ReportEpoch& e) { return static_cast<double>(e.num_used); }, 0);
  column("tracked", [](const ReportEpoch& e) { return e.num_tracked < 0 ? kNoValue : e.num_tracked; }, 0);
  column("visible", [](const ReportEpoch& e) { return e.num_visible < 0 ? kNoValue : e.num_visible; }, 0);
  w.end_object();

  // Sky and C/N0: whole epochs thinned alike, so tracks stay continuous.
  const std::size_t sky_stride = std::max<std::size_t>(1, (d.sats.size() + kMaxSkyPoints - 1) / kMaxSkyPoints);
  std::vector<const ReportSat*> sky;
  std::size_t epoch_index = 0;
  for (std::size_t i = 0; i < d.sats.size(); ++i) {
    if (i > 0 && d.sats[i].t - d.sats[i - 1].t != 0.0) ++epoch_index;
    if (epoch_index % sky_stride == 0) sky.push_back(&d.sats[i]);
  }
  w.key("sky");
  w.begin_object();
  w.field_int("stride", static_cast<int64_t>(sky_stride));
  auto sky_column = [&](std::string_view name, auto get, int decimals) {
    w.key(name);
    w.begin_array();
    for (const ReportSat* s : sky) w.number(get(*s), decimals);
    w.end_array();
  };
  sky_column("t_s", [&](const ReportSat& s) { return s.t - t0; }, 1);
  sky_column("prn", [](const ReportSat& s) { return static_cast<double>(s.sat.prn()); }, 0);
  sky_column("az", [](const ReportSat& s) { return s.az_deg; }, 1);
  sky_column("el", [](const ReportSat& s) { return s.el_deg; }, 1);
  sky_column("cn0", [](const ReportSat& s) { return s.cn0_dbhz; }, 1);
  sky_column("used", [](const ReportSat& s) { return s.used ? 1.0 : 0.0; }, 0);
  w.key("state");
  w.begin_array();
  for (const ReportSat* s : sky) w.string(s->state);
  w.end_array();
  w.key("sat");
  w.begin_array();
  for (const ReportSat* s : sky) w.string(std::string_view(sat_name(s->sat).data(), 3));
  w.end_array();
  w.end_object();

  // Every satellite-epoch by state (the sky plot is thinned and overlaps).
  w.key("state_counts");
  w.begin_object();
  for (const char* st : {"used", "nlos", "excluded", "tracked", "searching", "blocked", "below_mask"}) {
    int64_t n = 0;
    for (const ReportSat& x : d.sats) n += x.state == st;
    w.field_int(st, n);
  }
  w.end_object();

  w.key("cn0_bins");
  w.begin_array();
  for (const Cn0Bin& b : cn0_bins(d)) {
    w.begin_object();
    w.field("el_lo_deg", b.el_lo_deg, 0);
    w.field("el_hi_deg", b.el_hi_deg, 0);
    w.field("sim_median_dbhz", b.sim_median_dbhz, 2);
    w.field_int("sim_n", b.sim_n);
    w.field("ref_median_dbhz", b.ref_median_dbhz, 2);
    w.field_int("ref_n", b.ref_n);
    w.end_object();
  }
  w.end_array();
  if (d.reference) {
    w.key("reference");
    w.begin_object();
    w.field_string("source", d.reference->source);
    w.field_int("samples", static_cast<int64_t>(d.reference->el_deg.size()));
    w.key("el");
    w.begin_array();
    for (double x : d.reference->el_deg) w.number(x, 1);
    w.end_array();
    w.key("cn0");
    w.begin_array();
    for (double x : d.reference->cn0_dbhz) w.number(x, 1);
    w.end_array();
    w.end_object();
  }

  w.key("multipath");
  w.begin_array();
  for (const MultipathRow& m : d.multipath) {
    w.begin_object();
    w.field_string("label", m.label);
    w.field("us_mean", m.us_per_epoch_mean, 1);
    w.field("us_p95", m.us_per_epoch_p95, 1);
    w.field("pos_err_rms_m", m.pos_err_rms_m, 3);
    w.field("pos_err_max_m", m.pos_err_max_m, 3);
    w.field("nlos_delay_err_rms_m", m.nlos_delay_err_rms_m, 3);
    w.field("misclassified_pct", m.misclassified_pct, 3);
    w.end_object();
  }
  w.end_array();
  w.end_object();
  return out;
}

}  // namespace

void ReportCollector::on_epoch(const time::GpsTime& t, const receiver::Fix& fix, const world::Truth& truth) {
  ReportEpoch e;
  e.t = t;
  e.fix_type = static_cast<int>(fix.type);
  e.num_used = fix.num_used;
  e.num_visible = fix.num_visible;
  e.num_tracked = fix.num_tracked;
  if (fix.type != receiver::FixType::kNone) {
    e.h_acc_m = fix.h_acc_m;
    e.v_acc_m = fix.v_acc_m;
    if (truth.valid) {
      const Lla at = geo::lla_from_ecef(truth.pos_m);
      const Enu d = geo::ecef_to_enu_vector(fix.pos_m - truth.pos_m, at.lat_rad, at.lon_rad);
      e.e_m = d.x;
      e.n_m = d.y;
      e.u_m = d.z;
    }
  }
  data_.epochs.push_back(e);
  for (int i = 0; i < fix.num_sats; ++i) {
    const receiver::SatInfo& s = fix.sats[i];
    ReportSat r;
    r.t = t;
    r.sat = s.sat;
    r.az_deg = s.az_rad * kRadToDeg;
    r.el_deg = s.el_rad * kRadToDeg;
    r.cn0_dbhz = s.tracked ? s.cn0_dbhz : 0.0;
    r.state = daemon::sat_state_name(daemon::sat_state(s));
    r.used = s.used;
    data_.sats.push_back(r);
  }
}

std::vector<Cn0Bin> cn0_bins(const ReportData& d) {
  const int n = static_cast<int>(90.0 / kBinDeg);
  std::vector<std::vector<double>> sim(static_cast<std::size_t>(n)), ref(static_cast<std::size_t>(n));
  auto bin = [&](double el) { return std::clamp(static_cast<int>(std::floor(el / kBinDeg)), 0, n - 1); };
  for (const ReportSat& s : d.sats)
    if (s.cn0_dbhz > 0.0 && s.el_deg >= 0.0) sim[static_cast<std::size_t>(bin(s.el_deg))].push_back(s.cn0_dbhz);
  if (d.reference) {
    for (std::size_t i = 0; i < d.reference->el_deg.size(); ++i) {
      const double el = d.reference->el_deg[i];
      if (el >= 0.0 && d.reference->cn0_dbhz[i] > 0.0)
        ref[static_cast<std::size_t>(bin(el))].push_back(d.reference->cn0_dbhz[i]);
    }
  }
  std::vector<Cn0Bin> out;
  for (int k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (sim[i].empty() && ref[i].empty()) continue;
    Cn0Bin b;
    b.el_lo_deg = k * kBinDeg;
    b.el_hi_deg = (k + 1) * kBinDeg;
    b.sim_n = static_cast<int>(sim[i].size());
    b.ref_n = static_cast<int>(ref[i].size());
    b.sim_median_dbhz = statistics::quantile_linear(sim[i], 0.5);
    b.ref_median_dbhz = statistics::quantile_linear(ref[i], 0.5);
    out.push_back(b);
  }
  return out;
}

std::string write_html_page(const std::string& dir, const std::string& title, const std::string& json,
                            std::string_view script_url) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir, 0, "cannot create the report folder: " + ec.message());
  const std::string path = (std::filesystem::path(dir) / "report.html").string();
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw Error(path, 0, "cannot open for writing");
  f << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << html_escape(title)
    << "</title>\n<style>\n"
    << asset("/report.css") << "</style>\n<script>\n"
    << script_safe(asset("/chart.min.js")) << "\n</script>\n<script>\n"
    << script_safe(asset("/gnss_charts.js")) << "\n</script>\n</head>\n<body>\n"
    << "<script type=\"application/json\" id=\"report-data\">" << script_safe(json) << "</script>\n"
    << "<div id=\"report\"></div>\n<script>\n"
    << script_safe(asset(script_url)) << "\n</script>\n</body>\n</html>\n";
  f.close();
  if (!f) throw Error(path, 0, "write failed");
  return path;
}

std::string write_report(const ReportData& data, const std::string& dir) {
  if (data.epochs.empty() && data.sats.empty() && data.multipath.empty()) {
    throw Error("report: nothing to plot (no epochs, satellites or multipath rows)");
  }
  return write_html_page(dir, data.title, report_json(data), "/report.js");
}

}  // namespace gnssemu::cli

// SPDX-License-Identifier: Apache-2.0
#pragma once
// The HTML report of a run (docs/cli.md §Report): `gnssemu batch --report DIR`
// and `gnssemu plot`. One self-contained file, DIR/report.html: Chart.js,
// the chart code and the data are inlined, so it opens anywhere offline.
// Plots: sky over the run, C/N0 against elevation (beside a real receiver's
// curve when given), error time series, horizontal-error CDF with CEP50/95,
// satellites over time, and for `bench multipath` time against error.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/receiver/fix.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/truth.hpp"
#include "tools/gnssemu/batch/batch.hpp"

namespace gnssemu::cli {

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

/// One epoch of the run.
struct ReportEpoch {
  time::GpsTime t;
  int fix_type = 0;                 ///< 0 none, 2, 3
  int num_used = 0;
  int num_visible = -1;             ///< above the mask; -1: unknown
  int num_tracked = -1;             ///< -1: unknown
  double e_m = kNoValue, n_m = kNoValue, u_m = kNoValue;  ///< fix - truth, local ENU, m; NaN: no fix
  double h_acc_m = kNoValue, v_acc_m = kNoValue;          ///< reported accuracy, m; NaN: unknown
};

/// One satellite at one epoch.
struct ReportSat {
  time::GpsTime t;
  SatId sat;
  double az_deg = 0.0, el_deg = 0.0;
  double cn0_dbhz = 0.0;            ///< 0: not tracked
  std::string_view state;           ///< sat_state_name (static text)
  bool used = false;
};

/// A real receiver's C/N0 against elevation (GSV of an NMEA log, or a CSV).
struct Cn0Reference {
  std::string source;               ///< file name, for the legend
  std::vector<double> el_deg, cn0_dbhz;
};

/// One setting of `gnssemu bench multipath` (its CSV row).
struct MultipathRow {
  std::string label;                ///< e.g. "cone 128, 16 bounces, reuse 0 m / 0 deg"
  double us_per_epoch_mean = 0.0, us_per_epoch_p95 = 0.0;
  double pos_err_rms_m = kNoValue, pos_err_max_m = kNoValue;
  double nlos_delay_err_rms_m = kNoValue;
  double misclassified_pct = kNoValue;
};

struct ReportData {
  std::string title;                ///< heading, e.g. "gnssemu batch: static.csv"
  std::vector<std::string> inputs;  ///< lines naming what the report was made from
  double elevation_mask_deg = kNoValue;
  double acquire_dbhz = kNoValue, lose_dbhz = kNoValue;
  std::vector<ReportEpoch> epochs;
  std::vector<ReportSat> sats;
  std::optional<Cn0Reference> reference;
  std::vector<MultipathRow> multipath;
};

/// Fills a ReportData from a run, epoch by epoch (batch).
class ReportCollector final : public BatchObserver {
public:
  explicit ReportCollector(ReportData& data) : data_(data) {}
  void on_epoch(const time::GpsTime& t, const receiver::Fix& fix, const world::Truth& truth) override;

private:
  ReportData& data_;
};

/// C/N0 against elevation in 5-degree bins: medians of the run and of the reference.
struct Cn0Bin {
  double el_lo_deg = 0.0, el_hi_deg = 0.0;
  double sim_median_dbhz = kNoValue, ref_median_dbhz = kNoValue;
  int sim_n = 0, ref_n = 0;
};
std::vector<Cn0Bin> cn0_bins(const ReportData& data);

/// Write dir/report.html (dir is created). Returns the file's path. Throws
/// gnssemu::Error when nothing can be plotted or the file cannot be written.
std::string write_report(const ReportData& data, const std::string& dir);

/// Write dir/report.html (dir is created): the report style, Chart.js and the
/// shared charts, json in #report-data, then the page script (an embedded
/// asset's url, e.g. "/report.js"). Returns the file's path. Throws gnssemu::Error.
std::string write_html_page(const std::string& dir, const std::string& title, const std::string& json,
                            std::string_view script_url);

}  // namespace gnssemu::cli

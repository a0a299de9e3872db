// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu plot`: the HTML report (report.hpp) from files a run left behind:
// batch's --errors and --sats CSVs, a `bench multipath` CSV, and a real
// receiver's C/N0 (an NMEA log's GSV, or a CSV with el_deg,cn0_dbhz).
// Columns are read by name; every bad row is an error naming file:line.
#include <ostream>
#include <string>

#include "tools/gnssemu/report/report.hpp"

namespace gnssemu::cli {

struct PlotArgs {
  std::string errors_path;     ///< batch --errors CSV
  std::string sats_path;       ///< batch --sats CSV
  std::string multipath_path;  ///< bench multipath CSV
  std::string reference_path;  ///< real receiver C/N0: NMEA log or el_deg,cn0_dbhz CSV
  std::string out_dir;         ///< report folder
  double mask_deg = kNoValue;  ///< elevation mask to draw, deg (unknown from the CSVs)
};

/// Append the epochs of an errors CSV (`gps_week,tow_s,fix_type,nsat,e_m,n_m,u_m`,
/// optional `hacc_m,vacc_m,nvisible,ntracked`).
void read_errors_csv(const std::string& path, ReportData& data);
/// Append the satellites of a sats CSV. A tracked satellite that is not used
/// in an epoch with a fix (from the errors CSV, read first) was excluded by
/// fault detection; without the errors CSV it is shown as tracked.
void read_sats_csv(const std::string& path, ReportData& data);
/// Append the rows of a `bench multipath` CSV.
void read_multipath_csv(const std::string& path, ReportData& data);
/// A real receiver's C/N0 against elevation: GPS satellites of the $GPGSV
/// sentences (checksum verified; '#' lines and binary data skipped) of an
/// NMEA log, or a CSV with el_deg and cn0_dbhz columns.
Cn0Reference read_cn0_reference(const std::string& path);

/// Reads what args names and writes args.out_dir/report.html; prints the
/// path and the C/N0 comparison to err. Throws gnssemu::Error.
void run_plot(const PlotArgs& args, std::ostream& out, std::ostream& err);

/// One line per 5-degree elevation bin: medians of the run and the
/// reference, their difference, and the mean absolute difference.
void write_cn0_comparison(const ReportData& data, std::ostream& err);

}  // namespace gnssemu::cli

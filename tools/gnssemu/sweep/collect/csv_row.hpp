// SPDX-License-Identifier: Apache-2.0
#pragma once
// CSV rows of the sweep's tables (tasks.csv, summary.csv, results.csv):
// RFC 4180 quoting, so axis values with commas (generator tables) survive.
#include <string>
#include <string_view>
#include <vector>

namespace gnssemu::cli::sweep {

/// cells joined by commas, each quoted when it holds , " or a line break; ends with '\n'.
std::string csv_row(const std::vector<std::string>& cells);

/// One line (without its '\n') split into cells, quotes removed. Throws
/// gnssemu::Error(name, line, ...) on an unterminated quote.
std::vector<std::string> split_csv_row(std::string_view line, const std::string& name, int line_no);

/// A whole file: header and rows, empty lines skipped.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  /// Index of a column, or -1.
  int column(std::string_view name) const;
};
/// Throws gnssemu::Error when a row's cell count differs from the header's.
CsvTable parse_csv(std::string_view text, const std::string& name);

}  // namespace gnssemu::cli::sweep

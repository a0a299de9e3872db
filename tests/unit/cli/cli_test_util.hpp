// SPDX-License-Identifier: Apache-2.0
#pragma once
// Helpers for the gnssemu CLI tests: run the CLI in-process and read its CSV
// by column name, as consumers do.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tools/gnssemu/cli.hpp"

namespace gnssemu::cli::test {

inline std::string nav_path(const std::string& name) { return std::string(GNSSEMU_TEST_DATA) + "/nav/" + name; }

/// A loadable config: origin at Paris, the given nav file, then extra TOML.
inline std::string config_text(const std::string& nav_file, const std::string& extra = "") {
  return "[origin]\nlat_deg = 48.8738\nlon_deg = 2.2950\nheight_m = 100.0\n\n[nav]\nfile = \"" + nav_file +
         "\"\n\n" + extra;
}

struct CliResult {
  int status = -1;
  std::string out, err;
};

inline CliResult run(std::vector<std::string> args) {
  args.insert(args.begin(), "gnssemu");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  CliResult r;
  r.status = run_cli(static_cast<int>(argv.size()), argv.data(), out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

/// A CSV read by column name. Cells stay strings; num() converts.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  int col(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return static_cast<int>(i);
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  const std::string& cell(std::size_t row, const std::string& name) const { return rows.at(row).at(col(name)); }
  double num(std::size_t row, const std::string& name) const { return std::stod(cell(row, name)); }
};

inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream ss(line);
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

inline Csv parse_csv(const std::string& text) {
  Csv csv;
  std::istringstream in(text);
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (first) {
      csv.header = split_csv_line(line);
      first = false;
    } else {
      csv.rows.push_back(split_csv_line(line));
      EXPECT_EQ(csv.rows.back().size(), csv.header.size()) << line;
    }
  }
  return csv;
}

/// A static receiver in Paris from 2022-01-01 (week 2190, tow 522000 s) for
/// duration_s: two truth rows.
inline std::string static_truth(double duration_s) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,522000.0,48.8738,2.2950,100.0\n"
                "2190,%.1f,48.8738,2.2950,100.0\n",
                522000.0 + duration_s);
  return buf;
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A scratch folder for one test, removed at the end.
class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("gnssemu_cli_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }

private:
  std::filesystem::path path_;
};

}  // namespace gnssemu::cli::test

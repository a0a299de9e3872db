// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu base`: the [base] reference station run offline over a time span,
// its RTCM 3 stream written to a file (what gnssemud's base sends live), with
// the raw observations and the ephemerides it encoded as CSV for checks
// against a decoder (tests/integration/wire/rtcm_rtklib_integration.py).
#include <CLI/CLI.hpp>
#include <ostream>
#include <string>

namespace gnssemu::cli {

class BaseCommand {
public:
  /// Adds "base" to app.
  explicit BaseCommand(CLI::App& app);
  BaseCommand(const BaseCommand&) = delete;
  BaseCommand& operator=(const BaseCommand&) = delete;
  CLI::App* app() const noexcept { return cmd_; }
  bool parsed() const { return cmd_->parsed(); }
  /// Throws gnssemu::Error on bad input; returns the exit status.
  int run(std::ostream& out, std::ostream& err);

private:
  CLI::App* cmd_ = nullptr;
  std::string config_, out_path_, raw_csv_, eph_csv_, messages_;
  double lat_deg_ = 0.0, lon_deg_ = 0.0, height_m_ = 0.0, tow_s_ = 0.0, duration_s_ = 60.0;
  int week_ = -1, station_id_ = 0;
  long long seed_ = -1;
  bool open_sky_ = false;
};

}  // namespace gnssemu::cli

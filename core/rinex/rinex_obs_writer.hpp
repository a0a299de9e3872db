// SPDX-License-Identifier: Apache-2.0
#pragma once
// RINEX 3.04 observation file writer for the receiver's raw measurements
// (RawEpoch): a complete header (marker, receiver and antenna, approximate
// position, per system C/L/D/S of each tracked signal, time of first
// observation, phase shifts, GLONASS slots and code-phase biases) and one
// epoch record per RawEpoch. Layouts: RINEX 3.04 Tables A1-A3; the header
// order and the LLI reading follow RTKLIB's outrnxobsh/outrnxobsb
// (shared/reference/rtk-raw.md §1.2).
#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "core/common/gnss_signals.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/receiver/raw_measurements.hpp"

namespace gnssemu::rinex {

/// What the header says besides the observations.
struct ObsHeaderInfo {
  std::string marker_name = "GNSSEMU";
  std::string observer = "gnssemu";
  std::string agency = "";
  std::string receiver_number = "1";
  std::string receiver_type = "GNSSEMU";  ///< e.g. "U-BLOX NEO-M8T"
  std::string receiver_version = "";
  std::string antenna_number = "1";
  std::string antenna_type = "GNSSEMU PATCH   NONE";  ///< IGS name (A16) + radome (A4)
  Ecef approx_pos_m;           ///< APPROX POSITION XYZ, ECEF m
  Enu antenna_delta_hen_m;     ///< ANTENNA: DELTA H/E/N (x = H, y = E, z = N), m
  double interval_s = 0.0;     ///< INTERVAL, s; 0: not written
  SystemSet systems;           ///< systems with SYS / # / OBS TYPES lines
  int num_bands = 1;           ///< 1: L1 band; 2: and each system's second signal (gnss_signals.hpp)
  /// GLONASS slot (RINEX number) and FDMA channel k of every slot the nav data hold.
  std::vector<std::pair<int, int>> glonass_channels;
  int leap_seconds = -1;       ///< LEAP SECONDS; < 0: not written
};

/// Loss-of-lock indicator of a measurement (RINEX 3.04 §5.7; RTKLIB's
/// reading of RAWX, rtk-raw.md §1.1): bit 0 when the lock is new or shorter
/// than at the previous epoch, bit 1 while the half cycle is unresolved.
int loss_of_lock_indicator(const receiver::RawMeasurement& m, double prev_lock_time_s) noexcept;

/// Signal strength indicator 1-9 from C/N0 (RINEX 3.04 §5.7: dB-Hz / 6, clamped).
int signal_strength_indicator(double cn0_dbhz) noexcept;

class ObsWriter {
public:
  /// out must outlive the writer. The header is written at the first epoch
  /// (its TIME OF FIRST OBS) or by finish() when there is none.
  ObsWriter(std::ostream& out, ObsHeaderInfo info);

  /// One epoch record of every measurement of a system in the header; an
  /// epoch without valid time or without measurements is skipped. No allocation.
  void write(const receiver::RawEpoch& epoch) noexcept;
  /// Writes the header if no epoch was written.
  void finish() noexcept;
  int epochs_written() const noexcept { return epochs_; }
  /// The header to be written: changes count until the first epoch.
  ObsHeaderInfo& header() noexcept { return info_; }

private:
  void write_header(const time::GpsTime& first) noexcept;

  std::ostream& out_;
  ObsHeaderInfo info_;
  bool header_done_ = false;
  int epochs_ = 0;
  /// Lock time of each satellite and band at the previous epoch, s (-1: not tracked).
  std::array<std::array<double, kNumBands>, kNumSats> prev_lock_s_{};
};

}  // namespace gnssemu::rinex
